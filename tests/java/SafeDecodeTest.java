// Unit tests of meshtopo.SafeDecode (msgs/java/meshtopo/SafeDecode.java), no daemon needed
// (ctest java.safe_decode): every sample message msgs_write_samples encodes in C decodes; every
// truncation of one is refused, a byte after it too, and 1,000 random corruptions of each are
// refused with SafeDecode.Refused or decode, never anything else (no OutOfMemoryError, no
// NegativeArraySizeException, no crash); forged hostile replies (a count of 2^31 - 1 with 10
// bytes after it, a part claiming 60000 bytes with 5, a string longer than the buffer, offsets
// that do not describe the arrays, ...) are refused with the field named, where lcm-gen's own
// decoder fails with an Error or a RuntimeException.
// usage: java -cp lcm.jar:meshtopo-msgs.jar:CLASSES SafeDecodeTest SAMPLES_DIR
import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.nio.file.DirectoryStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.Random;
import meshtopo.*;

public class SafeDecodeTest {
    static int passed = 0, failed = 0;

    /** Encoded bytes written field by field, as LCM does (big-endian). */
    static final class Bytes {
        final ByteArrayOutputStream buf = new ByteArrayOutputStream();
        final DataOutputStream out = new DataOutputStream(buf);
        Bytes i64(long v) throws IOException {
            out.writeLong(v);
            return this;
        }
        Bytes i32(int v) throws IOException {
            out.writeInt(v);
            return this;
        }
        Bytes i8(int v) throws IOException {
            out.writeByte(v);
            return this;
        }
        Bytes str(String s) throws IOException { // length counting the NUL, bytes, NUL
            out.writeInt(s.length() + 1);
            out.writeBytes(s);
            out.writeByte(0);
            return this;
        }
        Bytes raw(int n) throws IOException {
            out.write(new byte[n]);
            return this;
        }
        byte[] get() { return buf.toByteArray(); }
    }

    /** The decoder of each type the client receives. */
    static Object decode(String type, byte[] b) throws IOException {
        switch (type) {
            case "ack_t":
                return SafeDecode.ack(b);
            case "reply_t":
                return SafeDecode.reply(b);
            case "reply_part_t":
                return SafeDecode.replyPart(b);
            case "mesh_transfer_t":
                return SafeDecode.meshTransfer(b);
            case "status_t":
                return SafeDecode.status(b);
            case "topology_t":
                return SafeDecode.topology(b);
            default:
                throw new IllegalArgumentException(type);
        }
    }

    static void check(boolean ok, String what) {
        if (ok) {
            passed++;
        } else {
            failed++;
            System.out.println("FAIL: " + what);
        }
    }

    /** decode(type, b) must throw Refused whose message contains every one of `words`. */
    static void refused(String name, String type, byte[] b, String... words) {
        try {
            decode(type, b);
            check(false, name + ": accepted");
        } catch (SafeDecode.Refused e) {
            boolean all = true;
            for (String w : words) all &= e.getMessage().contains(w);
            check(all,
                    name + ": refused as \"" + e.getMessage() + "\", expected the words "
                            + String.join(" | ", words));
            if (all) System.out.println("ok " + name + ": " + e.getMessage());
        } catch (Throwable e) { // OutOfMemoryError included: the test is what catches it
            check(false, name + ": threw " + e);
        }
    }

    /** decode(type, b) may accept or refuse, but must not throw anything else. */
    static boolean safe(String name, String type, byte[] b) {
        try {
            decode(type, b);
            return true;
        } catch (SafeDecode.Refused e) {
            return true;
        } catch (Throwable e) {
            check(false, name + ": threw " + e);
            return false;
        }
    }

    static void samples(Path dir) throws IOException {
        String[] received = {
                "ack_t", "reply_t", "reply_part_t", "mesh_transfer_t", "status_t", "topology_t"};
        Random random = new Random(32);
        int files = 0;
        try (DirectoryStream<Path> found = Files.newDirectoryStream(dir, "*.lcmbin")) {
            for (Path path : found) {
                String name = path.getFileName().toString(); // NAME.TYPE.lcmbin
                String type = name.split("\\.")[1];
                byte[] b = Files.readAllBytes(path);
                if (!java.util.Arrays.asList(received).contains(type)) {
                    refused(name + " as reply_t", "reply_t", b, "wrong fingerprint");
                    continue;
                }
                files++;
                // The toy part (total_size 20) keeps the layout but not the protocol's sizes.
                boolean toy = name.startsWith("reply_part.");
                try {
                    SafeDecode.check(type, b);
                    decode(type, b);
                    check(!toy, name + " decodes");
                } catch (SafeDecode.Refused e) {
                    check(toy && e.getMessage().startsWith("reply_part_t.total_size"),
                            name + ": " + e.getMessage());
                }
                boolean ok = true;
                for (int n = 0; n < b.length && ok; n++)
                    ok = safe(name + " cut to " + n, type, java.util.Arrays.copyOf(b, n));
                for (int n = 0; n < b.length && ok; n++) { // every cut is refused, not accepted
                    try {
                        SafeDecode.check(type, java.util.Arrays.copyOf(b, n));
                        ok = false;
                        check(false, name + " cut to " + n + " bytes passes the check");
                    } catch (SafeDecode.Refused e) {
                        // expected
                    }
                }
                if (ok)
                    refused(name + " + 1 byte", type, java.util.Arrays.copyOf(b, b.length + 1),
                            "1 bytes after the end");
                for (int k = 0; k < 1000 && ok;
                        k++) { // random bytes overwritten, lengths above all
                    byte[] c = b.clone();
                    for (int flips = 1 + random.nextInt(4); flips > 0; flips--)
                        c[8 + random.nextInt(c.length - 8)] = (byte) random.nextInt(256);
                    ok = safe(name + " corrupted (" + k + ")", type, c);
                }
                check(ok, name + ": every cut and corruption refused or decoded, nothing thrown");
            }
        }
        check(files >= 12, "samples of the received types found in " + dir + ": " + files);
    }

    static void forged() throws IOException {
        // reply_t: header, then num_items = 2^31 - 1 and 10 bytes.
        Bytes head = new Bytes()
                             .i64(reply_t.LCM_FINGERPRINT)
                             .i64(1)
                             .i64(7)
                             .i32(0)
                             .str("")
                             .str("m")
                             .i32(1)
                             .i32(1);
        byte[] b = concat(head.get(), new Bytes().i32(Integer.MAX_VALUE).raw(10).get());
        refused("reply_t count 2^31-1", "reply_t", b, "reply_t.item_status", "2147483647",
                "10 left");
        try { // what SafeDecode is for: the generated decoder allocates first, then fails
            new reply_t(b);
            check(false, "lcm-gen's decoder accepted the forged reply_t");
        } catch (Throwable e) {
            System.out.println("lcm-gen's own decoder on it: " + e);
        }
        b = concat(head.get(), new Bytes().i32(Integer.MIN_VALUE).raw(10).get());
        refused("reply_t count -2^31", "reply_t", b, "reply_t.item_status",
                "negative length -2147483648");
        // reply_part_t whose length says 60000 with 5 bytes of data.
        b = new Bytes()
                    .i64(reply_part_t.LCM_FINGERPRINT)
                    .i64(1)
                    .i64(7)
                    .i64(100000)
                    .i64(0)
                    .i32(reply_part_t.PART_SIZE)
                    .i64(0)
                    .i32(60000)
                    .raw(5)
                    .get();
        refused("reply_part_t length 60000, 5 bytes", "reply_part_t", b, "reply_part_t.data",
                "60000 values", "5 left");
        // ack_t whose error string says 1000 bytes, 3 there; one without its NUL; one of length 0.
        Bytes ackHead = new Bytes().i64(ack_t.LCM_FINGERPRINT).i64(1).i64(7).i32(0);
        refused("ack_t string past the end", "ack_t",
                concat(ackHead.get(), new Bytes().i32(1000).raw(3).get()), "ack_t.error",
                "1000 bytes, 3 left");
        refused("ack_t string without NUL", "ack_t",
                concat(ackHead.get(),
                        new Bytes().i32(2).i8('a').i8('b').str("").i32(0).i64(0).i32(0).get()),
                "ack_t.error", "does not end with a NUL");
        refused("ack_t string length 0", "ack_t",
                concat(ackHead.get(), new Bytes().i32(0).raw(40).get()), "ack_t.error",
                "at least 1");
        refused("ack_t a billion reports", "ack_t",
                concat(ackHead.get(),
                        new Bytes().str("").str("m").i32(1).i64(0).i32(1000000000).raw(64).get()),
                "ack_t.reports", "1000000000 structs");
        // A topology_t nested in an ack, cut inside its strings.
        refused("ack_t report cut short", "ack_t",
                concat(ackHead.get(),
                        new Bytes()
                                .str("")
                                .str("m")
                                .i32(1)
                                .i64(0)
                                .i32(1)
                                .i64(0)
                                .i32(50)
                                .raw(8)
                                .get()),
                "ack_t.reports[0].mesh_id", "50 bytes");
        // Well-formed bytes that break the rules: offsets, parts, missing ranges, listed counts.
        reply_t r = new reply_t();
        r.error = r.mesh_id = "";
        r.num_items = 1;
        r.item_status = new byte[1];
        r.num_item_offsets = 2;
        r.item_offsets = new int[] {0, 5}; // 5 groups, there is 1
        r.num_groups = 1;
        r.group_boundary = new boolean[1];
        r.num_value_offsets = 2;
        r.value_offsets = new int[] {0, 1};
        r.value2_offsets = new int[] {0, 0};
        r.num_values = 1;
        r.values = new int[1];
        r.values2 = new int[0];
        r.reals = new double[0];
        r.reports = new topology_t[0];
        r.list_mesh_ids = r.list_sources = new String[0];
        r.list_versions = r.list_num_verts = r.list_num_faces = new int[0];
        r.list_utimes = r.list_num_defects = r.list_content_hashes = new long[0];
        refused("reply_t offsets past the groups", "reply_t", encode(r),
                "reply_t.item_offsets[1] = 5", "num_groups = 1");
        r.item_offsets = new int[] {0, 1};
        check(safe("reply_t fixed", "reply_t", encode(r)) && decodes("reply_t", encode(r)),
                "the fixed reply_t decodes");
        r.num_item_offsets = 1;
        r.item_offsets = new int[] {0};
        refused("reply_t offsets count", "reply_t", encode(r),
                "reply_t.item_offsets: 1 entries, expected 2");

        reply_part_t p = new reply_part_t();
        p.total_size = 100000;
        p.part_size = reply_part_t.PART_SIZE;
        p.offset = 1000;
        p.length = 3;
        p.data = new byte[3];
        refused("reply_part_t offset off the grid", "reply_part_t", encode(p),
                "reply_part_t.offset: 1000");
        p.offset = reply_part_t.PART_SIZE;
        refused("reply_part_t short length", "reply_part_t", encode(p), "reply_part_t.length: 3",
                "expected " + (100000 - reply_part_t.PART_SIZE));
        p.part_size = 1 << 20;
        refused("reply_part_t huge part_size", "reply_part_t", encode(p),
                "reply_part_t.part_size: 1048576");

        mesh_transfer_t t = new mesh_transfer_t();
        t.error = "";
        t.num_missing = mesh_transfer_t.MISSING_MAX + 1;
        t.missing_offsets = new long[t.num_missing];
        t.missing_lengths = new long[t.num_missing];
        refused("mesh_transfer_t too many ranges", "mesh_transfer_t", encode(t),
                "num_missing: 1025");

        topology_t top = new topology_t();
        top.mesh_id = top.source = "";
        top.boundary_loops = 1;
        top.num_boundary_loop_lengths = 2;
        top.boundary_loop_lengths = new int[] {3, 4};
        top.component_min_face = top.component_faces = top.component_vertices =
                top.component_boundary_loops = top.component_genus =
                        top.component_genus_with_boundary = top.face_size_keys = top.edge_use_keys =
                                top.defect_a = top.defect_b = top.defect_c = new int[0];
        top.component_edges = top.component_euler_characteristic = top.component_boundary_edges =
                top.face_size_counts = top.edge_use_counts = new long[0];
        top.component_closed = top.component_manifold = top.component_orientable = new boolean[0];
        top.defect_kind = new byte[0];
        refused("topology_t lists more loops than it counts", "topology_t", encode(top),
                "num_boundary_loop_lengths = 2");
        top.boundary_loops = 2;
        top.boundary_loop_lengths = new int[] {3, -4};
        refused("topology_t negative loop length", "topology_t", encode(top),
                "boundary_loop_lengths[1] = -4");

        // A status_t handed to the reply decoder; answer() on something that is no answer.
        refused("status as reply", "reply_t",
                new Bytes().i64(status_t.LCM_FINGERPRINT).raw(100).get(),
                "the bytes are a status_t");
        try {
            SafeDecode.answer(encode(p));
            check(false, "answer() takes a reply_part_t");
        } catch (SafeDecode.Refused e) {
            check(e.getMessage().contains("not a reply_t or ack_t"), "answer(): " + e.getMessage());
        }
    }

    static boolean decodes(String type, byte[] b) {
        try {
            decode(type, b);
            return true;
        } catch (IOException e) {
            System.out.println("FAIL: " + e.getMessage());
            return false;
        }
    }

    static byte[] encode(lcm.lcm.LCMEncodable msg) throws IOException {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        msg.encode(new DataOutputStream(out));
        return out.toByteArray();
    }

    static byte[] concat(byte[] a, byte[] b) {
        byte[] c = java.util.Arrays.copyOf(a, a.length + b.length);
        System.arraycopy(b, 0, c, a.length, b.length);
        return c;
    }

    public static void main(String[] args) throws Exception {
        if (args.length != 1) {
            System.err.println("usage: SafeDecodeTest SAMPLES_DIR");
            System.exit(2);
        }
        samples(Paths.get(args[0]));
        forged();
        System.out.println(passed + " passed, " + failed + " failed");
        System.exit(failed == 0 ? 0 : 1);
    }
}
