// Shows that LogDecode can fail (ctest protocol.lcm_log_decodes_self_test):
// writes small LCM logs with lcm.logging.Log, one well-formed event per
// channel of the protocol, and checks LogDecode passes that log and reports
// exactly the one planted event as undecodable in each broken variant (a
// mesh_chunk_t on SUBMIT, a channel no rule names, cut bytes, extra bytes),
// and fails a log where a channel that must appear is absent.
// usage: java -cp lcm.jar:meshtopo-msgs.jar:CLASSES LogDecodeSelfTest DIR

import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.File;
import java.io.IOException;
import java.io.PrintStream;
import java.lang.reflect.Array;
import java.lang.reflect.Field;
import java.lang.reflect.Modifier;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Map;
import lcm.lcm.LCMEncodable;
import lcm.logging.Log;

public class LogDecodeSelfTest {
    static int failures = 0;

    static void check(boolean ok, String what) {
        System.out.println((ok ? "ok    " : "FAIL  ") + what);
        if (!ok) failures++;
    }

    /** A message of meshtopo.TYPE with every string set and every array empty. */
    static LCMEncodable sample(String type) throws ReflectiveOperationException {
        Object msg = Class.forName("meshtopo." + type).getConstructor().newInstance();
        for (Field f : msg.getClass().getFields()) {
            if (Modifier.isStatic(f.getModifiers())) continue;
            Class<?> t = f.getType();
            if (t == String.class) f.set(msg, type + "." + f.getName());
            else if (t.isArray()) f.set(msg, Array.newInstance(t.getComponentType(), 0));
            else if (t == long.class && f.getName().equals("utime"))
                f.setLong(msg, 1700000000000000L);
        }
        return (LCMEncodable) msg;
    }

    static byte[] encode(LCMEncodable msg) throws IOException {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        msg.encode(new DataOutputStream(out));
        return out.toByteArray();
    }

    /** One event to write: a channel and its bytes. */
    static final class Ev {
        final String channel;
        final byte[] data;

        Ev(String channel, byte[] data) {
            this.channel = channel;
            this.data = data;
        }
    }

    /** One well-formed event per channel: the six under the prefix, and the
     *  four answers on a client's reply channel. */
    static List<Ev> goodEvents(String prefix) throws Exception {
        List<Ev> evs = new ArrayList<>();
        for (String[] c : LogDecode.PREFIX_CHANNELS)
            evs.add(new Ev(prefix + c[0], encode(sample(c[1]))));
        String reply = prefix + "REPLY_host_1234_5678";
        for (String[] s : LogDecode.REPLY_SUFFIXES)
            evs.add(new Ev(reply + s[0], encode(sample(s[1]))));
        return evs;
    }

    static String write(File dir, String name, List<Ev> evs) throws IOException {
        File f = new File(dir, name);
        if (f.exists() && !f.delete()) throw new IOException("cannot replace " + f);
        Log log = new Log(f.getPath(), "rw");
        long number = 0;
        for (Ev e : evs) {
            Log.Event ev = new Log.Event();
            ev.eventNumber = number;
            ev.utime = 1700000000000000L + number++;
            ev.channel = e.channel;
            ev.data = e.data;
            log.write(ev);
        }
        log.close();
        return f.getPath();
    }

    /** Runs LogDecode as the test does; returns its exit status and prints its table. */
    static int decode(String... args) throws IOException {
        ByteArrayOutputStream buf = new ByteArrayOutputStream();
        int rc;
        try (PrintStream out = new PrintStream(buf, true, "UTF-8")) {
            rc = LogDecode.run(args, out);
        }
        for (String line : new String(buf.toByteArray(), StandardCharsets.UTF_8).split("\n"))
            System.out.println("      | " + line);
        return rc;
    }

    /** The channels LogDecode counts undecodable events on, and how many each. */
    static String undecodable(String path, String prefix) throws IOException {
        StringBuilder sb = new StringBuilder();
        for (Map.Entry<String, LogDecode.Row> e : LogDecode.decodeLog(path, prefix).entrySet())
            if (e.getValue().undecodable > 0)
                sb.append(sb.length() > 0 ? " " : "").append(e.getKey()).append('=')
                  .append(e.getValue().undecodable);
        return sb.toString();
    }

    /** The good events with one planted event among them. */
    static void planted(File dir, String name, Ev bad, String expect) throws Exception {
        List<Ev> evs = goodEvents("MESHTOPO_");
        evs.add(3, bad);
        String path = write(dir, name, evs);
        System.out.println(name + ":");
        check(decode(path) == 1, name + ": LogDecode exits 1");
        String got = undecodable(path, "MESHTOPO_");
        check(got.equals(expect), name + ": exactly one undecodable event, on " + expect
                                      + " (got: " + got + ")");
    }

    public static void main(String[] args) throws Exception {
        if (args.length != 1) {
            System.err.println("usage: LogDecodeSelfTest DIR");
            System.exit(2);
        }
        File dir = new File(args[0]);
        if (!dir.isDirectory() && !dir.mkdirs()) throw new IOException("cannot make " + dir);

        // Every type a channel names is in the jar, and the table maps as the protocol says.
        check("mesh_chunk_t".equals(LogDecode.typeOf("MESHTOPO_SUBMIT_CHUNK", "MESHTOPO_")),
              "MESHTOPO_SUBMIT_CHUNK carries mesh_chunk_t");
        check("mesh_t".equals(LogDecode.typeOf("MESHTOPO_SUBMIT", "MESHTOPO_")),
              "MESHTOPO_SUBMIT carries mesh_t");
        check("reply_part_t".equals(LogDecode.typeOf("MESHTOPO_REPLY_a_1_2_PART", "MESHTOPO_")),
              "a reply channel + _PART carries reply_part_t");
        check(LogDecode.typeOf("MESHTOPO_REPLY_a_1_2", "MESHTOPO_") == null,
              "a bare reply channel has no type");
        check(LogDecode.typeOf("OTHER_STATUS", "MESHTOPO_") == null,
              "another prefix's STATUS has no type");

        System.out.println("good.lcmlog:");
        String good = write(dir, "good.lcmlog", goodEvents("MESHTOPO_"));
        check(decode(good) == 0, "good.lcmlog: one event per channel, LogDecode exits 0");
        check(undecodable(good, "MESHTOPO_").isEmpty(), "good.lcmlog: nothing undecodable");

        System.out.println("prefixed.lcmlog:");
        String prefixed = write(dir, "prefixed.lcmlog", goodEvents("LAB2_"));
        check(decode("--prefix", "LAB2_", prefixed) == 0,
              "prefixed.lcmlog --prefix LAB2_: exits 0");
        check(decode(prefixed) == 1,
              "prefixed.lcmlog without --prefix: exits 1 (unknown channels)");

        planted(dir, "wrong_type.lcmlog",
                new Ev("MESHTOPO_SUBMIT", encode(sample("mesh_chunk_t"))), "MESHTOPO_SUBMIT=1");
        planted(dir, "no_rule.lcmlog",
                new Ev("MESHTOPO_REPLY_host_1234_5678", encode(sample("reply_t"))),
                "MESHTOPO_REPLY_host_1234_5678=1");
        byte[] status = encode(sample("status_t"));
        planted(dir, "cut.lcmlog",
                new Ev("MESHTOPO_STATUS", Arrays.copyOf(status, status.length - 3)),
                "MESHTOPO_STATUS=1");
        planted(dir, "extra_bytes.lcmlog",
                new Ev("MESHTOPO_STATUS", Arrays.copyOf(status, status.length + 4)),
                "MESHTOPO_STATUS=1");

        System.out.println("no_transfer.lcmlog:");
        List<Ev> evs = goodEvents("MESHTOPO_");
        evs.removeIf(e -> e.channel.endsWith("_TRANSFER"));
        String noTransfer = write(dir, "no_transfer.lcmlog", evs);
        check(decode(noTransfer) == 1, "no_transfer.lcmlog: no _TRANSFER event, LogDecode exits 1");
        check(undecodable(noTransfer, "MESHTOPO_").isEmpty(),
              "no_transfer.lcmlog: every event there decodes");

        System.out.println(failures + " failure(s)");
        System.exit(failures == 0 ? 0 : 1);
    }
}
