/*
 * link_tcp.c — the Linux board's link (boards/board.h): a TCP connection to
 * LUMO_LINK=HOST:PORT (lumo-server --serial-listen: a serial line carried
 * over TCP, docs/server.md), connected on first use. Desktop code.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <netdb.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>
#include "board.h"

/* ---- the link: TCP to LUMO_LINK=HOST:PORT, connected on first use ---- */

static int g_link = -2;   /* -2: not tried yet; -1: none */

static int link_connect(const char *spec)
{
    char host[256];
    const char *colon = strrchr(spec, ':');
    struct addrinfo hints, *res, *ai;
    int fd = -1;

    if (colon == NULL || (size_t)(colon - spec) >= sizeof host)
        return -1;
    memcpy(host, spec, (size_t)(colon - spec));
    host[colon - spec] = '\0';
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    if (getaddrinfo(host, colon + 1, &hints, &res) != 0)
        return -1;
    for (ai = res; ai != NULL && fd < 0; ai = ai->ai_next) {
        fd = socket(ai->ai_family, ai->ai_socktype, ai->ai_protocol);
        if (fd >= 0 && connect(fd, ai->ai_addr, ai->ai_addrlen) != 0) {
            close(fd);
            fd = -1;
        }
    }
    freeaddrinfo(res);
    return fd;
}

static int link_fd(void)
{
    const char *spec;

    if (g_link == -2) {
        spec = getenv("LUMO_LINK");
        g_link = spec ? link_connect(spec) : -1;
        if (g_link < 0)
            fprintf(stderr, "board: no link (LUMO_LINK=%s)\n", spec ? spec : "unset");
    }
    return g_link;
}

int board_link_write(const uint8_t *buf, size_t n)
{
    int fd = link_fd();

    while (fd >= 0 && n > 0) {
        ssize_t k = send(fd, buf, n, MSG_NOSIGNAL);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        buf += k;
        n -= (size_t)k;
    }
    return fd >= 0 ? 0 : -1;
}

int32_t board_link_read(uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    struct pollfd p;
    ssize_t k;
    int fd = link_fd(), r;

    if (fd < 0)
        return -1;
    if (cap > 0x7fffffffu)
        cap = 0x7fffffffu;
    p.fd = fd;
    p.events = POLLIN;
    do
        r = poll(&p, 1, timeout_ms > 0x7fffffffu ? 0x7fffffff : (int)timeout_ms);
    while (r < 0 && errno == EINTR);
    if (r <= 0)
        return r == 0 ? 0 : -1;
    do
        k = read(fd, buf, cap);
    while (k < 0 && errno == EINTR);
    return k > 0 ? (int32_t)k : -1;
}
