/*
 * server.c — lumo-server's epoll loop: listeners, clients, timers, signals
 * (serve/server.h).
 */
#include "serve/server.h"
#include "common/status_msg.h"
#include "lumo/net_usb.h"
#include "serve/usb.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/resource.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

enum { KIND_CONN = 1, KIND_LISTEN_TCP, KIND_LISTEN_SERIAL, KIND_SIGNAL, KIND_USB };
/* Where a client came from (the listener index, then USB). */
enum { VIA_TCP = 0, VIA_SERIAL = 1, VIA_USB = 2 };

/* Sweep for timeouts this often. */
#define SWEEP_US 200000
#define MAX_EVENTS 128

int64_t srv_now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

void srv_log(const srv_serve *s, int always, const char *fmt, ...)
{
    char line[512];
    va_list ap;

    if (s && s->opt.quiet && !always)
        return;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    fprintf(stderr, "lumo-server: %s\n", line);
}

/* ---- the timer heap (connections waiting for a time: latency, rate) ----------- */

static void heap_swap(srv_heap *h, size_t i, size_t j)
{
    srv_conn *t = h->a[i];
    h->a[i] = h->a[j];
    h->a[j] = t;
    h->a[i]->heap_idx = (int)i;
    h->a[j]->heap_idx = (int)j;
}

static void heap_up(srv_heap *h, size_t i)
{
    while (i > 0 && h->a[(i - 1) / 2]->wake_us > h->a[i]->wake_us) {
        heap_swap(h, i, (i - 1) / 2);
        i = (i - 1) / 2;
    }
}

static void heap_down(srv_heap *h, size_t i)
{
    for (;;) {
        size_t l = 2 * i + 1, r = l + 1, m = i;
        if (l < h->n && h->a[l]->wake_us < h->a[m]->wake_us)
            m = l;
        if (r < h->n && h->a[r]->wake_us < h->a[m]->wake_us)
            m = r;
        if (m == i)
            return;
        heap_swap(h, i, m);
        i = m;
    }
}

static void heap_remove(srv_heap *h, srv_conn *c)
{
    size_t i = (size_t)c->heap_idx;

    if (c->heap_idx < 0)
        return;
    c->heap_idx = -1;
    if (i != --h->n) {
        h->a[i] = h->a[h->n];
        h->a[i]->heap_idx = (int)i;
        heap_down(h, i);
        heap_up(h, i);
    }
}

/* Put c in the heap at c->wake_us (out of it when 0). 0 or -1 (no memory:
 * the connection is then served by the sweep, a little late). */
static int heap_set(srv_heap *h, srv_conn *c)
{
    if (!c->wake_us) {
        heap_remove(h, c);
        return 0;
    }
    if (c->heap_idx >= 0) {
        heap_down(h, (size_t)c->heap_idx);
        heap_up(h, (size_t)c->heap_idx);
        return 0;
    }
    if (h->n == h->cap) {
        size_t cap = h->cap ? h->cap * 2 : 64;
        srv_conn **a = realloc(h->a, cap * sizeof *a);
        if (!a)
            return -1;
        h->a = a, h->cap = cap;
    }
    h->a[h->n] = c;
    c->heap_idx = (int)h->n++;
    heap_up(h, (size_t)c->heap_idx);
    return 0;
}

/* ---- listeners ------------------------------------------------------------------- */

static int split_addr(const char *spec, char *host, size_t hostcap, char *port, size_t portcap)
{
    const char *colon = strrchr(spec, ':');
    size_t hl;

    if (!colon || !colon[1] || strlen(colon + 1) >= portcap)
        return -1;
    hl = (size_t)(colon - spec);
    if (hl >= 2 && spec[0] == '[' && spec[hl - 1] == ']')
        spec++, hl -= 2;
    if (hl >= hostcap)
        return -1;
    memcpy(host, spec, hl);
    host[hl] = 0;
    strcpy(port, colon + 1);
    return 0;
}

static int open_listener(const char *spec, unsigned *port_out, char *err, size_t errlen)
{
    char host[256], port[16];
    struct addrinfo hints, *res = NULL, *ai;
    int fd = -1, one = 1, rc;

    if (split_addr(spec, host, sizeof host, port, sizeof port)) {
        srv_fail(err, errlen, LUMO_ERR_IO, "bad address '%s' (want ADDR:PORT, e.g. 127.0.0.1:7420)", spec);
        return -1;
    }
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
    if ((rc = getaddrinfo(host[0] ? host : NULL, port, &hints, &res))) {
        srv_fail(err, errlen, LUMO_ERR_IO, "address '%s': %s", spec, gai_strerror(rc));
        return -1;
    }
    for (ai = res; ai; ai = ai->ai_next) {
        fd = socket(ai->ai_family, ai->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, ai->ai_protocol);
        if (fd < 0)
            continue;
        setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        if (bind(fd, ai->ai_addr, ai->ai_addrlen) == 0 && listen(fd, 4096) == 0)
            break;
        srv_fail(err, errlen, LUMO_ERR_IO, "listen on %s: %s", spec, strerror(errno));
        close(fd);
        fd = -1;
    }
    freeaddrinfo(res);
    if (fd >= 0) {
        struct sockaddr_storage ss;
        socklen_t sl = sizeof ss;
        *port_out = 0;
        if (getsockname(fd, (struct sockaddr *)&ss, &sl) == 0)
            *port_out = ss.ss_family == AF_INET6 ? ntohs(((struct sockaddr_in6 *)&ss)->sin6_port)
                                                 : ntohs(((struct sockaddr_in *)&ss)->sin_port);
    } else if (!ai) {
        if (!err[0])
            srv_fail(err, errlen, LUMO_ERR_IO, "listen on %s: no usable address", spec);
    }
    return fd;
}

static void peer_name(const struct sockaddr_storage *ss, char *out, size_t cap)
{
    char host[INET6_ADDRSTRLEN] = "?";
    unsigned port = 0;

    if (ss->ss_family == AF_INET) {
        const struct sockaddr_in *a = (const struct sockaddr_in *)ss;
        inet_ntop(AF_INET, &a->sin_addr, host, sizeof host);
        port = ntohs(a->sin_port);
        snprintf(out, cap, "%s:%u", host, port);
    } else if (ss->ss_family == AF_INET6) {
        const struct sockaddr_in6 *a = (const struct sockaddr_in6 *)ss;
        inet_ntop(AF_INET6, &a->sin6_addr, host, sizeof host);
        port = ntohs(a->sin6_port);
        snprintf(out, cap, "[%s]:%u", host, port);
    } else {
        snprintf(out, cap, "?");
    }
}

/* ---- connections ----------------------------------------------------------------- */

static void conn_close(srv_serve *s, srv_conn *c, int64_t now)
{
    char line[480];

    srv_conn_summary(c, now, line, sizeof line);
    srv_log(s, 0, "%s", line);
    heap_remove(&s->timers, c);
    epoll_ctl(s->epfd, EPOLL_CTL_DEL, c->fd, NULL);
    if (c->abort || c->job_count) {
        /* output left behind: reset, so the kernel drops it now rather
         * than keep it for a peer that does not read */
        struct linger lg = {1, 0};
        setsockopt(c->fd, SOL_SOCKET, SO_LINGER, &lg, sizeof lg);
    }
    close(c->fd);
    if (c->prev)
        c->prev->next = c->next;
    else
        s->conns = c->next;
    if (c->next)
        c->next->prev = c->prev;
    s->nconns--;
    srv_conn_free(c);
    free(c);
}

/* After anything happened to c: close it, or register what it waits for. */
static void conn_settle(srv_serve *s, srv_conn *c, int64_t now)
{
    uint32_t ev;

    if (c->state != SRV_CONN_CLOSED)
        srv_conn_pump(c, now);
    if (c->state == SRV_CONN_CLOSED) {
        conn_close(s, c, now);
        return;
    }
    ev = (c->want_read ? EPOLLIN : 0u) | (c->want_write ? EPOLLOUT : 0u);
    if (ev != c->events) {
        struct epoll_event e;
        e.events = ev;
        e.data.ptr = c;
        epoll_ctl(s->epfd, EPOLL_CTL_MOD, c->fd, &e);
        c->events = ev;
    }
    heap_set(&s->timers, c);
}

/* The ERROR of a full server, written to the fresh socket as it is. */
static void refuse_client(srv_serve *s, int fd, const char *peer)
{
    uint8_t frame[LUMO_NET_OVERHEAD + 8 + 128];
    char text[96];
    size_t n = 0;

    snprintf(text, sizeof text, "server full: %u clients", s->opt.max_clients);
    if (lumo_net_error_encode(LUMO_ERR_LIMIT, text, frame, sizeof frame, &n) == LUMO_OK) {
        ssize_t w = send(fd, frame, n, MSG_NOSIGNAL | MSG_DONTWAIT);
        (void)w;
    }
    close(fd);
    s->refused++;
    srv_log(s, 0, "#- %s: refused: %s", peer, text);
}

/* A connected socket fd (non-blocking) becomes a client: TCP, serial or a
 * USB bridge's (serve/usb.h). */
static void adopt(srv_serve *s, int fd, int via, const char *peer, int64_t now)
{
    struct epoll_event e;
    srv_conn *c;
    int one = 1, sndbuf = SRV_SNDBUF;

    if (s->nconns >= s->opt.max_clients) {
        refuse_client(s, fd, peer);
        return;
    }
    if (!(c = malloc(sizeof *c))) {
        srv_log(s, 1, "%s: out of memory for a client", peer);
        close(fd);
        return;
    }
    if (via != VIA_USB)
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    /* a fixed kernel send buffer: a client that stops reading holds at
     * most this much kernel memory and is found stalled soon */
    setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf);
    srv_conn_init(c, s, fd, via == VIA_SERIAL, ++s->next_id, peer, now);
    c->kind = KIND_CONN;
    c->usb = via == VIA_USB;
    c->events = EPOLLIN;
    e.events = EPOLLIN;
    e.data.ptr = c;
    if (epoll_ctl(s->epfd, EPOLL_CTL_ADD, fd, &e) < 0) {
        srv_log(s, 1, "%s: epoll: %s", peer, strerror(errno));
        close(fd);
        free(c);
        return;
    }
    c->next = s->conns;
    if (s->conns)
        s->conns->prev = c;
    s->conns = c;
    s->nconns++;
    s->served++;
}

static void on_accept(srv_serve *s, int which, int64_t now)
{
    for (;;) {
        struct sockaddr_storage ss;
        socklen_t sl = sizeof ss;
        char peer[64];
        int fd = accept4(s->lfd[which], (struct sockaddr *)&ss, &sl, SOCK_NONBLOCK | SOCK_CLOEXEC);

        if (fd < 0) {
            if (errno == EINTR || errno == ECONNABORTED)
                continue;
            if (errno != EAGAIN && errno != EWOULDBLOCK)
                srv_log(s, 1, "accept: %s", strerror(errno));
            return;
        }
        peer_name(&ss, peer, sizeof peer);
        adopt(s, fd, which, peer, now);
    }
}

/* USB devices found: their bridges' sockets (serve/usb.h). */
static void on_usb(srv_serve *s, int64_t now)
{
    char peer[64];
    int fd;

    while ((fd = srv_usb_take(s->usb, peer, sizeof peer)) >= 0) {
        srv_log(s, 0, "%s: a lumo client, claimed", peer);
        adopt(s, fd, VIA_USB, peer, now);
    }
}

/* ---- the loop ---------------------------------------------------------------------- */

static void start_drain(srv_serve *s, int64_t now)
{
    srv_conn *c, *next;
    int i;

    s->draining = 1;
    s->drain_deadline_us = now + (int64_t)s->opt.drain_ms * 1000;
    for (i = 0; i < 2; i++)
        if (s->lfd[i] >= 0) {
            epoll_ctl(s->epfd, EPOLL_CTL_DEL, s->lfd[i], NULL);
            close(s->lfd[i]);
            s->lfd[i] = -1;
        }
    if (s->usb)
        epoll_ctl(s->epfd, EPOLL_CTL_DEL, srv_usb_event_fd(s->usb), NULL);
    srv_log(s, 1, "shutting down: %u clients, finishing their output (at most %u ms)", s->nconns,
            s->opt.drain_ms);
    for (c = s->conns; c; c = next) {
        next = c->next;
        srv_conn_drain(c, s->drain_deadline_us);
        conn_settle(s, c, now);
    }
}

static void sweep(srv_serve *s, int64_t now)
{
    srv_conn *c, *next;

    for (c = s->conns; c; c = next) {
        srv_conn_state was = c->state;
        next = c->next;
        srv_conn_check_time(c, now, s->idle_us);
        if (c->state != was)
            conn_settle(s, c, now);   /* send the ERROR, or close */
    }
}

static void raise_fd_limit(srv_serve *s)
{
    struct rlimit rl;
    rlim_t need = (rlim_t)s->opt.max_clients + 32;

    if (getrlimit(RLIMIT_NOFILE, &rl) == 0 && rl.rlim_cur < need) {
        rl.rlim_cur = rl.rlim_max == RLIM_INFINITY || rl.rlim_max > need ? need : rl.rlim_max;
        setrlimit(RLIMIT_NOFILE, &rl);
        if (getrlimit(RLIMIT_NOFILE, &rl) == 0 && rl.rlim_cur < need) {
            uint32_t m = rl.rlim_cur > 64 ? (uint32_t)(rl.rlim_cur - 32) : 32;
            srv_log(s, 1, "warning: open file limit %llu: at most %u clients", (unsigned long long)rl.rlim_cur, m);
            s->opt.max_clients = m;
        }
    }
}

static int write_port_file(const srv_serve *s)
{
    FILE *f = fopen(s->opt.port_file, "w");
    if (!f)
        return -1;
    fprintf(f, "%u %u\n", s->port[0], s->port[1]);
    return fclose(f);
}

lumo_status srv_serve_run(srv_pkg *pkgs, uint32_t npkgs, const srv_serve_options *opt, char *err, size_t errlen)
{
    srv_serve s;
    struct epoll_event ev[MAX_EVENTS];
    sigset_t mask, caller_mask;
    int64_t next_sweep;
    int i;
    static int tags[5] = {KIND_CONN, KIND_LISTEN_TCP, KIND_LISTEN_SERIAL, KIND_SIGNAL, KIND_USB};
    lumo_status st = LUMO_OK;

    memset(&s, 0, sizeof s);
    s.pkgs = pkgs;
    s.npkgs = npkgs;
    s.opt = *opt;
    if (!s.opt.listen)
        s.opt.listen = SRV_DEFAULT_LISTEN;
    if (!s.opt.max_clients)
        s.opt.max_clients = SRV_DEFAULT_MAX;
    if (!s.opt.idle_timeout_s)
        s.opt.idle_timeout_s = SRV_DEFAULT_IDLE_S;
    if (!s.opt.drain_ms)
        s.opt.drain_ms = SRV_DRAIN_MS;
    s.idle_us = (int64_t)s.opt.idle_timeout_s * 1000000;
    s.link.rate_bytes = s.opt.rate_kbit * 1000.0 / 8.0;
    s.link.latency_us = (int64_t)s.opt.latency_ms * 1000;
    s.link.seed = s.opt.seed;
    s.serial_link = s.link;
    s.serial_link.loss = s.opt.loss;
    s.lfd[0] = s.lfd[1] = s.sigfd = s.epfd = -1;
    raise_fd_limit(&s);

    signal(SIGPIPE, SIG_IGN);
    sigprocmask(SIG_BLOCK, NULL, &caller_mask);
    sigemptyset(&mask);
    sigaddset(&mask, SIGINT);
    sigaddset(&mask, SIGTERM);
    if (sigprocmask(SIG_BLOCK, &mask, NULL) < 0 || (s.sigfd = signalfd(-1, &mask, SFD_NONBLOCK | SFD_CLOEXEC)) < 0 ||
        (s.epfd = epoll_create1(EPOLL_CLOEXEC)) < 0) {
        st = srv_fail(err, errlen, LUMO_ERR_IO, "event loop: %s", strerror(errno));
        goto out;
    }
    err[0] = 0;
    if ((s.lfd[0] = open_listener(s.opt.listen, &s.port[0], err, errlen)) < 0) {
        st = LUMO_ERR_IO;
        goto out;
    }
    if (s.opt.serial_listen && (s.lfd[1] = open_listener(s.opt.serial_listen, &s.port[1], err, errlen)) < 0) {
        st = LUMO_ERR_IO;
        goto out;
    }
    for (i = 0; i < 2; i++) {
        struct epoll_event e;
        if (s.lfd[i] < 0)
            continue;
        e.events = EPOLLIN;
        e.data.ptr = &tags[i + 1];
        epoll_ctl(s.epfd, EPOLL_CTL_ADD, s.lfd[i], &e);
    }
    {
        struct epoll_event e;
        e.events = EPOLLIN;
        e.data.ptr = &tags[3];
        epoll_ctl(s.epfd, EPOLL_CTL_ADD, s.sigfd, &e);
    }
    if (s.opt.usb) {
        struct epoll_event e;
        if ((st = srv_usb_start(&s.usb, s.opt.usb_any, s.opt.usb_vid, s.opt.usb_pid, err, errlen)))
            goto out;
        e.events = EPOLLIN;
        e.data.ptr = &tags[4];
        epoll_ctl(s.epfd, EPOLL_CTL_ADD, srv_usb_event_fd(s.usb), &e);
    }
    for (i = 0; i < (int)npkgs; i++)
        srv_log(&s, 1, "package %d: %s (%u meshes, %s, %zu bytes, id %08x)", i, pkgs[i].path, pkgs[i].mesh_count,
                pkgs[i].ivg.present ? "IVG" : "no IVG", pkgs[i].size, pkgs[i].id);
    srv_log(&s, 1, "listening on %s (tcp port %u), at most %u clients, idle timeout %u s", s.opt.listen, s.port[0],
            s.opt.max_clients, s.opt.idle_timeout_s);
    if (s.lfd[1] >= 0)
        srv_log(&s, 1, "serial line on %s (tcp port %u): resynchronised after garbage", s.opt.serial_listen,
                s.port[1]);
    if (s.usb) {
        if (s.opt.usb_any)
            srv_log(&s, 1, "USB: every device with a lumo interface (class %02x/%02x/%02x)", LUMO_USB_CLASS,
                    LUMO_USB_SUBCLASS, LUMO_USB_PROTOCOL);
        else
            srv_log(&s, 1, "USB: devices %04x:%04x with a lumo interface", s.opt.usb_vid, s.opt.usb_pid);
    }
    if (s.link.rate_bytes > 0 || s.link.latency_us || s.serial_link.loss > 0)
        srv_log(&s, 1, "link emulation per client: rate %g kbit/s, latency %u ms, serial loss %g per frame (seed %llu)",
                s.opt.rate_kbit, s.opt.latency_ms, s.opt.loss, (unsigned long long)s.opt.seed);
    if (s.opt.port_file && write_port_file(&s)) {
        st = srv_fail(err, errlen, LUMO_ERR_IO, "%s: %s", s.opt.port_file, strerror(errno));
        goto out;
    }

    next_sweep = srv_now_us() + SWEEP_US;
    for (;;) {
        int64_t now = srv_now_us(), until = next_sweep;
        int n, timeout_ms;

        if (s.draining && (!s.conns || now >= s.drain_deadline_us))
            break;
        if (s.timers.n && s.timers.a[0]->wake_us < until)
            until = s.timers.a[0]->wake_us;
        if (s.draining && s.drain_deadline_us < until)
            until = s.drain_deadline_us;
        timeout_ms = until <= now ? 0 : (int)((until - now + 999) / 1000);
        n = epoll_wait(s.epfd, ev, MAX_EVENTS, timeout_ms);
        if (n < 0 && errno != EINTR) {
            st = srv_fail(err, errlen, LUMO_ERR_IO, "epoll_wait: %s", strerror(errno));
            break;
        }
        now = srv_now_us();
        for (i = 0; i < n; i++) {
            int kind = *(int *)ev[i].data.ptr;
            if (kind == KIND_LISTEN_TCP || kind == KIND_LISTEN_SERIAL) {
                if (!s.draining)
                    on_accept(&s, kind == KIND_LISTEN_SERIAL, now);
            } else if (kind == KIND_USB) {
                if (!s.draining)
                    on_usb(&s, now);
            } else if (kind == KIND_SIGNAL) {
                struct signalfd_siginfo si;
                while (read(s.sigfd, &si, sizeof si) == (ssize_t)sizeof si) {
                    if (s.draining) {
                        srv_log(&s, 1, "second signal: closing now");
                        s.drain_deadline_us = now;
                    } else {
                        start_drain(&s, now);
                    }
                }
            } else {
                srv_conn *c = ev[i].data.ptr;
                if (ev[i].events & (EPOLLIN | EPOLLHUP | EPOLLERR))
                    srv_conn_on_readable(c, now);
                if (ev[i].events & (EPOLLHUP | EPOLLERR))
                    srv_conn_hangup(c);   /* nothing can be sent any more */
                conn_settle(&s, c, now);
            }
        }
        while (s.timers.n && s.timers.a[0]->wake_us <= now) {
            srv_conn *c = s.timers.a[0];
            heap_remove(&s.timers, c);
            c->wake_us = 0;
            conn_settle(&s, c, now);
        }
        if (now >= next_sweep) {
            sweep(&s, now);
            next_sweep = now + SWEEP_US;
        }
    }
    {
        int64_t now = srv_now_us();
        while (s.conns) {
            srv_conn *c = s.conns;
            if (c->state != SRV_CONN_CLOSED && !c->reason[0])
                snprintf(c->reason, sizeof c->reason, "server shutdown");
            else if (c->state != SRV_CONN_CLOSED && strcmp(c->reason, "server shutdown") == 0)
                snprintf(c->reason, sizeof c->reason, "server shutdown: output cut at the deadline");
            conn_close(&s, c, now);
        }
    }
    if (!st)
        srv_log(&s, 1, "stopped: %llu clients served, %llu refused", (unsigned long long)s.served,
                (unsigned long long)s.refused);
out:
    while (s.conns)
        conn_close(&s, s.conns, srv_now_us());
    for (i = 0; i < 2; i++)
        if (s.lfd[i] >= 0)
            close(s.lfd[i]);
    if (s.sigfd >= 0) {
        struct signalfd_siginfo si;
        while (read(s.sigfd, &si, sizeof si) == (ssize_t)sizeof si)
            ;   /* consumed: a signal left pending would kill us when unblocked */
        close(s.sigfd);
    }
    srv_usb_stop(s.usb);
    if (s.epfd >= 0)
        close(s.epfd);
    free(s.timers.a);
    /* The caller's mask back, not an unblock: `timeout` and shells send a
     * stop signal to the process and again to its group, and the second
     * copy may land after the drain above. A caller that blocked the signals
     * itself (lumo-server --dynamic: its engine must be stopped and summed
     * up first) keeps them blocked until it exits. */
    sigprocmask(SIG_SETMASK, &caller_mask, NULL);
    return st;
}
