/* The C side of the Python package (lib/python/meshtopo): the few calls it
 * makes through ctypes besides the libraries' own (meshtopo/core.h,
 * meshtopo/io.h, meshtopo/report_json.h), for what ctypes cannot reach
 * well: status names from the status table, whole-mesh loops that would
 * cost one foreign call per element, and the client's LCM-typed replies
 * read into plain arrays, received messages decoded safely. They add no
 * algorithm: each calls the libraries. */
#ifndef MESHTOPO_PYTHON_API_H
#define MESHTOPO_PYTHON_API_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/client.h"
#include "meshtopo/mesh.h"
#include "meshtopo/msgs.h"
#include "meshtopo/status.h"

/* ---- Meshes (python_mesh.c) -------------------------------------------- */

/* The enumerator's name of a status ("MT_ERR_INVALID_ARG"), from the same
 * table as mt_strerror; "MT_UNKNOWN_STATUS" past the table. */
const char *mt_py_status_name(mt_status status);

/* Size in bytes of a library struct the package mirrors (ctypes structs,
 * numpy records), by name ("mt_report"); 0 for an unknown name. The package
 * checks its layouts against it when it loads. */
size_t mt_py_sizeof(const char *type_name);

/* Component of every face record (numbered as report->components), MT_NONE
 * for a record the build rejected: out_components[0 .. capacity) gets
 * min(capacity, face count) entries. Returns the face count. */
size_t mt_py_face_components(const mt_mesh *mesh, uint32_t *out_components, size_t capacity);

/* ---- Client (python_client.c) ------------------------------------------ */

/* mt_client_create with the options the package exposes (NULL / 0: the
 * defaults of mt_client_options). */
mt_status mt_py_client_create(const char *lcm_url, const char *channel_prefix, int timeout_ms,
                              int retries, const char *source, mt_client **out, mt_diag *diag);

/* mt_client_submit; on an ack (even one with an error status) *out_version
 * and *out_content_hash get its version and content hash, and, when the ack
 * carries a report, *out_report_json the report as JSON (the summary of
 * `meshtopo send --json`'s "report": meshtopo::json's summary with the
 * daemon's keys, plus "num_defects"), to free with mt_report_json_free;
 * else NULL. */
mt_status mt_py_client_submit(mt_client *client, const char *mesh_id, const mt_face_list *list,
                              int strict, int32_t *out_version, int64_t *out_content_hash,
                              char **out_report_json, mt_diag *diag);

/* A reply held for the package (an opaque, heap-allocated reply_t). */
typedef struct mt_py_reply mt_py_reply;

/* mt_client_query, or mt_client_list when kind is LIST_MESHES (ids
 * ignored). *out_reply gets the reply whenever one arrived (even with an
 * error status), else NULL; free it with mt_py_reply_free. */
mt_status mt_py_client_query(mt_client *client, const char *mesh_id, int32_t version, int32_t kind,
                             const uint32_t *ids, size_t num_ids, mt_py_reply **out_reply,
                             mt_diag *diag);

void mt_py_reply_free(mt_py_reply *reply);

/* The answered version, and the sizes of the flat arrays of
 * mt_py_reply_flatten: out_sizes[0] items, [1] groups, [2] values,
 * [3] values2, [4] reals, [5] listed meshes. */
int32_t mt_py_reply_version(const mt_py_reply *reply);
void mt_py_reply_sizes(const mt_py_reply *reply, size_t out_sizes[6]);

/* The reply's items and groups as CSR arrays, read through the client's
 * accessors (meshtopo/client_reply.h): item i's status is item_status[i]
 * and its groups item_groups[i] .. item_groups[i + 1]; group g's boundary
 * flag is group_boundary[g], its values values[group_values[g] ..
 * group_values[g + 1]), its values2 likewise. Each array is as large as
 * mt_py_reply_sizes says (+ 1 for the offset arrays); reals gets the reply's
 * reals. */
void mt_py_reply_flatten(const mt_py_reply *reply, int32_t *item_status, uint64_t *item_groups,
                         uint8_t *group_boundary, uint64_t *group_values, int32_t *values,
                         uint64_t *group_values2, int32_t *values2, double *reals);

/* Mesh `index` of a LIST_MESHES reply (index below sizes[5]): id and
 * source (owned by the reply), version, utime, counts and content hash. */
void mt_py_reply_listed(const mt_py_reply *reply, size_t index, const char **out_mesh_id,
                        const char **out_source, int32_t *out_version, int64_t *out_utime,
                        int32_t *out_num_verts, int32_t *out_num_faces, int64_t *out_num_defects,
                        int64_t *out_content_hash);

/* ---- Messages (python_msgs.c) ------------------------------------------ */

/* The meshtopo message type named `name` ("reply_t" or "meshtopo.reply_t"),
 * NULL for none. mt_msgs_type_of (meshtopo/msgs.h) finds one by fingerprint. */
const mt_msgs_type *mt_py_msgs_type(const char *name);

/* The type's name ("reply_t"), sizeof its struct, its number of fields. */
const char *mt_py_msgs_type_name(const mt_msgs_type *type);
size_t mt_py_msgs_struct_size(const mt_msgs_type *type);
int mt_py_msgs_num_fields(const mt_msgs_type *type);

/* Field `index` of msg (a struct of `type`) as lcm-gen's typeinfo describes
 * it (the generated get_field): 0, or nonzero past the last field. */
int mt_py_msgs_field(const mt_msgs_type *type, const void *msg, int index, lcm_field_t *out_field);

/* The one type `channel` carries (meshtopo/channels.h): PREFIX + a daemon
 * channel's suffix, or a reply channel + an answer type's suffix ("_ACK",
 * "_REPLY", "_PART", "_TRANSFER"); NULL for none. */
const mt_msgs_type *mt_py_msgs_channel_type(const char *prefix, const char *channel);

/* Decodes received bytes: mt_msgs_decode (every length checked against the
 * bytes before anything is allocated), then the rules of the type that the
 * client library applies after decoding: reply_t offsets
 * (mt_client_reply_check), topology_t counts and lists, own or in an ack_t or
 * reply_t (mt_client_report_from_topology), the layout of a reply_part_t
 * (msgs/reply_part_t.lcm) and mesh_transfer_t's MISSING_MAX. MT_OK with a
 * heap struct of `type` in *out_msg (release it with mt_py_msgs_free), or
 * MT_ERR_CORRUPT (MT_ERR_NOMEM) with diag naming the field and the sizes. */
mt_status mt_py_msgs_decode(const mt_msgs_type *type, const void *buf, size_t size, void **out_msg,
                            mt_diag *diag);

/* Releases a struct of mt_py_msgs_decode (its arrays too). NULL-safe. */
void mt_py_msgs_free(const mt_msgs_type *type, void *msg);

#endif
