/* Safe decoding of meshtopo's LCM messages: a walk over the encoded bytes
 * that follows the type's field list (lcm-gen --c-typeinfo) and checks every
 * length before anything is allocated, then the generated decoder. Follows the
 * LCM encoding: an 8-byte big-endian fingerprint, then the fields in order,
 * integers big-endian, strings as an int32 length counting the NUL, then the
 * bytes and the NUL; an array's length is an earlier member of the struct. */
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/msgs.h"

/* Nested types deeper than this are refused (our types nest one level). */
#define MAX_DEPTH 16

/* Where the walk is, for error messages: one frame per nesting level. */
typedef struct walk_frame {
    const struct walk_frame *parent;
    const char *type_name; /* outermost frame only */
    const char *field;     /* field of the parent holding this struct */
    int64_t index;         /* element of that field, -1 for a scalar */
} walk_frame;

typedef struct walk {
    const uint8_t *buf;
    size_t size;
    size_t pos;
    char *error;
    size_t error_size;
} walk;

static void append(char *out, size_t out_size, size_t *len, const char *fmt, ...)
{
    if (*len >= out_size) return;
    va_list args;
    va_start(args, fmt);
    int n = vsnprintf(out + *len, out_size - *len, fmt, args);
    va_end(args);
    if (n > 0) *len += (size_t)n < out_size - *len ? (size_t)n : out_size - *len;
}

static void append_path(char *out, size_t out_size, size_t *len, const walk_frame *frame)
{
    if (frame->parent == NULL) {
        append(out, out_size, len, "%s", frame->type_name);
        return;
    }
    append_path(out, out_size, len, frame->parent);
    append(out, out_size, len, ".%s", frame->field);
    if (frame->index >= 0) append(out, out_size, len, "[%lld]", (long long)frame->index);
}

/* Records "TYPE.path.FIELD: reason" in the caller's error buffer; returns -1. */
static int fail(walk *w, const walk_frame *frame, const char *field, const char *fmt, ...)
{
    if (w->error == NULL || w->error_size == 0) return -1;
    size_t len = 0;
    w->error[0] = '\0';
    append_path(w->error, w->error_size, &len, frame);
    if (field) append(w->error, w->error_size, &len, ".%s", field);
    append(w->error, w->error_size, &len, ": ");
    if (len < w->error_size) {
        va_list args;
        va_start(args, fmt);
        vsnprintf(w->error + len, w->error_size - len, fmt, args);
        va_end(args);
    }
    return -1;
}

static size_t bytes_left(const walk *w)
{
    return w->size - w->pos;
}

static uint64_t read_be(const uint8_t *p, size_t width)
{
    uint64_t v = 0;
    for (size_t i = 0; i < width; i++) v = (v << 8) | p[i];
    return v;
}

size_t mt_msgs_field_width(lcm_field_type_t type)
{
    switch (type) {
        case LCM_FIELD_INT8_T:
        case LCM_FIELD_BYTE:
        case LCM_FIELD_BOOLEAN:
            return 1;
        case LCM_FIELD_INT16_T:
            return 2;
        case LCM_FIELD_INT32_T:
        case LCM_FIELD_FLOAT:
            return 4;
        case LCM_FIELD_INT64_T:
        case LCM_FIELD_DOUBLE:
            return 8;
        case LCM_FIELD_STRING:
        case LCM_FIELD_USER_TYPE:
            return 0;
    }
    return 0;
}

/* Stores a scalar primitive into the scratch struct, so that the array
 * lengths read later through get_field see it. */
static void store_scalar(lcm_field_type_t type, const uint8_t *p, void *dst)
{
    uint64_t v = read_be(p, mt_msgs_field_width(type));
    switch (type) {
        case LCM_FIELD_INT8_T:
        case LCM_FIELD_BOOLEAN: {
            int8_t x = (int8_t)(uint8_t)v;
            memcpy(dst, &x, sizeof x);
            break;
        }
        case LCM_FIELD_BYTE: {
            uint8_t x = (uint8_t)v;
            memcpy(dst, &x, sizeof x);
            break;
        }
        case LCM_FIELD_INT16_T: {
            int16_t x = (int16_t)(uint16_t)v;
            memcpy(dst, &x, sizeof x);
            break;
        }
        case LCM_FIELD_INT32_T:
        case LCM_FIELD_FLOAT: {
            uint32_t x = (uint32_t)v; /* a float is stored as its bits */
            memcpy(dst, &x, sizeof x);
            break;
        }
        case LCM_FIELD_INT64_T:
        case LCM_FIELD_DOUBLE:
            memcpy(dst, &v, sizeof v);
            break;
        case LCM_FIELD_STRING:
        case LCM_FIELD_USER_TYPE:
            break;
    }
}

/* The meshtopo type a nested field names ("topology_t" or
 * "meshtopo.topology_t"); NULL for a type of another package. */
static const mt_msgs_type *type_named(const char *typestr)
{
    const char *prefix = "meshtopo.";
    if (strncmp(typestr, prefix, strlen(prefix)) == 0) typestr += strlen(prefix);
    for (size_t i = 0; i < mt_msgs_num_types; i++)
        if (strcmp(mt_msgs_types[i]->name, typestr) == 0) return mt_msgs_types[i];
    return NULL;
}

static int check_string(walk *w, const walk_frame *frame, const char *field, int64_t index)
{
    char where[64] = "";
    if (index >= 0) snprintf(where, sizeof where, "[%lld]", (long long)index);
    if (bytes_left(w) < 4)
        return fail(w, frame, field, "string%s length needs 4 bytes, %zu left", where,
                    bytes_left(w));
    int32_t length = (int32_t)(uint32_t)read_be(w->buf + w->pos, 4);
    w->pos += 4;
    if (length < 1)
        return fail(w, frame, field, "string%s length %d (it counts the NUL, so at least 1)", where,
                    (int)length);
    if ((uint32_t)length > bytes_left(w))
        return fail(w, frame, field, "string%s of %d bytes, %zu left", where, (int)length,
                    bytes_left(w));
    const uint8_t *s = w->buf + w->pos;
    const uint8_t *nul = memchr(s, 0, (size_t)length);
    if (nul == NULL)
        return fail(w, frame, field, "string%s of %d bytes does not end with a NUL", where,
                    (int)length);
    if (nul != s + length - 1)
        return fail(w, frame, field, "string%s of %d bytes has a NUL at byte %td", where,
                    (int)length, nul - s);
    w->pos += (size_t)length;
    return 0;
}

static int check_struct(walk *w, const mt_msgs_type *type, void *scratch, const walk_frame *frame,
                        int depth);

/* Checks `count` encoded structs of `type`, each walked with a zeroed scratch
 * struct of its own. */
static int check_struct_array(walk *w, const mt_msgs_type *type, int64_t count,
                              const walk_frame *frame, const char *field, int scalar, int depth)
{
    if (depth >= MAX_DEPTH) return fail(w, frame, field, "types nested deeper than %d", MAX_DEPTH);
    void *scratch = calloc(1, type->struct_size ? type->struct_size : 1);
    if (scratch == NULL) return fail(w, frame, field, "out of memory");
    int status = 0;
    for (int64_t i = 0; i < count && status == 0; i++) {
        walk_frame child = {frame, NULL, field, scalar ? -1 : i};
        size_t before = w->pos;
        memset(scratch, 0, type->struct_size);
        status = check_struct(w, type, scratch, &child, depth + 1);
        /* A struct that encodes to no bytes would let a huge count through. */
        if (status == 0 && w->pos == before)
            status = fail(w, frame, field, "element type %s encodes to no bytes", type->name);
    }
    free(scratch);
    return status;
}

static int check_field(walk *w, const mt_msgs_type *type, void *scratch, int index,
                       const walk_frame *frame, int depth)
{
    lcm_field_t f;
    memset(&f, 0, sizeof f);
    if (type->get_field(scratch, index, &f) != 0)
        return fail(w, frame, NULL, "field %d of %s has no description", index, type->name);

    /* How many values: 1 for a scalar, the product of the dimensions for an
     * array. Dimensions come from members already read into the scratch. */
    if (f.num_dim < 0 || f.num_dim > LCM_TYPE_FIELD_MAX_DIM)
        return fail(w, frame, f.name, "bad dimension count %d", f.num_dim);
    int64_t count = 1;
    for (int d = 0; d < f.num_dim; d++) {
        if (f.dim_size[d] < 0)
            return fail(w, frame, f.name, "negative array length %d", (int)f.dim_size[d]);
        count *= f.dim_size[d];
        if (count > INT32_MAX)
            return fail(w, frame, f.name, "array of more than %d values", (int)INT32_MAX);
    }

    size_t width = mt_msgs_field_width(f.type);
    if (width > 0) {
        if ((uint64_t)count > bytes_left(w) / width)
            return fail(w, frame, f.name, "%lld values need %llu bytes, %zu left", (long long)count,
                        (unsigned long long)count * width, bytes_left(w));
        if (f.num_dim == 0) store_scalar(f.type, w->buf + w->pos, f.data);
        w->pos += (size_t)count * width;
        return 0;
    }
    if (f.type == LCM_FIELD_STRING) {
        /* Each string takes at least 5 bytes (length and NUL). */
        if ((uint64_t)count > bytes_left(w) / 5)
            return fail(w, frame, f.name, "%lld strings cannot fit in %zu bytes", (long long)count,
                        bytes_left(w));
        for (int64_t i = 0; i < count; i++)
            if (check_string(w, frame, f.name, f.num_dim == 0 ? -1 : i) != 0) return -1;
        return 0;
    }
    if (f.type == LCM_FIELD_USER_TYPE) {
        const mt_msgs_type *nested = type_named(f.typestr);
        if (nested == NULL) return fail(w, frame, f.name, "unknown type %s", f.typestr);
        if ((uint64_t)count > bytes_left(w))
            return fail(w, frame, f.name, "%lld structs cannot fit in %zu bytes", (long long)count,
                        bytes_left(w));
        return check_struct_array(w, nested, count, frame, f.name, f.num_dim == 0, depth);
    }
    return fail(w, frame, f.name, "unsupported field type %d", (int)f.type);
}

static int check_struct(walk *w, const mt_msgs_type *type, void *scratch, const walk_frame *frame,
                        int depth)
{
    for (int i = 0, n = type->num_fields(); i < n; i++)
        if (check_field(w, type, scratch, i, frame, depth) != 0) return -1;
    return 0;
}

const mt_msgs_type *mt_msgs_type_of(const void *buf, size_t size)
{
    /* Every fingerprint is computed, whatever the bytes (see msgs.h, Threads). */
    int have_fingerprint = buf != NULL && size >= 8;
    int64_t fingerprint = have_fingerprint ? (int64_t)read_be(buf, 8) : 0;
    const mt_msgs_type *found = NULL;
    for (size_t i = 0; i < mt_msgs_num_types; i++)
        if (mt_msgs_types[i]->fingerprint() == fingerprint && have_fingerprint)
            found = mt_msgs_types[i];
    return found;
}

int mt_msgs_check(const mt_msgs_type *type, const void *buf, size_t size, char *error,
                  size_t error_size)
{
    walk w = {buf, size, 0, error, error_size};
    walk_frame top = {NULL, type->name, NULL, -1};
    if (error && error_size) error[0] = '\0';
    if (size > INT_MAX) return fail(&w, &top, NULL, "%zu bytes is more than LCM can decode", size);
    if (buf == NULL && size > 0) return fail(&w, &top, NULL, "no buffer");
    if (size < 8) return fail(&w, &top, NULL, "%zu bytes, shorter than a fingerprint", size);
    int64_t fingerprint = (int64_t)read_be(buf, 8);
    if (fingerprint != type->fingerprint()) {
        const mt_msgs_type *other = mt_msgs_type_of(buf, size);
        if (other)
            return fail(&w, &top, NULL, "wrong fingerprint: the bytes are a %s", other->name);
        return fail(&w, &top, NULL, "wrong fingerprint 0x%016llx, not a meshtopo type",
                    (unsigned long long)fingerprint);
    }
    w.pos = 8;
    void *scratch = calloc(1, type->struct_size ? type->struct_size : 1);
    if (scratch == NULL) return fail(&w, &top, NULL, "out of memory");
    int status = check_struct(&w, type, scratch, &top, 0);
    free(scratch);
    if (status != 0) return -1;
    if (w.pos != size)
        return fail(&w, &top, NULL, "%zu bytes after the end of the message", size - w.pos);
    return 0;
}

int mt_msgs_decode(const mt_msgs_type *type, const void *buf, size_t size, void *out_msg,
                   char *error, size_t error_size)
{
    memset(out_msg, 0, type->struct_size);
    if (mt_msgs_check(type, buf, size, error, error_size) != 0) return -1;
    int used = type->decode(buf, 0, (int)size, out_msg);
    if (used != (int)size) {
        /* Cannot happen when the check above is right; the partly decoded
         * struct may hold uninitialised pointers, so it is dropped, not freed. */
        memset(out_msg, 0, type->struct_size);
        if (error && error_size)
            snprintf(error, error_size, "%s: the LCM decoder refused a checked message (%d)",
                     type->name, used);
        return -1;
    }
    return 0;
}
