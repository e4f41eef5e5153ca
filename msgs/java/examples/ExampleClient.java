// ExampleClient: a meshtopo client in Java with nothing but lcm.jar and meshtopo-msgs.jar. It waits
// for meshtopod's heartbeat, submits a 32 x 32 vertex grid (mesh_t on PREFIX SUBMIT), reads the
// ack, asks for one vertex's one-ring, then for the one-rings of 4096 vertex ids, an answer of
// about 250 KB that comes as reply_part_t pieces: it reassembles them, pulls missing parts with
// reply_pull_t a window at a time, checks the answer hash and decodes the whole answer. Every
// received message goes through meshtopo.SafeDecode; every answer is checked against the grid.
// usage: java -cp lcm.jar:meshtopo-msgs.jar:CLASSES ExampleClient [--lcm-url URL] [--lose-part K]
//   --lose-part K  ignore the first copy of part K, as if the network lost it (shows the pull)
import java.util.*;
import java.util.concurrent.*;
import lcm.lcm.*;
import meshtopo.*;

public class ExampleClient {
    static final String PREFIX = "MESHTOPO_";
    static final int N = 32; // grid side
    static final int WINDOW = 3; // parts per pull: 3 x 57 KiB fit Linux's default 208 KiB socket
                                 // receive buffer, which lcm.jar keeps
    static final BlockingQueue<Object[]> inbox = new LinkedBlockingQueue<>(); // {channel, bytes}
    static LCM lcm;
    static String reply; // our reply channel R: answers come on R_ACK, R_REPLY, R_PART
    static long nextId = new Random().nextInt(1 << 30);
    static final long MAX_ANSWER = 256 << 20; // bytes we accept to reassemble
    static int losePart = -1, pulls = 0;
    static boolean lost = false;

    public static void main(String[] args) throws Exception {
        String url = null;
        for (int i = 0; i + 1 < args.length; i += 2) {
            if (args[i].equals("--lcm-url")) url = args[i + 1];
            if (args[i].equals("--lose-part")) losePart = Integer.parseInt(args[i + 1]);
        }
        lcm = url == null ? new LCM() : new LCM(url);
        reply = PREFIX + "REPLY_java_" + ProcessHandle.current().pid() + "_"
                + Long.toHexString(nextId);
        LCMSubscriber keep = (l, channel, ins) -> { // on LCM's thread: keep a copy of the bytes
            byte[] b = new byte[ins.available()];
            System.arraycopy(ins.getBuffer(), ins.getBufferOffset(), b, 0, b.length);
            inbox.add(new Object[] {channel, b});
        };
        lcm.subscribe(PREFIX + "STATUS", keep);
        Object[] beat = inbox.poll(10, TimeUnit.SECONDS); // the first heartbeat, before anything
        if (beat == null) throw new Exception("no heartbeat from meshtopod in 10 s");
        System.out.println("daemon: " + SafeDecode.status((byte[]) beat[1]).instance);
        lcm.unsubscribe(PREFIX + "STATUS", keep);
        lcm.subscribe(reply + "_.*", keep);

        // The grid: vertex i * N + j at (j, i, 0), each cell cut into two counter-clockwise
        // triangles along its diagonal; nbrs and faces say what every one-ring must hold.
        mesh_t mesh = new mesh_t();
        mesh.utime = System.currentTimeMillis() * 1000;
        mesh.request_id = nextId++;
        mesh.reply_channel = reply;
        mesh.mesh_id = "java-grid";
        mesh.source = "ExampleClient";
        mesh.num_verts = N * N;
        mesh.num_position_values = 3 * N * N;
        mesh.positions = new double[3 * N * N];
        for (int v = 0; v < N * N; v++) {
            mesh.positions[3 * v] = v % N;
            mesh.positions[3 * v + 1] = v / N;
        }
        mesh.num_faces = 2 * (N - 1) * (N - 1);
        mesh.face_vertex_counts = new int[mesh.num_faces];
        mesh.num_indices = 3 * mesh.num_faces;
        mesh.face_vertex_indices = new int[mesh.num_indices];
        List<Set<Integer>> nbrs = new ArrayList<>(), faces = new ArrayList<>();
        for (int v = 0; v < N * N; v++) {
            nbrs.add(new TreeSet<>());
            faces.add(new TreeSet<>());
        }
        for (int f = 0; f < mesh.num_faces; f++) {
            int corner = f / 2 / (N - 1) * N + f / 2 % (N - 1); // lower left of the cell
            int[] tri = f % 2 == 0 ? new int[] {0, 1, N + 1} : new int[] {0, N + 1, N};
            mesh.face_vertex_counts[f] = 3;
            for (int k = 0; k < 3; k++) {
                int v = corner + tri[k];
                mesh.face_vertex_indices[3 * f + k] = v;
                faces.get(v).add(f);
                for (int o : tri)
                    if (o != tri[k]) nbrs.get(v).add(corner + o);
            }
        }
        ack_t ack = (ack_t) request(PREFIX + "SUBMIT", mesh, mesh.request_id);
        if (ack.status != status_code_t.OK) throw new Exception("submission refused: " + ack.error);
        expect(ack.num_reports == 1, "the ack carries the build's report");
        topology_t t = ack.reports[0];
        expect(t.num_verts == N * N && t.num_faces == mesh.num_faces && t.boundary_loops == 1
                        && t.num_edges == 2 * N * (N - 1) + (N - 1) * (N - 1)
                        && t.euler_characteristic == 1 && t.manifold && t.num_defects == 0,
                "the grid's report");
        System.out.println(
                "ack: version " + ack.version + ", " + t.num_edges + " edges, 1 boundary loop");

        // Vertex 33 at (1, 1): six neighbours, counter-clockwise from (2, 1): 34 66 65 32 0 1.
        reply_t one = query(new int[] {N + 1});
        String ring = Arrays.toString(Arrays.copyOf(one.values, one.num_values));
        expect(one.num_groups == 1 && !one.group_boundary[0] && one.num_values == 6
                        && "34, 66, 65, 32, 0, 1, 34, 66, 65, 32, 0, 1".contains(
                                ring.replaceAll("[\\[\\]]", "")),
                "ring of vertex 33: " + ring);
        System.out.println("ring of vertex 33: " + ring);

        // Every vertex four times over: 4096 one-rings in one answer, too large for one datagram.
        int[] ids = new int[4 * N * N];
        for (int k = 0; k < ids.length; k++) ids[k] = k % (N * N);
        reply_t all = query(ids);
        for (int k = 0; k < ids.length; k++) {
            int g = all.item_offsets[k], v = ids[k], i = v / N, j = v % N;
            Set<Integer> n = new TreeSet<>(), f = new TreeSet<>();
            for (int x = all.value_offsets[g]; x < all.value_offsets[g + 1]; x++)
                n.add(all.values[x]);
            for (int x = all.value2_offsets[g]; x < all.value2_offsets[g + 1]; x++)
                f.add(all.values2[x]);
            boolean border = i == 0 || j == 0 || i == N - 1 || j == N - 1;
            expect(all.item_offsets[k + 1] == g + 1 && all.group_boundary[g] == border
                            && n.equals(nbrs.get(v)) && f.equals(faces.get(v)),
                    "ring of vertex " + v);
        }
        System.out.println("rings of " + ids.length + " ids: as the grid says; pulls: " + pulls);
        expect(!lost || pulls > 0, "the lost part was pulled");
        System.out.println("ExampleClient: OK"); // LCM's reader thread is a daemon: no close needed
    }

    static void expect(boolean ok, String what) throws Exception {
        if (!ok) throw new Exception("wrong answer: " + what);
    }

    static reply_t query(int[] ids) throws Exception {
        query_t q = new query_t();
        q.utime = System.currentTimeMillis() * 1000;
        q.request_id = nextId++;
        q.reply_channel = reply;
        q.mesh_id = "java-grid";
        q.kind = query_t.VERTEX_RING;
        q.num_ids = ids.length;
        q.ids = ids;
        q.instance = "";
        reply_t r = (reply_t) request(PREFIX + "QUERY", q, q.request_id);
        if (r.status != status_code_t.OK || r.num_items != ids.length)
            throw new Exception("query failed: " + r.error);
        return r;
    }

    // Sends a request and returns its answer (ack_t or reply_t), whole or reassembled from parts.
    // The request goes again (same id: the daemon answers it again) after 1 s without an answer
    // or a part; a message SafeDecode refuses is reported and dropped.
    static LCMEncodable request(String channel, LCMEncodable msg, long id) throws Exception {
        byte[] buf = null; // the answer being reassembled
        boolean[] have = null;
        long hash = 0, heard = System.currentTimeMillis(); // last send or part
        int partSize = 0, held = 0, asked = 0, arrived = 0;
        lcm.publish(channel, msg);
        for (int tries = 1;;) {
            Object[] m = inbox.poll(30, TimeUnit.MILLISECONDS);
            if (System.currentTimeMillis() - heard >= 1000) { // silence: start over
                if (tries++ == 5) throw new Exception("no answer to request " + id);
                lcm.publish(channel, msg);
                heard = System.currentTimeMillis();
                buf = null;
                held = 0;
            }
            if (m == null && held == 0) continue;
            String from = m == null ? "" : (String) m[0];
            try {
                if (from.equals(reply + "_ACK") || from.equals(reply + "_REPLY")) {
                    byte[] b = (byte[]) m[1];
                    LCMEncodable a =
                            from.endsWith("_ACK") ? SafeDecode.ack(b) : SafeDecode.reply(b);
                    long of =
                            a instanceof ack_t ? ((ack_t) a).request_id : ((reply_t) a).request_id;
                    if (of == id) return a;
                } else if (from.equals(reply + "_PART")) {
                    reply_part_t p = SafeDecode.replyPart((byte[]) m[1]);
                    if (p.request_id != id) continue;
                    if (p.offset / p.part_size == losePart && !lost) {
                        lost = true;
                        continue;
                    }
                    if (buf == null) { // the first part fixes the answer's size (capped), hash,
                                       // part size
                        if (p.total_size > MAX_ANSWER) throw new Exception("answer over our cap");
                        buf = new byte[(int) p.total_size];
                        hash = p.answer_hash;
                        partSize = p.part_size;
                        have = new boolean[(int) ((p.total_size + partSize - 1) / partSize)];
                        asked = Math.min(have.length, reply_part_t.FIRST_PARTS); // sent unasked
                    }
                    if (p.total_size != buf.length || p.answer_hash != hash
                            || p.part_size != partSize)
                        continue; // another answer
                    int k = (int) (p.offset / partSize);
                    heard = System.currentTimeMillis();
                    if (have[k]) continue;
                    System.arraycopy(p.data, 0, buf, (int) p.offset, p.length);
                    have[k] = true;
                    held++;
                    arrived++;
                    if (held == have.length) {
                        if (answerHash(buf) != hash)
                            throw new Exception("the parts do not hash right");
                        LCMEncodable a =
                                SafeDecode.answer(buf); // reply_t or ack_t, by its fingerprint
                        System.out.println("answer " + id + ": " + buf.length + " bytes in "
                                + have.length + " parts, a " + SafeDecode.typeOf(buf));
                        return a;
                    }
                }
            } catch (SafeDecode.Refused e) {
                System.out.println("refused a message on " + from + ": " + e.getMessage());
                continue;
            }
            if (held > 0 && (m == null || arrived >= asked)) { // 30 ms quiet, or the window is in
                reply_pull_t pull = new reply_pull_t(); // the next WINDOW missing parts
                pull.utime = System.currentTimeMillis() * 1000;
                pull.request_id = id;
                pull.reply_channel = reply;
                pull.total_size = buf.length;
                pull.answer_hash = hash;
                pull.offsets = new long[WINDOW];
                for (int k = 0; k < have.length && pull.num_ranges < WINDOW; k++)
                    if (!have[k]) pull.offsets[pull.num_ranges++] = (long) k * partSize;
                pull.offsets = Arrays.copyOf(pull.offsets, pull.num_ranges);
                pull.lengths = new long[pull.num_ranges];
                for (int r = 0; r < pull.num_ranges; r++)
                    pull.lengths[r] = Math.min(partSize, buf.length - pull.offsets[r]);
                lcm.publish(PREFIX + "QUERY_PULL", pull);
                pulls++;
                asked = pull.num_ranges;
                arrived = 0;
            }
        }
    }

    // reply_part_t.answer_hash: 64-bit FNV-1a over the bytes as big-endian 8-byte words (zero
    // padded).
    static long answerHash(byte[] b) {
        long h = 0xcbf29ce484222325L;
        for (int i = 0; i < b.length; i += 8) {
            long w = 0;
            for (int k = 0; k < 8; k++) w = w << 8 | (i + k < b.length ? b[i + k] & 0xff : 0);
            h = (h ^ w) * 0x100000001b3L;
        }
        return h;
    }
}
