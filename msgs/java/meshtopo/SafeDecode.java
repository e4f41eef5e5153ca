// meshtopo.SafeDecode: decodes what a meshtopo client receives (ack_t, reply_t, reply_part_t,
// mesh_transfer_t, status_t, topology_t) from untrusted bytes. lcm-gen 1.3's Java constructors
// (new reply_t(bytes)) allocate every array and string at the length the bytes declare before
// reading it (new int[num_values], new char[length - 1]), so one forged length throws
// OutOfMemoryError or NegativeArraySizeException, or decodes garbage. SafeDecode first walks the
// bytes against LAYOUTS (the fields of msgs/*.lcm, in order) and calls the generated decoder only
// on a well-formed message; anything else is refused with SafeDecode.Refused naming the field and
// the sizes ("reply_t.item_status: 2147483647 values need 2147483647 bytes, 10 left").
//
// Checked, as mt_msgs_decode does in C (msgs/include/meshtopo/msgs.h):
//   fingerprint   the first 8 bytes are the type's LCM_FINGERPRINT
//   arrays        length member >= 0; length * element size <= bytes left
//   strings       int32 length (counting the NUL) >= 1 and <= bytes left; NUL last, none before
//   nested        count <= bytes left, each struct walked (topology_t in ack_t and reply_t)
//   end           no byte after the message
// then the rules the C client applies to what it decoded (lib/client):
//   reply_t       item_offsets / value_offsets / value2_offsets: num_items + 1 (num_groups + 1)
//                 entries, from 0, never decreasing, ending at num_groups / num_values /
//                 num_values2 (mt_client_reply_check); none at all in an answer without items
//   topology_t    counts and per-component / histogram entries >= 0, every *_listed <= its
//                 count (mt_client_report_from_topology)
//   reply_part_t  0 < part_size <= PART_SIZE, total_size > SINGLE_MESSAGE_MAX, offset a
//                 multiple of part_size below total_size, length = min(part_size, total_size -
//                 offset) (msgs/reply_part_t.lcm)
//   mesh_transfer_t num_missing <= MISSING_MAX
// LAYOUTS is checked against each generated class's LCM_FINGERPRINT_BASE (lcm-gen's hash of the
// member names, types and array lengths), so a .lcm change not made here refuses that type
// ("layout ... does not match") instead of misreading it.
package meshtopo;

import java.io.IOException;
import java.lang.reflect.Array;
import java.util.HashMap;
import java.util.Map;

public final class SafeDecode {
    private SafeDecode() {}

    /** The bytes are not a well-formed message of the type; the message names the field. */
    public static final class Refused extends IOException {
        public Refused(String message) { super(message); }
    }

    // clang-format off
    // The types a client receives, field by field as msgs/NAME.lcm declares them.
    private static final String[][] LAYOUTS = {
        {"topology_t", "int64_t utime", "string mesh_id", "int32_t version", "string source",
         "int64_t mesh_utime", "int64_t build_duration_us", "int64_t content_hash",
         "int32_t num_verts", "int32_t num_faces", "int32_t num_faces_valid", "int64_t num_edges",
         "int64_t num_half_edges", "int64_t boundary_edges", "int32_t boundary_loops",
         "boolean boundary_loops_ambiguous", "int32_t num_boundary_loop_lengths",
         "int32_t boundary_loop_lengths[num_boundary_loop_lengths]", "int64_t nonmanifold_edges",
         "int64_t inconsistent_orientation_edges", "int64_t duplicate_directed_edges",
         "int32_t nonmanifold_vertices", "int32_t bowtie_vertices", "int32_t isolated_vertices",
         "int32_t unreferenced_vertices", "int32_t degenerate_faces", "int32_t duplicate_faces",
         "int64_t out_of_range_indices", "int32_t faces_with_out_of_range_indices",
         "int32_t nonfinite_vertices", "int32_t connected_components",
         "int32_t vertex_connected_components", "int64_t euler_characteristic", "boolean closed",
         "boolean manifold", "boolean orientable", "boolean consistently_oriented",
         "int32_t genus", "int32_t num_components_listed",
         "int32_t component_min_face[num_components_listed]",
         "int32_t component_faces[num_components_listed]",
         "int32_t component_vertices[num_components_listed]",
         "int64_t component_edges[num_components_listed]",
         "int64_t component_euler_characteristic[num_components_listed]",
         "int64_t component_boundary_edges[num_components_listed]",
         "int32_t component_boundary_loops[num_components_listed]",
         "boolean component_closed[num_components_listed]",
         "boolean component_manifold[num_components_listed]",
         "boolean component_orientable[num_components_listed]",
         "int32_t component_genus[num_components_listed]",
         "int32_t component_genus_with_boundary[num_components_listed]",
         "int32_t num_face_size_bins", "int32_t face_size_keys[num_face_size_bins]",
         "int64_t face_size_counts[num_face_size_bins]", "int32_t num_edge_use_bins",
         "int32_t edge_use_keys[num_edge_use_bins]", "int64_t edge_use_counts[num_edge_use_bins]",
         "int64_t num_defects", "int32_t num_defects_listed",
         "int8_t defect_kind[num_defects_listed]", "int32_t defect_a[num_defects_listed]",
         "int32_t defect_b[num_defects_listed]", "int32_t defect_c[num_defects_listed]"},
        {"ack_t", "int64_t utime", "int64_t request_id", "int32_t status", "string error",
         "string mesh_id", "int32_t version", "int64_t content_hash", "int32_t num_reports",
         "topology_t reports[num_reports]"},
        {"reply_t", "int64_t utime", "int64_t request_id", "int32_t status", "string error",
         "string mesh_id", "int32_t version", "int32_t kind", "int32_t num_items",
         "int8_t item_status[num_items]", "int32_t num_item_offsets",
         "int32_t item_offsets[num_item_offsets]", "int32_t num_groups",
         "boolean group_boundary[num_groups]", "int32_t num_value_offsets",
         "int32_t value_offsets[num_value_offsets]", "int32_t value2_offsets[num_value_offsets]",
         "int32_t num_values", "int32_t values[num_values]", "int32_t num_values2",
         "int32_t values2[num_values2]", "int32_t num_reals", "double reals[num_reals]",
         "int32_t num_reports", "topology_t reports[num_reports]", "int32_t num_meshes",
         "string list_mesh_ids[num_meshes]", "int32_t list_versions[num_meshes]",
         "string list_sources[num_meshes]", "int64_t list_utimes[num_meshes]",
         "int32_t list_num_verts[num_meshes]", "int32_t list_num_faces[num_meshes]",
         "int64_t list_num_defects[num_meshes]", "int64_t list_content_hashes[num_meshes]"},
        {"reply_part_t", "int64_t utime", "int64_t request_id", "int64_t total_size",
         "int64_t answer_hash", "int32_t part_size", "int64_t offset", "int32_t length",
         "byte data[length]"},
        {"mesh_transfer_t", "int64_t utime", "int64_t request_id", "int32_t status",
         "string error", "int64_t total_size", "int64_t received_bytes", "boolean complete",
         "int64_t listed_until", "int32_t num_missing", "int64_t missing_offsets[num_missing]",
         "int64_t missing_lengths[num_missing]"},
        {"status_t", "int64_t utime", "string name", "string instance", "int32_t pid",
         "int64_t uptime_us", "string channel_prefix", "int32_t meshes_held",
         "int32_t versions_held", "int64_t memory_bytes", "int64_t submissions", "int64_t builds",
         "int64_t queries", "int64_t errors", "int64_t duplicate_requests",
         "int32_t worker_threads", "int32_t builds_in_progress", "int32_t builds_queued",
         "string last_error", "int64_t last_error_utime", "int32_t transfers_active",
         "int64_t transfer_bytes", "int64_t chunks", "int64_t transfers_completed",
         "int64_t transfers_expired", "int64_t transfers_refused", "int32_t archive_versions",
         "int64_t archive_writes", "int64_t archive_errors", "int64_t archive_loads",
         "int64_t archive_evictions", "int32_t archive_backlog", "int64_t archive_bytes",
         "int64_t memory_budget", "string cluster", "int32_t cluster_members",
         "double cluster_share", "int64_t cluster_view"},
    };
    // Bytes of one element of each primitive type (strings and structs: 0).
    private static final Map<String, Integer> WIDTH = Map.of("int8_t", 1, "byte", 1, "boolean", 1,
        "int16_t", 2, "int32_t", 4, "float", 4, "int64_t", 8, "double", 8, "string", 0);
    // topology_t members that count something (never negative), and each listed <= count.
    // Arrays included (every element): what mt_client_report_from_topology refuses.
    private static final String[] TOPOLOGY_COUNTS = {"num_verts", "num_faces", "num_faces_valid",
        "num_edges", "num_half_edges", "boundary_edges", "boundary_loops", "nonmanifold_edges",
        "inconsistent_orientation_edges", "duplicate_directed_edges", "nonmanifold_vertices",
        "bowtie_vertices", "isolated_vertices", "unreferenced_vertices", "degenerate_faces",
        "duplicate_faces", "out_of_range_indices", "faces_with_out_of_range_indices",
        "nonfinite_vertices", "connected_components", "vertex_connected_components", "num_defects",
        "boundary_loop_lengths", "component_min_face", "component_faces", "component_vertices",
        "component_edges", "component_boundary_edges", "component_boundary_loops", "face_size_keys",
        "face_size_counts", "edge_use_keys", "edge_use_counts"};
    // clang-format on

    private static final class Field {
        final String type, name, length; // length: the member holding the count, or null
        Field(String spec) {
            String[] w = spec.split(" ");
            int b = w[1].indexOf('[');
            type = w[0];
            name = b < 0 ? w[1] : w[1].substring(0, b);
            length = b < 0 ? null : w[1].substring(b + 1, w[1].length() - 1);
        }
    }

    private static final class Layout {
        final String name;
        final Field[] fields;
        long hash = 0x12345678L; // lcm-gen's lcm_struct_hash of the fields, as it computes it
        Layout(String[] row) {
            name = row[0];
            fields = new Field[row.length - 1];
            for (int i = 1; i < row.length; i++) {
                Field f = fields[i - 1] = new Field(row[i]);
                hash = text(hash, f.name);
                if (WIDTH.containsKey(f.type)) hash = text(hash, f.type);
                hash = step(hash, f.length == null ? 0 : 1);
                if (f.length != null) hash = text(step(hash, 1), f.length); // LCM_VAR = 1
            }
        }
        private static long step(long v, int c) { return ((v << 8) ^ (v >> 55)) + (byte) c; }
        private static long text(long v, String s) {
            v = step(v, s.length());
            for (int i = 0; i < s.length(); i++) v = step(v, s.charAt(i));
            return v;
        }
    }

    private static final Map<String, Layout> BY_NAME = new HashMap<>();
    static {
        for (String[] row : LAYOUTS) BY_NAME.put(row[0], new Layout(row));
    }

    /** The generated class's fingerprint base, for the layout check. */
    private static long base(String type) {
        switch (type) {
            case "topology_t":
                return topology_t.LCM_FINGERPRINT_BASE;
            case "ack_t":
                return ack_t.LCM_FINGERPRINT_BASE;
            case "reply_t":
                return reply_t.LCM_FINGERPRINT_BASE;
            case "reply_part_t":
                return reply_part_t.LCM_FINGERPRINT_BASE;
            case "mesh_transfer_t":
                return mesh_transfer_t.LCM_FINGERPRINT_BASE;
            default:
                return status_t.LCM_FINGERPRINT_BASE;
        }
    }

    /** The type (of those above) whose fingerprint starts the bytes, or null. */
    public static String typeOf(byte[] b) {
        if (b == null || b.length < 8) return null;
        long fp = 0;
        for (int i = 0; i < 8; i++) fp = fp << 8 | (b[i] & 0xff);
        if (fp == ack_t.LCM_FINGERPRINT) return "ack_t";
        if (fp == reply_t.LCM_FINGERPRINT) return "reply_t";
        if (fp == reply_part_t.LCM_FINGERPRINT) return "reply_part_t";
        if (fp == mesh_transfer_t.LCM_FINGERPRINT) return "mesh_transfer_t";
        if (fp == status_t.LCM_FINGERPRINT) return "status_t";
        return fp == topology_t.LCM_FINGERPRINT ? "topology_t" : null;
    }

    /** Checks that b is exactly one well-formed encoded message of `type`; throws Refused. */
    public static void check(String type, byte[] b) throws Refused {
        Layout layout = BY_NAME.get(type);
        if (layout == null) throw new Refused("SafeDecode: no layout of type " + type);
        for (String t : new String[] {type, "topology_t"}) // the type, and the one it nests
            if (BY_NAME.get(t).hash != base(t))
                throw new Refused(type + ": SafeDecode's layout of " + t
                        + " does not match meshtopo." + t + " (msgs/" + t
                        + ".lcm changed: update SafeDecode.LAYOUTS)");
        if (b == null || b.length < 8)
            throw new Refused(type + ": " + (b == null ? 0 : b.length)
                    + " bytes, shorter than a fingerprint");
        String found = typeOf(b);
        if (!type.equals(found))
            throw new Refused(type + ": wrong fingerprint"
                    + (found != null ? ": the bytes are a " + found : ", not its type"));
        int end = walk(layout, b, 8, type);
        if (end != b.length)
            throw new Refused(type + ": " + (b.length - end) + " bytes after the end");
    }

    /** Walks one struct from `pos`; returns where it ends. */
    private static int walk(Layout t, byte[] b, int pos, String path) throws Refused {
        Map<String, Long> ints = new HashMap<>();
        for (Field f : t.fields) {
            String at = path + "." + f.name;
            long count = f.length == null ? 1 : ints.get(f.length);
            long left = b.length - pos;
            if (count < 0)
                throw new Refused(at + ": negative length " + count + " (" + f.length + ")");
            Integer width = WIDTH.get(f.type);
            if (width == null) { // a nested struct: at least one byte each
                if (count > left)
                    throw new Refused(
                            at + ": " + count + " structs cannot fit in " + left + " bytes");
                for (long i = 0; i < count; i++)
                    pos = walk(BY_NAME.get(f.type), b, pos, at + "[" + i + "]");
            } else if (width == 0) { // strings: at least 5 bytes each (length and NUL)
                if (count > left / 5)
                    throw new Refused(
                            at + ": " + count + " strings cannot fit in " + left + " bytes");
                for (long i = 0; i < count; i++)
                    pos = string(b, pos, f.length == null ? at : at + "[" + i + "]");
            } else {
                if (count > left / width)
                    throw new Refused(at + ": " + count + " values need " + count * width
                            + " bytes, " + left + " left");
                if (f.length == null && f.type.startsWith("int"))
                    ints.put(f.name, read(b, pos, width));
                pos += (int) (count * width);
            }
        }
        return pos;
    }

    private static int string(byte[] b, int pos, String at) throws Refused {
        long left = b.length - pos;
        if (left < 4) throw new Refused(at + ": string length needs 4 bytes, " + left + " left");
        long n = read(b, pos, 4);
        pos += 4;
        left -= 4;
        if (n < 1)
            throw new Refused(at + ": string length " + n + " (it counts the NUL, so at least 1)");
        if (n > left) throw new Refused(at + ": string of " + n + " bytes, " + left + " left");
        for (int i = 0; i < n; i++)
            if ((b[pos + i] == 0) != (i == n - 1))
                throw new Refused(at + ": string of " + n + " bytes "
                        + (i == n - 1 ? "does not end with a NUL" : "has a NUL at byte " + i));
        return pos + (int) n;
    }

    private static long read(byte[] b, int pos, int width) {
        long v = b[pos]; // sign-extended first byte
        for (int i = 1; i < width; i++) v = v << 8 | (b[pos + i] & 0xff);
        return v;
    }

    // ---- Decoders: check, the generated constructor, then the type's rules -----------------

    public static ack_t ack(byte[] b) throws IOException {
        check("ack_t", b);
        ack_t a = new ack_t(b);
        for (int i = 0; i < a.num_reports; i++) rules(a.reports[i], "ack_t.reports[" + i + "]");
        return a;
    }

    public static reply_t reply(byte[] b) throws IOException {
        check("reply_t", b);
        reply_t r = new reply_t(b);
        boolean empty = r.num_items == 0 && r.num_groups == 0 && r.num_item_offsets == 0
                && r.num_value_offsets == 0 && r.num_values == 0 && r.num_values2 == 0;
        if (!empty) {
            offsets("item_offsets", r.item_offsets, r.num_items + 1L, r.num_groups, "num_groups");
            offsets("value_offsets", r.value_offsets, r.num_groups + 1L, r.num_values,
                    "num_values");
            offsets("value2_offsets", r.value2_offsets, r.num_groups + 1L, r.num_values2,
                    "num_values2");
        }
        for (int i = 0; i < r.num_reports; i++) rules(r.reports[i], "reply_t.reports[" + i + "]");
        return r;
    }

    public static reply_part_t replyPart(byte[] b) throws IOException {
        check("reply_part_t", b);
        reply_part_t p = new reply_part_t(b);
        if (p.part_size <= 0 || p.part_size > reply_part_t.PART_SIZE)
            throw new Refused("reply_part_t.part_size: " + p.part_size + " is not within 1.."
                    + reply_part_t.PART_SIZE);
        if (p.total_size <= mesh_chunk_t.SINGLE_MESSAGE_MAX)
            throw new Refused("reply_part_t.total_size: " + p.total_size
                    + ", an answer in parts has more than " + mesh_chunk_t.SINGLE_MESSAGE_MAX
                    + " bytes");
        if (p.offset < 0 || p.offset >= p.total_size || p.offset % p.part_size != 0)
            throw new Refused("reply_part_t.offset: " + p.offset + " is not a multiple of "
                    + p.part_size + " below " + p.total_size);
        if (p.length != Math.min(p.part_size, p.total_size - p.offset))
            throw new Refused("reply_part_t.length: " + p.length + " bytes at offset " + p.offset
                    + ", expected " + Math.min(p.part_size, p.total_size - p.offset));
        return p;
    }

    public static mesh_transfer_t meshTransfer(byte[] b) throws IOException {
        check("mesh_transfer_t", b);
        mesh_transfer_t t = new mesh_transfer_t(b);
        if (t.num_missing > mesh_transfer_t.MISSING_MAX)
            throw new Refused("mesh_transfer_t.num_missing: " + t.num_missing + " ranges, at most "
                    + mesh_transfer_t.MISSING_MAX);
        return t;
    }

    public static status_t status(byte[] b) throws IOException {
        check("status_t", b);
        return new status_t(b);
    }

    public static topology_t topology(byte[] b) throws IOException {
        check("topology_t", b);
        topology_t t = new topology_t(b);
        rules(t, "topology_t");
        return t;
    }

    /** A reassembled answer (reply_part_t pieces): a reply_t or an ack_t, by its fingerprint. */
    public static lcm.lcm.LCMEncodable answer(byte[] b) throws IOException {
        String type = typeOf(b);
        if ("reply_t".equals(type)) return reply(b);
        if ("ack_t".equals(type)) return ack(b);
        throw new Refused("answer: the bytes are "
                + (type == null ? "no meshtopo type" : "a " + type) + ", not a reply_t or ack_t");
    }

    private static void offsets(String name, int[] o, long expected, int end, String endName)
            throws Refused {
        if (o.length != expected)
            throw new Refused(
                    "reply_t." + name + ": " + o.length + " entries, expected " + expected);
        if (o[0] != 0) throw new Refused("reply_t." + name + "[0] = " + o[0] + ", expected 0");
        for (int i = 1; i < o.length; i++)
            if (o[i] < o[i - 1])
                throw new Refused("reply_t." + name + "[" + i + "] = " + o[i]
                        + " is below the one before, " + o[i - 1]);
        if (o[o.length - 1] != end)
            throw new Refused("reply_t." + name + "[" + (o.length - 1) + "] = " + o[o.length - 1]
                    + ", expected " + endName + " = " + end);
    }

    private static void rules(topology_t t, String at) throws Refused {
        try {
            for (String name : TOPOLOGY_COUNTS) {
                Object v = topology_t.class.getField(name).get(t);
                boolean array = v.getClass().isArray();
                for (int i = 0, n = array ? Array.getLength(v) : 1; i < n; i++) {
                    long x = ((Number) (array ? Array.get(v, i) : v)).longValue();
                    if (x < 0)
                        throw new Refused(at + "." + name + (array ? "[" + i + "]" : "") + " = " + x
                                + " is negative");
                }
            }
        } catch (ReflectiveOperationException e) {
            throw new Refused(at + ": " + e);
        }
        if (t.num_boundary_loop_lengths > t.boundary_loops)
            throw new Refused(at + ".num_boundary_loop_lengths = " + t.num_boundary_loop_lengths
                    + " lists more than boundary_loops = " + t.boundary_loops);
        if (t.num_components_listed > t.connected_components)
            throw new Refused(at + ".num_components_listed = " + t.num_components_listed
                    + " lists more than connected_components = " + t.connected_components);
        if (t.num_defects_listed > t.num_defects)
            throw new Refused(at + ".num_defects_listed = " + t.num_defects_listed
                    + " lists more than num_defects = " + t.num_defects);
    }
}
