/* Paths of what is installed with this program (the message jar, the
 * archive commands' module): relative to the directory of /proc/self/exe,
 * the same in the build tree and wherever the tree is installed. */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

bool cli_beside_program(const char *relative, char *out, size_t size)
{
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) return false;
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (!slash) return false;
    *slash = '\0';
    int len = snprintf(out, size, "%s/%s", exe, relative);
    return len > 0 && (size_t)len < size;
}
