// Decodes every event of an LCM log (lcm-logger's file) with the one meshtopo
// type its channel carries (ctest protocol.lcm_log_decodes): PREFIX + SUBMIT,
// SUBMIT_CHUNK, QUERY, QUERY_PULL, TOPOLOGY, STATUS by name, answers by the
// suffix of the request's reply channel (_ACK, _REPLY, _PART, _TRANSFER).
// Prints channel / type / events / undecodable; exits 1 when any event does
// not decode (or its channel has no type) or a channel that must appear did not.
// usage: java -cp lcm.jar:meshtopo-msgs.jar:CLASSES LogDecode [--prefix P] LOG

import java.io.ByteArrayInputStream;
import java.io.DataInput;
import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.PrintStream;
import java.lang.reflect.Constructor;
import java.lang.reflect.InvocationTargetException;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;
import lcm.logging.Log;

public class LogDecode {
    public static final String DEFAULT_PREFIX = "MESHTOPO_";
    // The channels under the prefix and their one type each.
    static final String[][] PREFIX_CHANNELS = {
        {"SUBMIT", "mesh_t"},
        {"SUBMIT_CHUNK", "mesh_chunk_t"},
        {"QUERY", "query_t"},
        {"QUERY_PULL", "reply_pull_t"},
        {"TOPOLOGY", "topology_t"},
        {"STATUS", "status_t"},
    };
    // Suffixes the answers add to a request's reply_channel, and their types.
    static final String[][] REPLY_SUFFIXES = {
        {"_ACK", "ack_t"},
        {"_REPLY", "reply_t"},
        {"_PART", "reply_part_t"},
        {"_TRANSFER", "mesh_transfer_t"},
    };
    // Every type of package meshtopo, to name what a wrong event carries.
    static final String[] ALL_TYPES = {
        "ack_t", "mesh_chunk_t", "mesh_t", "mesh_transfer_t", "query_t", "reply_part_t",
        "reply_pull_t", "reply_t", "status_code_t", "status_t", "topology_t",
    };

    /** One channel's tally. */
    public static final class Row {
        public final String channel;
        public final String type;  // null: the channel matches no rule
        public long events;
        public long undecodable;
        public String firstError;

        Row(String channel, String type) {
            this.channel = channel;
            this.type = type;
        }
    }

    /** The one type of a channel, or null when no rule names it. */
    public static String typeOf(String channel, String prefix) {
        for (String[] c : PREFIX_CHANNELS)
            if (channel.equals(prefix + c[0])) return c[1];
        for (String[] s : REPLY_SUFFIXES)
            if (channel.length() > s[0].length() && channel.endsWith(s[0])) return s[1];
        return null;
    }

    static final Map<String, Constructor<?>> decoders = new TreeMap<>();
    static final Map<Long, String> fingerprints = new TreeMap<>();

    static Constructor<?> decoder(String type) throws ReflectiveOperationException {
        Constructor<?> c = decoders.get(type);
        if (c == null) {
            c = Class.forName("meshtopo." + type).getConstructor(DataInput.class);
            decoders.put(type, c);
        }
        return c;
    }

    /** The type whose fingerprint the bytes start with, for messages. */
    static String carried(byte[] data) {
        if (fingerprints.isEmpty()) {
            for (String t : ALL_TYPES) {
                try {
                    Class<?> cls = Class.forName("meshtopo." + t);
                    fingerprints.put(cls.getField("LCM_FINGERPRINT").getLong(null), t);
                } catch (ReflectiveOperationException e) {
                    // a type this jar lacks cannot be named
                }
            }
        }
        if (data.length < 8) return "fewer than 8 bytes";
        long fp = 0;
        for (int i = 0; i < 8; i++) fp = (fp << 8) | (data[i] & 0xff);
        String t = fingerprints.get(fp);
        return t != null ? "carries " + t : String.format("unknown fingerprint %016x", fp);
    }

    /** Null when data is one whole message of the type, else why not. */
    public static String decodeError(String type, byte[] data) {
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(data));
        try {
            decoder(type).newInstance(in);
            int left = in.available();
            return left == 0 ? null : left + " bytes left after the message";
        } catch (InvocationTargetException e) {
            Throwable cause = e.getCause();
            String what = cause instanceof EOFException ? "truncated" : String.valueOf(cause);
            return what + " (" + carried(data) + ")";
        } catch (OutOfMemoryError e) {
            return "absurd length (" + carried(data) + ")";
        } catch (ReflectiveOperationException | IOException e) {
            return "no decoder for meshtopo." + type + ": " + e;
        }
    }

    /** Every channel of the log with its tally, in order of first appearance. */
    public static Map<String, Row> decodeLog(String path, String prefix) throws IOException {
        Map<String, Row> rows = new LinkedHashMap<>();
        Log log = new Log(path, "r");
        try {
            while (true) {
                Log.Event e;
                try {
                    e = log.readNext();
                } catch (EOFException eof) {
                    break;
                }
                Row row = rows.get(e.channel);
                if (row == null) {
                    row = new Row(e.channel, typeOf(e.channel, prefix));
                    rows.put(e.channel, row);
                }
                row.events++;
                String err = row.type == null ? "no rule gives this channel a type ("
                                                    + carried(e.data) + ")"
                                              : decodeError(row.type, e.data);
                if (err != null) {
                    row.undecodable++;
                    if (row.firstError == null)
                        row.firstError = "event " + e.eventNumber + ": " + err;
                }
            }
        } finally {
            log.close();
        }
        return rows;
    }

    /** The channels (or suffixes) that must appear with events, and are missing. */
    public static List<String> missing(Map<String, Row> rows, String prefix) {
        List<String> out = new ArrayList<>();
        for (String[] c : PREFIX_CHANNELS) {
            Row r = rows.get(prefix + c[0]);
            if (r == null || r.events == 0) out.add(prefix + c[0] + " (" + c[1] + ")");
        }
        for (String[] s : REPLY_SUFFIXES) {
            boolean seen = false;
            for (Row r : rows.values())
                if (s[1].equals(r.type) && r.events > 0 && r.channel.endsWith(s[0])) seen = true;
            if (!seen) out.add("a reply channel + " + s[0] + " (" + s[1] + ")");
        }
        return out;
    }

    /** Prints the table; 0 when everything decodes and every channel appeared. */
    public static int run(String[] args, PrintStream out) throws IOException {
        String prefix = DEFAULT_PREFIX, path = null;
        for (int i = 0; i < args.length; i++) {
            if (args[i].equals("--prefix") && i + 1 < args.length) {
                prefix = args[++i];
            } else if (args[i].startsWith("--prefix=")) {
                prefix = args[i].substring("--prefix=".length());
            } else if (path == null && !args[i].startsWith("--")) {
                path = args[i];
            } else {
                out.println("usage: LogDecode [--prefix PREFIX] LOG");
                return 2;
            }
        }
        if (path == null) {
            out.println("usage: LogDecode [--prefix PREFIX] LOG");
            return 2;
        }
        Map<String, Row> rows = decodeLog(path, prefix);
        int width = "channel".length();
        for (Row r : rows.values()) width = Math.max(width, r.channel.length());
        String fmt = "%-" + width + "s  %-16s %8s %12s%n";
        out.printf(fmt, "channel", "type", "events", "undecodable");
        long events = 0, bad = 0;
        for (Row r : rows.values()) {
            out.printf(fmt, r.channel, r.type == null ? "(none)" : r.type, r.events, r.undecodable);
            events += r.events;
            bad += r.undecodable;
        }
        out.printf(fmt, "total (" + rows.size() + " channels)", "", events, bad);
        for (Row r : rows.values())
            if (r.firstError != null)
                out.println("UNDECODABLE on " + r.channel + ": " + r.undecodable + " of " + r.events
                            + " events; first: " + r.firstError);
        List<String> absent = missing(rows, prefix);
        for (String m : absent) out.println("MISSING: no event on " + m);
        if (bad == 0 && absent.isEmpty()) {
            out.println("OK: " + events + " events on " + rows.size()
                        + " channels, each decoded by its channel's one type");
            return 0;
        }
        return 1;
    }

    public static void main(String[] args) throws IOException {
        System.exit(run(args, System.out));
    }
}
