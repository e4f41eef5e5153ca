/* meshtopo::msgs: the LCM message types of package meshtopo (generated from
 * the .lcm files in msgs/ by lcm-gen at build time) and a safe way to decode them.
 *
 * The decoders lcm-gen 1.3 writes trust their input: a negative or huge array
 * length, a string without its terminating NUL or a message cut short can make
 * them read out of bounds, allocate absurd sizes or free uninitialised
 * pointers. mt_msgs_decode first walks the bytes against the type's field list
 * (lcm-gen's typeinfo), allocating nothing whose size the message sets, and
 * calls the generated decoder only on a well-formed message: untrusted bytes
 * give an error, never a crash. Use it (not meshtopo_*_t_decode or the
 * generated _subscribe handlers) on anything received from the network.
 *
 * Threads: everything here is reentrant, but lcm-gen's fingerprint functions
 * (used by every encode and decode) fill a static on their first call without
 * a lock; call mt_msgs_type_of(NULL, 0), which computes them all, once
 * before starting threads that use the types. */
#ifndef MESHTOPO_MSGS_H
#define MESHTOPO_MSGS_H

#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm_coretypes.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One generated message type, seen through functions taking void * so that
 * code can handle every type alike. mt_msgs_type_NAME (NAME without "_t")
 * exists for each type; meshtopo/msgs_types.h declares them. */
typedef struct mt_msgs_type {
    const char *name;   /* LCM type name without the package: "mesh_t" */
    size_t struct_size; /* sizeof(meshtopo_NAME_t) */
    int64_t (*fingerprint)(void);
    int (*num_fields)(void);
    int (*get_field)(const void *msg, int index, lcm_field_t *out_field);
    int (*encoded_size)(const void *msg);
    int (*encode)(void *buf, int offset, int maxlen, const void *msg);
    int (*decode)(const void *buf, int offset, int maxlen, void *msg);
    int (*decode_cleanup)(void *msg);
} mt_msgs_type;

#ifdef __cplusplus
}
#endif

/* The generated part: every meshtopo_*_t header, mt_msgs_type_NAME for each
 * type and the mt_msgs_types table. */
#include "meshtopo/msgs_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Size of the error text buffers below that never truncates a message. */
#define MT_MSGS_ERROR_SIZE 256

/* The meshtopo type whose fingerprint starts buf (the first 8 bytes of every
 * LCM message), or NULL when there is none or size < 8. The bytes after the
 * fingerprint are not looked at: call mt_msgs_decode next. Computes every
 * type's fingerprint on each call (see Threads above). */
const mt_msgs_type *mt_msgs_type_of(const void *buf, size_t size);

/* Checks that buf[0 .. size) is exactly one well-formed encoded message of
 * `type`: its fingerprint, every length member non-negative and within the
 * bytes, every string NUL-terminated with no NUL before its end, no byte left
 * over. Only scratch structs of the type's own size are allocated, never a size
 * read from the message. Returns 0 when it is; otherwise -1 and, when
 * error is not NULL, a one-line reason naming the field ("reply_t.reports[0]
 * .defect_a: 40 values need 160 bytes, 12 left") in error[0 .. error_size). */
int mt_msgs_check(const mt_msgs_type *type, const void *buf, size_t size, char *error,
                  size_t error_size);

/* mt_msgs_check, then the generated decoder into *out_msg (a meshtopo_NAME_t
 * of `type`). Returns 0 on success: the caller then owns out_msg's arrays and
 * strings and must release them with type->decode_cleanup(out_msg) (the same
 * as meshtopo_NAME_t_decode_cleanup). Returns -1 with the reason in error
 * (as mt_msgs_check) on failure: out_msg is then zeroed and owns nothing, so
 * there is nothing to clean up. */
int mt_msgs_decode(const mt_msgs_type *type, const void *buf, size_t size, void *out_msg,
                   char *error, size_t error_size);

/* Bytes of one element of a primitive field type, the same encoded and in the
 * generated C struct (lcm-gen maps boolean and byte to one-byte types); 0 for
 * strings and nested types. */
size_t mt_msgs_field_width(lcm_field_type_t type);

#ifdef __cplusplus
}
#endif

#endif
