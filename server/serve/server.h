/*
 * serve/server.h — lumo-server's event loop (docs/server.md "lumo-server"):
 * one thread, one epoll set, any number of clients and packages.
 *
 * Listeners: a TCP one (frames of docs/protocol.md; a refused frame ends the
 * client) and optionally a "serial" one: TCP connections that carry a raw
 * serial line (same frames; the receive side resynchronises after garbage,
 * and --loss damages frames on the way out to exercise the client's
 * resynchronisation); with --usb, USB devices too (serve/usb.h: a bridge
 * per device hands the loop a socket, served like a TCP client). Every connection is a serve/conn.h; the loop reads,
 * pumps and times them out. SIGINT / SIGTERM: stop accepting and reading,
 * finish the queued output until the drain deadline, close, return.
 */
#ifndef SRV_SERVE_SERVER_H
#define SRV_SERVE_SERVER_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"
#include "serve/conn.h"
#include "serve/index.h"
#include "serve/link.h"

#define SRV_DEFAULT_LISTEN    "127.0.0.1:7420"
#define SRV_DEFAULT_IDLE_S    30u
#define SRV_DEFAULT_MAX       1024u
#define SRV_DRAIN_MS          2000u
#define SRV_SNDBUF            (256 << 10)   /* kernel send buffer per client (SO_SNDBUF) */

typedef struct srv_serve_options {
    const char *listen;         /* "ADDR:PORT" (PORT 0: any free port) */
    const char *serial_listen;  /* or NULL */
    double      rate_kbit;      /* per connection, kbit/s; 0: unlimited */
    uint32_t    latency_ms;
    double      loss;           /* serial listener: per frame, 0..1 */
    uint64_t    seed;           /* of the loss */
    uint32_t    max_clients;
    uint32_t    idle_timeout_s;
    uint32_t    drain_ms;
    int         quiet;          /* no per-client lines */
    const char *port_file;      /* write "TCP_PORT SERIAL_PORT\n" once listening */
    int         usb;            /* also serve USB devices (serve/usb.h) */
    int         usb_any;        /* of any VID:PID, else usb_vid:usb_pid */
    uint16_t    usb_vid, usb_pid;
} srv_serve_options;

typedef struct srv_heap {
    srv_conn **a;
    size_t     n, cap;
} srv_heap;

struct srv_serve {
    srv_pkg          *pkgs;
    uint32_t          npkgs;
    srv_serve_options opt;
    srv_link_config   link, serial_link;
    int64_t           idle_us;

    int               epfd, sigfd;
    int               lfd[2];       /* TCP, serial (-1: none) */
    unsigned          port[2];
    srv_conn         *conns;        /* every open connection */
    uint32_t          nconns;
    uint64_t          next_id, served, refused;
    srv_heap          timers;       /* connections waiting for a time */
    struct srv_usb   *usb;          /* the USB watcher (--usb), or NULL */
    int               draining;
    int64_t           drain_deadline_us;
};

/* Serve the packages until SIGINT or SIGTERM. LUMO_ERR_IO (with err) when a
 * listener cannot be set up; LUMO_OK after a drain. */
lumo_status srv_serve_run(srv_pkg *pkgs, uint32_t npkgs, const srv_serve_options *opt, char *err,
                          size_t errlen);

/* Monotonic clock in microseconds. */
int64_t srv_now_us(void);
/* A line on stderr with the program's prefix (not under --quiet unless
 * always is set). */
void srv_log(const srv_serve *s, int always, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

#endif
