/*
 * link_tcp.c — lumo-client's socket links: a TCP connection to lumo-server
 * (reliable: a refused frame ends the conversation; a dropped connection is
 * opened again and resumed), and a serial line carried over TCP, as
 * `lumo-server --serial-listen` serves it (lossy: bytes may be lost or
 * damaged on the way, the conversation resynchronises, docs/protocol.md §1
 * and "Transports").
 */
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include "../../net/host/net_socket.h"
#include "client.h"

static int tcp_open(client_link *l)
{
    l->fd = host_net_connect(l->target, l->err, sizeof l->err);
    return l->fd < 0 ? -1 : 0;
}

static int tcp_send(client_link *l, const uint8_t *p, size_t n)
{
    if (l->fd < 0 || host_net_write_all(l->fd, p, n)) {
        snprintf(l->err, sizeof l->err, "send: %s", l->fd < 0 ? "not connected" : strerror(errno));
        return -1;
    }
    l->bytes_out += n;
    return 0;
}

static long tcp_read(client_link *l, uint8_t *buf, size_t cap, int timeout_ms)
{
    struct pollfd pfd;
    ssize_t n;
    int r;

    pfd.fd = l->fd, pfd.events = POLLIN, pfd.revents = 0;
    do
        r = poll(&pfd, 1, timeout_ms);
    while (r < 0 && errno == EINTR);
    if (r == 0)
        return LINK_TIMEOUT;
    do
        n = read(l->fd, buf, cap);
    while (n < 0 && errno == EINTR);
    if (n < 0) {
        snprintf(l->err, sizeof l->err, "%s", strerror(errno));
        return LINK_ERROR;
    }
    l->bytes_in += (uint64_t)n;
    return (long)n;
}

static void tcp_close(client_link *l)
{
    if (l->fd >= 0)
        close(l->fd);
    l->fd = -1;
}

const link_ops link_tcp = {"tcp", 0, 1, tcp_open, tcp_send, tcp_read, tcp_close};
const link_ops link_serial = {"serial", 1, 1, tcp_open, tcp_send, tcp_read, tcp_close};
