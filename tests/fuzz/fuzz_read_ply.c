/* libFuzzer target: the PLY reader (every encoding: the header decides) on arbitrary bytes, gzip
 * included; the checks are in fuzz_reader.h. */
#include "fuzz_reader.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return mt_fuzz_reader(data, size, MT_FORMAT_PLY_BINARY_LE, "fuzz.ply");
}
