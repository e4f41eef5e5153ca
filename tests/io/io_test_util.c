/* Helpers shared by the meshtopo::io tests (see io_test_util.h). */
#include "io_test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness.h"

#define MAX_PATHS 256

static char dir[64];
static char *paths[MAX_PATHS];
static int num_paths;

static void cleanup(void)
{
    for (int i = 0; i < num_paths; i++) {
        unlink(paths[i]);
        free(paths[i]);
    }
    if (dir[0]) rmdir(dir);
}

const char *io_test_path(const char *name)
{
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/meshtopo-io-test.XXXXXX");
        if (!mkdtemp(dir)) {
            mt_test_fail(__FILE__, __LINE__, "mkdtemp failed");
            snprintf(dir, sizeof dir, "/tmp");
        }
        atexit(cleanup);
    }
    size_t n = strlen(dir) + strlen(name) + 2;
    char *p = malloc(n);
    if (!p || num_paths == MAX_PATHS) {
        mt_test_fail(__FILE__, __LINE__, "too many temporary paths");
        free(p);
        return "/nonexistent/meshtopo-io-test";
    }
    snprintf(p, n, "%s/%s", dir, name);
    paths[num_paths++] = p;
    return p;
}

int io_test_slurp(const char *path, unsigned char **data, size_t *size)
{
    *data = NULL;
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    size_t cap = 1 << 16, len = 0;
    unsigned char *buf = malloc(cap);
    while (buf) {
        if (len == cap) {
            unsigned char *p = realloc(buf, cap * 2);
            if (!p) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = p;
            cap *= 2;
        }
        size_t k = fread(buf + len, 1, cap - len, f);
        if (k == 0) break;
        len += k;
    }
    fclose(f);
    if (!buf) return 0;
    *data = buf;
    *size = len;
    return 1;
}

int io_test_spill(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    int ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

mt_status io_test_read_text(const char *text, mt_format format, const char *name, mt_face_list *out,
                            mt_diag *diag)
{
    return mt_read_memory(text, strlen(text), format, name, out, diag);
}

void io_test_check_same(const mt_face_list *a, const mt_face_list *b, const char *what)
{
    if (a->num_verts != b->num_verts || a->num_faces != b->num_faces ||
        a->num_indices != b->num_indices) {
        mt_test_fail(__FILE__, __LINE__, "%s: counts differ: V %u/%u F %u/%u I %llu/%llu", what,
                     a->num_verts, b->num_verts, a->num_faces, b->num_faces,
                     (unsigned long long)a->num_indices, (unsigned long long)b->num_indices);
        return;
    }
    for (uint32_t f = 0; f < a->num_faces; f++) {
        if (a->face_sizes[f] != b->face_sizes[f]) {
            mt_test_fail(__FILE__, __LINE__, "%s: face %u has size %u vs %u", what, f,
                         a->face_sizes[f], b->face_sizes[f]);
            return;
        }
    }
    for (uint64_t k = 0; k < a->num_indices; k++) {
        if (a->face_indices[k] != b->face_indices[k]) {
            mt_test_fail(__FILE__, __LINE__, "%s: index %llu is %u vs %u", what,
                         (unsigned long long)k, a->face_indices[k], b->face_indices[k]);
            return;
        }
    }
    for (uint64_t k = 0; k < 3ull * a->num_verts; k++) {
        double x = a->positions ? a->positions[k] : 0.0;
        double y = b->positions ? b->positions[k] : 0.0;
        if (memcmp(&x, &y, sizeof x) != 0) {
            mt_test_fail(__FILE__, __LINE__, "%s: coordinate %llu is %.17g vs %.17g", what,
                         (unsigned long long)k, x, y);
            return;
        }
    }
}

void io_test_expect_parse_error_at(const char *file, int line_no, const void *data, size_t size,
                                   mt_format format, const char *name, uint64_t line,
                                   uint64_t offset, const char *fragment)
{
    mt_face_list list;
    memset(&list, 0xab, sizeof list);
    mt_diag diag;
    mt_status status = mt_read_memory(data, size, format, name, &list, &diag);
    if (status != MT_ERR_PARSE) {
        mt_test_fail(file, line_no, "expected MT_ERR_PARSE, got %d (%s): %s", (int)status,
                     mt_strerror(status), status == MT_OK ? "" : diag.message);
        if (status == MT_OK) mt_face_list_free(&list);
        return;
    }
    if (list.num_verts || list.num_faces || list.num_indices || list.positions || list.face_sizes ||
        list.face_indices)
        mt_test_fail(file, line_no, "the output list is not zeroed after a failure");
    if (diag.status != MT_ERR_PARSE) mt_test_fail(file, line_no, "diag.status is not set");
    char where[160];
    if (line > 0) {
        snprintf(where, sizeof where, "%s:%llu: ", name, (unsigned long long)line);
        if (diag.line != line)
            mt_test_fail(file, line_no, "diag.line is %llu, expected %llu (%s)",
                         (unsigned long long)diag.line, (unsigned long long)line, diag.message);
    } else if (offset == UINT64_MAX) {
        snprintf(where, sizeof where, "%s: byte offset ", name);
        if (diag.byte_offset == UINT64_MAX || diag.line != 0)
            mt_test_fail(file, line_no, "diag.byte_offset is not set, or diag.line is (%s)",
                         diag.message);
    } else {
        snprintf(where, sizeof where, "%s: byte offset %llu: ", name, (unsigned long long)offset);
        if (diag.byte_offset != offset)
            mt_test_fail(file, line_no, "diag.byte_offset is %llu, expected %llu (%s)",
                         (unsigned long long)diag.byte_offset, (unsigned long long)offset,
                         diag.message);
    }
    if (strncmp(diag.message, where, strlen(where)) != 0)
        mt_test_fail(file, line_no, "message '%s' does not start with '%s'", diag.message, where);
    if (!strstr(diag.message, fragment))
        mt_test_fail(file, line_no, "message '%s' does not contain '%s'", diag.message, fragment);
}
