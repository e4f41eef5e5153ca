/* Replays fuzz inputs without libFuzzer: links with one fuzz_*.c and feeds
 * LLVMFuzzerTestOneInput every file named on the command line (a directory:
 * every regular file in it, in name order), each in a buffer of exactly its
 * size so sanitizers see any overrun. Used by the fuzz_regressions.* ctests;
 * fails when an input fails or when there is no input at all. */
#include <dirent.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Reads a whole file into a malloc'd buffer of exactly its size (one byte for
 * an empty file). Returns NULL with a message on failure. */
static uint8_t *read_file(const char *path, size_t *out_size)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "replay: cannot open %s: %s\n", path, strerror(errno));
        return NULL;
    }
    size_t size = 0, capacity = 4096;
    uint8_t *buf = malloc(capacity);
    while (buf) {
        size_t got = fread(buf + size, 1, capacity - size, f);
        size += got;
        if (got == 0) break;
        if (size == capacity) {
            uint8_t *bigger = realloc(buf, capacity * 2);
            if (!bigger) free(buf);
            buf = bigger;
            capacity *= 2;
        }
    }
    int failed = !buf || ferror(f);
    fclose(f);
    if (failed) {
        fprintf(stderr, "replay: cannot read %s\n", path);
        free(buf);
        return NULL;
    }
    /* Shrink to the exact size so a read past the end is caught. */
    uint8_t *exact = malloc(size ? size : 1);
    if (!exact) {
        free(buf);
        return NULL;
    }
    memcpy(exact, buf, size);
    free(buf);
    *out_size = size;
    return exact;
}

static int replay_file(const char *path)
{
    size_t size = 0;
    uint8_t *data = read_file(path, &size);
    if (!data) return 1;
    fprintf(stderr, "replay: %s (%zu bytes)\n", path, size);
    LLVMFuzzerTestOneInput(data, size);
    free(data);
    return 0;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Replays every regular file of a directory in name order; adds to *count. */
static int replay_dir(const char *dir, size_t *count)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "replay: cannot open directory %s: %s\n", dir, strerror(errno));
        return 1;
    }
    char **paths = NULL;
    size_t num_paths = 0, capacity = 0;
    int failures = 0;
    struct dirent *entry;
    while ((entry = readdir(d)) != NULL) {
        size_t len = strlen(dir) + strlen(entry->d_name) + 2;
        char *path = malloc(len);
        if (!path) {
            failures++;
            break;
        }
        snprintf(path, len, "%s/%s", dir, entry->d_name);
        struct stat st;
        if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) {
            free(path);
            continue;
        }
        if (num_paths == capacity) {
            size_t bigger = capacity ? 2 * capacity : 64;
            char **grown = realloc(paths, bigger * sizeof *grown);
            if (!grown) {
                free(path);
                failures++;
                break;
            }
            paths = grown;
            capacity = bigger;
        }
        paths[num_paths++] = path;
    }
    closedir(d);
    if (num_paths > 0) qsort(paths, num_paths, sizeof *paths, compare_names);
    for (size_t i = 0; i < num_paths; i++) {
        failures += replay_file(paths[i]);
        free(paths[i]);
    }
    free(paths);
    *count += num_paths;
    return failures;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s FILE_OR_DIRECTORY...\n", argv[0]);
        return 2;
    }
    size_t count = 0;
    int failures = 0;
    for (int i = 1; i < argc; i++) {
        struct stat st;
        if (stat(argv[i], &st) == 0 && S_ISDIR(st.st_mode)) {
            failures += replay_dir(argv[i], &count);
        } else {
            failures += replay_file(argv[i]);
            count++;
        }
    }
    if (count == 0) {
        fprintf(stderr, "replay: no input found\n");
        return 1;
    }
    fprintf(stderr, "replay: %zu inputs, %d could not be read\n", count, failures);
    return failures ? 1 : 0;
}
