/* A private network namespace for `meshtopo-bench rtt`: the same setup as
 * tests/netns/netns-run (lo up with multicast, route 224.0.0.0/4 dev lo), done
 * in-process so that the benchmark needs no script or `ip` binary. The two
 * ioctls are all it takes; a netlink library would add a dependency for two
 * requests. Nothing is configured unless the namespace is new: the host's
 * interfaces and routes are never touched. */
#define _GNU_SOURCE /* unshare, CLONE_NEWNET */
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <net/if.h>
#include <net/route.h>
#include <netinet/in.h>
#include <sched.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include "rtt.h"

enum { SKIP = 77 };

static bool write_file(const char *path, const char *text)
{
    int fd = open(path, O_WRONLY | O_CLOEXEC);
    if (fd < 0) return false;
    size_t len = strlen(text);
    bool ok = write(fd, text, len) == (ssize_t)len;
    return close(fd) == 0 && ok;
}

/* Unshares the network namespace: directly as root, else inside a new user
 * namespace that maps the caller to root (as `unshare -rn`). */
static int unshare_network(char *err, size_t err_size)
{
    if (unshare(CLONE_NEWNET) == 0) return 0;
    int first = errno;
    uid_t uid = getuid();
    gid_t gid = getgid();
    if (unshare(CLONE_NEWUSER | CLONE_NEWNET) != 0) {
        snprintf(err, err_size, "cannot make a private network namespace: %s (as root), %s (user)",
                 strerror(first), strerror(errno));
        return SKIP;
    }
    char map[64];
    snprintf(map, sizeof map, "0 %u 1\n", (unsigned)uid);
    bool ok = write_file("/proc/self/uid_map", map) && write_file("/proc/self/setgroups", "deny");
    snprintf(map, sizeof map, "0 %u 1\n", (unsigned)gid);
    ok = ok && write_file("/proc/self/gid_map", map);
    if (!ok) {
        snprintf(err, err_size, "cannot map the user into the new namespace: %s", strerror(errno));
        return SKIP;
    }
    return 0;
}

int mt__rtt_enter_private_network(char *err, size_t err_size)
{
    struct stat before, after;
    if (stat("/proc/self/ns/net", &before) != 0) {
        snprintf(err, err_size, "cannot read /proc/self/ns/net: %s", strerror(errno));
        return SKIP;
    }
    int code = unshare_network(err, err_size);
    if (code != 0) return code;
    if (stat("/proc/self/ns/net", &after) != 0 || after.st_ino == before.st_ino) {
        snprintf(err, err_size, "refusing to set up the network: not in a new namespace");
        return 1;
    }

    int sock = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (sock < 0) {
        snprintf(err, err_size, "socket: %s", strerror(errno));
        return 1;
    }
    struct ifreq ifr;
    memset(&ifr, 0, sizeof ifr);
    snprintf(ifr.ifr_name, sizeof ifr.ifr_name, "lo");
    if (ioctl(sock, SIOCGIFFLAGS, &ifr) != 0) {
        snprintf(err, err_size, "reading the flags of lo: %s", strerror(errno));
        close(sock);
        return 1;
    }
    ifr.ifr_flags |= IFF_UP | IFF_MULTICAST;
    if (ioctl(sock, SIOCSIFFLAGS, &ifr) != 0) {
        snprintf(err, err_size, "bringing lo up with multicast: %s", strerror(errno));
        close(sock);
        return 1;
    }

    struct rtentry route;
    memset(&route, 0, sizeof route);
    struct sockaddr_in *dst = (struct sockaddr_in *)&route.rt_dst;
    struct sockaddr_in *mask = (struct sockaddr_in *)&route.rt_genmask;
    dst->sin_family = AF_INET;
    dst->sin_addr.s_addr = htonl(0xe0000000u); /* 224.0.0.0 */
    mask->sin_family = AF_INET;
    mask->sin_addr.s_addr = htonl(0xf0000000u); /* /4 */
    route.rt_flags = RTF_UP;
    char device[] = "lo";
    route.rt_dev = device;
    if (ioctl(sock, SIOCADDRT, &route) != 0) {
        snprintf(err, err_size, "adding the route 224.0.0.0/4 dev lo: %s", strerror(errno));
        close(sock);
        return 1;
    }
    close(sock);
    return 0;
}
