/* Streaming JSON writer (see json_writer.h): separators, Python-style
 * indentation (one space per level, "[]"/"{}" for empty containers) and
 * RFC 8259 string escaping with UTF-8 validation. */
#include "meshtopo/json_writer.h"

#include <inttypes.h>
#include <math.h>
#include <string.h>

void mt_json_init(mt_json *j, FILE *out)
{
    memset(j, 0, sizeof *j);
    j->out = out;
}

static void newline_indent(mt_json *j, int depth)
{
    if (j->compact) return;
    fputc('\n', j->out);
    for (int i = 0; i < depth; i++) fputc(' ', j->out);
}

/* Positions the output for a value: after its key, or as the next array
 * element, or as the whole document. False (and error set) on misuse. */
static bool value_prefix(mt_json *j)
{
    if (j->error) return false;
    if (j->key_pending) {
        j->key_pending = false;
        return true;
    }
    if (j->depth == 0) return true;
    if (j->is_object[j->depth - 1]) {
        j->error = true; /* a value inside an object needs a key first */
        return false;
    }
    if (j->has_items[j->depth - 1]) fputc(',', j->out);
    j->has_items[j->depth - 1] = true;
    newline_indent(j, j->depth);
    return true;
}

static void container_begin(mt_json *j, bool is_object)
{
    if (!value_prefix(j)) return;
    if (j->depth == MT_JSON_MAX_DEPTH) {
        j->error = true;
        return;
    }
    fputc(is_object ? '{' : '[', j->out);
    j->is_object[j->depth] = is_object;
    j->has_items[j->depth] = false;
    j->depth++;
}

static void container_end(mt_json *j, bool is_object)
{
    if (j->error) return;
    if (j->depth == 0 || j->is_object[j->depth - 1] != is_object || j->key_pending) {
        j->error = true;
        return;
    }
    j->depth--;
    if (j->has_items[j->depth]) newline_indent(j, j->depth);
    fputc(is_object ? '}' : ']', j->out);
}

void mt_json_object_begin(mt_json *j)
{
    container_begin(j, true);
}
void mt_json_object_end(mt_json *j)
{
    container_end(j, true);
}
void mt_json_array_begin(mt_json *j)
{
    container_begin(j, false);
}
void mt_json_array_end(mt_json *j)
{
    container_end(j, false);
}

void mt_json_key(mt_json *j, const char *key)
{
    if (j->error) return;
    if (j->depth == 0 || !j->is_object[j->depth - 1] || j->key_pending) {
        j->error = true;
        return;
    }
    if (j->has_items[j->depth - 1]) fputc(',', j->out);
    j->has_items[j->depth - 1] = true;
    newline_indent(j, j->depth);
    mt_json_write_escaped(j->out, key);
    fputs(": ", j->out);
    j->key_pending = true;
}

void mt_json_int(mt_json *j, int64_t value)
{
    if (value_prefix(j)) fprintf(j->out, "%" PRId64, value);
}

void mt_json_uint(mt_json *j, uint64_t value)
{
    if (value_prefix(j)) fprintf(j->out, "%" PRIu64, value);
}

void mt_json_double(mt_json *j, double value)
{
    /* JSON has no NaN or infinity: those become null. */
    if (!value_prefix(j)) return;
    if (isfinite(value))
        fprintf(j->out, "%.17g", value);
    else
        fputs("null", j->out);
}

void mt_json_bool(mt_json *j, bool value)
{
    if (value_prefix(j)) fputs(value ? "true" : "false", j->out);
}

void mt_json_null(mt_json *j)
{
    if (value_prefix(j)) fputs("null", j->out);
}

void mt_json_string(mt_json *j, const char *value)
{
    if (value_prefix(j)) mt_json_write_escaped(j->out, value);
}

/* Length of the valid UTF-8 sequence at s (1 to 4), or 0 if s does not start
 * one (stray continuation byte, overlong form, surrogate, past U+10FFFF, or
 * truncated). */
static size_t utf8_sequence_length(const unsigned char *s)
{
    unsigned char c = s[0];
    size_t len;
    unsigned char lo = 0x80, hi = 0xBF; /* allowed range of the second byte */
    if (c >= 0xC2 && c <= 0xDF) {
        len = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
        len = 3;
        if (c == 0xE0) lo = 0xA0; /* overlong */
        if (c == 0xED) hi = 0x9F; /* surrogates */
    } else if (c >= 0xF0 && c <= 0xF4) {
        len = 4;
        if (c == 0xF0) lo = 0x90; /* overlong */
        if (c == 0xF4) hi = 0x8F; /* past U+10FFFF */
    } else {
        return 0;
    }
    if (s[1] < lo || s[1] > hi) return 0;
    for (size_t i = 2; i < len; i++)
        if (s[i] < 0x80 || s[i] > 0xBF) return 0; /* also stops at the NUL */
    return len;
}

void mt_json_write_escaped(FILE *out, const char *text)
{
    const unsigned char *s = (const unsigned char *)text;
    fputc('"', out);
    while (*s) {
        unsigned char c = *s;
        if (c == '"' || c == '\\') {
            fputc('\\', out);
            fputc(c, out);
            s++;
        } else if (c < 0x20) {
            switch (c) {
                case '\n':
                    fputs("\\n", out);
                    break;
                case '\r':
                    fputs("\\r", out);
                    break;
                case '\t':
                    fputs("\\t", out);
                    break;
                case '\b':
                    fputs("\\b", out);
                    break;
                case '\f':
                    fputs("\\f", out);
                    break;
                default:
                    fprintf(out, "\\u%04x", (unsigned)c);
                    break;
            }
            s++;
        } else if (c < 0x80) {
            fputc(c, out);
            s++;
        } else {
            size_t len = utf8_sequence_length(s);
            if (len == 0) {
                fputs("\\ufffd", out);
                s++;
            } else {
                fwrite(s, 1, len, out);
                s += len;
            }
        }
    }
    fputc('"', out);
}

bool mt_json_finish(mt_json *j)
{
    if (j->depth != 0 || j->key_pending) j->error = true;
    fputc('\n', j->out);
    return !j->error;
}
