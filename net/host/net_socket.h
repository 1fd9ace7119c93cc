/*
 * net_socket.h — the desktop side of the transports (docs/protocol.md):
 * TCP connections and byte pipes (serial lines over TCP, replay files)
 * carrying lumo frames. POSIX; desktop code (not client-rules code).
 */
#ifndef LUMO_NET_SOCKET_H
#define LUMO_NET_SOCKET_H

#include <stddef.h>
#include <stdint.h>

/* Split "HOST:PORT" ("[::1]:PORT" for IPv6). 0 on success. */
int host_net_split(const char *addr, char *host, size_t hostlen, char *port, size_t portlen);

/* A connected TCP socket to "HOST:PORT" (blocking, TCP_NODELAY), or -1
 * with a one-line reason in err. */
int host_net_connect(const char *addr, char *err, size_t errlen);

/* Write all n bytes (retrying on EINTR / short writes). 0 or -1. */
int host_net_write_all(int fd, const uint8_t *p, size_t n);

/* Milliseconds of a monotonic clock (wrapping u32): the protocol driver's
 * clock (lumo_net_clock). */
uint32_t host_net_clock_ms(void *ctx);

#endif
