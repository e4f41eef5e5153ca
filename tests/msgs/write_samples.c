/* Writes every sample message (msgs_samples.c), encoded by the generated C
 * code, into DIR as NAME.TYPE.lcmbin, and the list of all meshtopo types into
 * DIR/types.txt: the input of the Java round trip (MsgsRoundTrip.java).
 * usage: msgs_write_samples DIR */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "msgs_samples.h"

static int write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL) {
        perror(path);
        return -1;
    }
    int ok = fwrite(data, 1, size, f) == size;
    ok = (fclose(f) == 0) && ok;
    if (!ok) fprintf(stderr, "msgs_write_samples: cannot write %s\n", path);
    return ok ? 0 : -1;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    char path[4096];
    char types[1024] = "";
    for (size_t t = 0; t < mt_msgs_num_types; t++) {
        strncat(types, mt_msgs_types[t]->name, sizeof types - strlen(types) - 2);
        strcat(types, "\n");
    }
    snprintf(path, sizeof path, "%s/types.txt", argv[1]);
    if (write_file(path, types, strlen(types)) != 0) return 1;

    for (size_t i = 0; i < mt_msgs_num_samples; i++) {
        const mt_msgs_sample *sample = &mt_msgs_samples[i];
        uint8_t msg[1024]; /* room for any meshtopo_*_t struct */
        if (sample->type->struct_size > sizeof msg) return 1;
        memset(msg, 0, sizeof msg);
        sample->fill(msg);
        size_t size = 0;
        uint8_t *buf = mt_msgs_encode_alloc(sample->type, msg, &size);
        if (buf == NULL) {
            fprintf(stderr, "msgs_write_samples: cannot encode %s\n", sample->name);
            return 1;
        }
        snprintf(path, sizeof path, "%s/%s.%s.lcmbin", argv[1], sample->name, sample->type->name);
        int status = write_file(path, buf, size);
        free(buf);
        if (status != 0) return 1;
    }
    printf("wrote %zu samples of %zu types to %s\n", mt_msgs_num_samples, mt_msgs_num_types,
           argv[1]);
    return 0;
}
