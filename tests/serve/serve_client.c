/*
 * tests/serve/serve_client.c — lumo-server from the outside: minimal
 * clients written with the codec (lumo/net.h) that check what the server
 * sends against the package, read independently with the SDK.
 *
 *   serve_client MODE PORT PACKAGE [options]
 *
 *   full     one client asks for everything (every mesh's geometry, then the
 *            lighting) with random amounts and pipelining: every answer is
 *            exactly the batches / rounds the protocol says (never more than
 *            asked), every frame under the max payload, the records
 *            concatenated equal the package's chunks byte for byte, and a
 *            client session takes all of it
 *   resume   the same, cut at random points and resumed with the cursors
 *            held: no byte held is sent twice
 *   hostile  malformed and out-of-place frames, each on its own connection,
 *            end that client with the right ERROR while a well-behaved client
 *            on the same server goes on between them and finishes
 *   idle     a client that never reads and one that never talks are closed
 *            after the server's idle timeout, beside a well-behaved one
 *   many N   N clients at once, each to the end
 *   serial   over the serial listener: garbage before and between frames,
 *            lost and damaged frames (--loss on the server) recovered by
 *            resynchronising and asking again
 *   full-limit N  N clients hold their connection; one more gets ERROR LIMIT
 *   timing R L    a full fetch through --rate R kbit/s and --latency L ms
 *            takes at least the bytes' time at that rate and 2 L per request
 *
 * Options: --max-payload N, --form q|f|none, --seed S, --pipeline K,
 * --package I, --cuts N (resume), --idle S (idle: the server's idle
 * timeout), --expect-loss 1 (serial: the server damages frames).
 * Output: a line per check, then "RESULT: N passed, M failed". Every wait
 * is bounded (poll timeouts, and an alarm for the whole run).
 */
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <arpa/inet.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "lumo/arena.h"
#include "lumo/ivg.h"
#include "lumo/net.h"
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo/session.h"
#include "lumo/wire.h"

/* ---- checks ---------------------------------------------------------------------- */

static int g_pass, g_fail;
static int g_bad;   /* failures inside the current check */

static void problem(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void problem(const char *fmt, ...)
{
    va_list ap;

    if (g_bad++ < 8) {
        va_start(ap, fmt);
        fputs("    ", stdout);
        vprintf(fmt, ap);
        fputc('\n', stdout);
        va_end(ap);
    }
}

/* Close a check: it passes when nothing went wrong since the last one. */
static void check(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void check(const char *fmt, ...)
{
    va_list ap;

    fputs(g_bad ? "FAIL " : "ok   ", stdout);
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    fputc('\n', stdout);
    fflush(stdout);
    if (g_bad)
        g_fail++;
    else
        g_pass++;
    g_bad = 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec / 1e9;
}

static uint64_t g_rng = 1;
static uint64_t rnd(void)
{
    uint64_t z = (g_rng += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* ---- the package, read with the SDK ------------------------------------------------ */

typedef struct pmesh_view {
    const uint8_t    *s;
    uint32_t          len;
    lumo_pmesh_header h;
    uint32_t         *rec;   /* batch_count + 1 */
} pmesh_view;

typedef struct pkg_view {
    uint8_t     *map;
    size_t       size;
    lumo_package pkg;
    uint32_t     id, meshes;
    pmesh_view   mesh[LUMO_MAX_MESHES];
    const uint8_t *info, *ivgd, *ivgs, *ordr;
    uint32_t     info_len, ivgd_len, ivgs_len, ordr_len;
    int          has_ivg;
    uint32_t     rounds;
    uint32_t    *first;      /* rounds + 1 */
    uint32_t    *off[2];     /* rounds + 1: byte offsets in the form's bundle payload */
    const uint8_t *bundle[2];
    uint32_t     bundle_len[2];
    size_t       arena_need;
} pkg_view;

static int pkg_load(pkg_view *v, const char *path)
{
    struct stat sb;
    lumo_pkg_info info;
    uint32_t i, b;
    int fd = open(path, O_RDONLY);

    memset(v, 0, sizeof *v);
    if (fd < 0 || fstat(fd, &sb) < 0) {
        fprintf(stderr, "serve_client: %s: %s\n", path, strerror(errno));
        return -1;
    }
    v->size = (size_t)sb.st_size;
    v->map = mmap(NULL, v->size, PROT_READ, MAP_PRIVATE, fd, 0);
    close(fd);
    if (v->map == MAP_FAILED || lumo_package_open(&v->pkg, v->map, v->size) || lumo_package_info(&v->pkg, &info)) {
        fprintf(stderr, "serve_client: %s: not a package this SDK reads\n", path);
        return -1;
    }
    v->id = lumo_wire_le32(v->map + 20);
    v->meshes = info.mesh_count;
    lumo_package_find(&v->pkg, LUMO_PKG_INFO, 0, &v->info, &v->info_len);
    for (i = 0; i < v->meshes; i++) {
        pmesh_view *m = &v->mesh[i];
        size_t at, n;
        const uint8_t *r;
        if (lumo_package_find(&v->pkg, LUMO_PKG_PMSH, i, &m->s, &m->len) ||
            lumo_pmesh_read_header(m->s, m->len, &m->h))
            return -1;
        at = m->h.header_bytes;
        m->rec = calloc((size_t)m->h.batch_count + 1, sizeof *m->rec);
        for (b = 0; b < m->h.batch_count; b++) {
            m->rec[b] = (uint32_t)at;
            if (lumo_pmesh_next_record(m->s, m->len, &at, &r, &n))
                return -1;
        }
        m->rec[b] = (uint32_t)at;
    }
    v->has_ivg = lumo_package_find(&v->pkg, LUMO_PKG_IVGD, 0, &v->ivgd, &v->ivgd_len) == LUMO_OK;
    if (v->has_ivg) {
        lumo_ivg_order o;
        uint32_t r, f;
        if (lumo_package_ivg_order(&v->pkg, &o) ||
            lumo_package_find(&v->pkg, LUMO_PKG_IVGS, 0, &v->ivgs, &v->ivgs_len))
            return -1;
        v->rounds = o.rounds;
        v->first = calloc((size_t)o.rounds + 1, sizeof *v->first);
        for (f = 0; f < 2; f++) {
            v->off[f] = calloc((size_t)o.rounds + 1, sizeof *v->off[f]);
            if (lumo_package_find(&v->pkg, f == LUMO_IVG_FORM_QUANTIZED ? LUMO_PKG_IVGQ : LUMO_PKG_IVGF, 0,
                                  &v->bundle[f], &v->bundle_len[f]))
                return -1;
        }
        for (r = 0; r <= o.rounds; r++) {
            v->first[r] = lumo_ivg_order_first(&o, r);
            for (f = 0; f < 2; f++)
                v->off[f][r] = lumo_ivg_order_offset(&o, (lumo_ivg_form)f, r);
        }
    }
    lumo_package_find(&v->pkg, LUMO_PKG_ORDR, 0, &v->ordr, &v->ordr_len);
    if (lumo_session_package_need(&v->pkg, &v->arena_need))
        return -1;
    return 0;
}

static void pkg_unload(pkg_view *v)
{
    uint32_t m;

    for (m = 0; m < v->meshes; m++)
        free(v->mesh[m].rec);
    free(v->first);
    free(v->off[0]);
    free(v->off[1]);
    if (v->map && v->map != MAP_FAILED)
        munmap(v->map, v->size);
}

/* Vertices held after the first b batches. */
static uint32_t verts_before(const pmesh_view *m, uint32_t b)
{
    uint64_t v;
    if (b == 0)
        return 0;
    v = (uint64_t)m->h.base_vertices + (uint64_t)(b - 1) * m->h.batch_vertices;
    return v > m->h.vertices ? m->h.vertices : (uint32_t)v;
}

/* The protocol's answer to (cursor c, amount n), counted one batch at a
 * time: whole batches holding at most n vertices, at least one. */
static uint32_t geometry_end(const pmesh_view *m, uint32_t c, uint32_t n)
{
    uint32_t e = c + 1;
    while (e < m->h.batch_count && verts_before(m, e + 1) - verts_before(m, c) <= n)
        e++;
    return e;
}

/* Bytes of the IVG record at p (docs/ivg-format.md §2.2). */
static uint32_t ivg_record_bytes(const uint8_t *p, int form)
{
    if (lumo_wire_le32(p) & 0x80000000u)
        return 4;
    return form == LUMO_IVG_FORM_QUANTIZED ? 46u : 148u;
}

#define BUNDLE_HEAD 16u   /* an IVG bundle's header (docs/ivg-format.md §2.1) */

/* ---- connections ------------------------------------------------------------------- */

typedef struct conn {
    int      fd;
    uint8_t *buf;
    size_t   cap, len, used;   /* used: bytes of the last frame returned */
    uint64_t in;
} conn;

static int g_port, g_serial_port;

static int tcp_connect(int port)
{
    struct sockaddr_in a;
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0), one = 1;

    if (fd < 0)
        return -1;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, (struct sockaddr *)&a, sizeof a) < 0) {
        close(fd);
        return -1;
    }
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    return fd;
}

static int conn_open(conn *c, int port, size_t cap)
{
    memset(c, 0, sizeof *c);
    c->cap = cap;
    c->buf = malloc(cap);
    c->fd = tcp_connect(port);
    return c->fd < 0 || !c->buf ? -1 : 0;
}

static void conn_close(conn *c)
{
    if (c->fd >= 0)
        close(c->fd);
    c->fd = -1;
    free(c->buf);
    c->buf = NULL;
}

static int send_all(int fd, const void *p, size_t n)
{
    const uint8_t *b = p;
    double t0 = now_s();

    while (n) {
        ssize_t w = send(fd, b, n, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (w > 0) {
            b += w, n -= (size_t)w;
            continue;
        }
        if (w < 0 && errno == EINTR)
            continue;
        if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) && now_s() - t0 < 10) {
            struct pollfd pf = {fd, POLLOUT, 0};
            poll(&pf, 1, 100);
            continue;
        }
        return -1;
    }
    return 0;
}

/* Read more bytes (at most limit, 0: as many as fit) within timeout_ms.
 * 1 read, 0 end of stream, -1 error or timeout. */
static int conn_fill(conn *c, int timeout_ms, size_t limit)
{
    struct pollfd pf = {c->fd, POLLIN, 0};
    size_t room = c->cap - c->len;
    ssize_t n;

    if (limit && limit < room)
        room = limit;
    if (room == 0)
        return -1;
    if (poll(&pf, 1, timeout_ms) <= 0)
        return -1;
    n = recv(c->fd, c->buf + c->len, room, 0);
    if (n > 0) {
        c->len += (size_t)n;
        c->in += (uint64_t)n;
        return 1;
    }
    return n == 0 ? 0 : -1;
}

/* Drop the frame returned last. */
static void conn_consume(conn *c)
{
    if (c->used) {
        memmove(c->buf, c->buf + c->used, c->len - c->used);
        c->len -= c->used;
        c->used = 0;
    }
}

/* The next frame: LUMO_OK, the codec's refusal, or LUMO_ERR_IO (end of
 * stream, timeout). */
static lumo_status conn_frame(conn *c, uint32_t max_payload, lumo_net_frame *f, int timeout_ms)
{
    conn_consume(c);
    for (;;) {
        size_t used = 0;
        lumo_status st = lumo_net_frame_decode(c->buf, c->len, max_payload, f, &used);
        if (st == LUMO_OK) {
            c->used = used;
            return LUMO_OK;
        }
        if (st != LUMO_ERR_TRUNCATED)
            return st;
        if (conn_fill(c, timeout_ms, 0) <= 0)
            return LUMO_ERR_IO;
    }
}

/* Wait for the end of the stream (EOF or reset): 1, or 0 on timeout. */
static int wait_closed(int fd, int timeout_ms)
{
    uint8_t tmp[65536];
    double t0 = now_s();

    while ((now_s() - t0) * 1000 < timeout_ms) {
        struct pollfd pf = {fd, POLLIN, 0};
        ssize_t n;
        if (poll(&pf, 1, 100) <= 0)
            continue;
        n = recv(fd, tmp, sizeof tmp, 0);
        if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN))
            return 1;
    }
    return 0;
}

typedef struct hello_opts {
    uint32_t package, arena, max_payload, resume_id, mesh_count;
    uint8_t  form;
    const uint32_t *cursors;
} hello_opts;

static size_t make_hello(const hello_opts *o, uint8_t *out, size_t cap)
{
    lumo_net_hello h;
    size_t n = 0;

    memset(&h, 0, sizeof h);
    h.package = o->package;
    h.arena_bytes = o->arena;
    h.max_payload = o->max_payload;
    h.width = 320, h.height = 240;
    h.ivg_form = o->form;
    h.resume_id = o->resume_id;
    h.mesh_count = o->mesh_count;
    if (lumo_net_hello_encode(&h, o->cursors, out, cap, &n))
        return 0;
    return n;
}

static size_t make_request(uint8_t channel, uint32_t mesh, uint32_t cursor, uint32_t amount, uint8_t *out)
{
    lumo_net_request r = {channel, mesh, cursor, amount};
    size_t n = 0;
    lumo_net_request_encode(&r, out, 64, &n);
    return n;
}

/* A frame of any type and payload, sealed by hand (hostile tests). */
static size_t make_raw(uint8_t type, const void *payload, uint32_t len, uint8_t *out)
{
    if (len)
        memcpy(out + LUMO_NET_HEADER, payload, len);
    lumo_net_frame_seal(out, type, len);
    return LUMO_NET_OVERHEAD + len;
}

/* ---- WELCOME ----------------------------------------------------------------------- */

/* The descriptors protocol.md §2 lists, in its order, equal to the package's
 * chunks; the arena need equal to the SDK's for the whole package. */
static void check_welcome(const pkg_view *v, const lumo_net_frame *f, lumo_session *s)
{
    lumo_net_welcome w;
    lumo_net_msg m;
    size_t at = 0;
    uint32_t k = 0, i;
    lumo_status st;

    if ((st = lumo_net_welcome_decode(f, &w))) {
        problem("WELCOME refused by the codec: %s", lumo_strerror(st));
        return;
    }
    if (w.package_id != v->id)
        problem("package id %08x, the package says %08x", w.package_id, v->id);
    if (w.arena_need != v->arena_need)
        problem("arena need %u, lumo_session_package_need says %zu", w.arena_need, v->arena_need);
    while (lumo_net_welcome_next(&w, &at, &m) == LUMO_OK) {
        uint32_t want_type = 0, want_index = 0, want_len = 0;
        const uint8_t *want = NULL;
        if (k == 0)
            want_type = LUMO_PKG_INFO, want = v->info, want_len = v->info_len;
        else if (k <= v->meshes)
            want_type = LUMO_PKG_PMSH, want_index = k - 1, want = v->mesh[k - 1].s, want_len = v->mesh[k - 1].h.header_bytes;
        else if (v->has_ivg && k == v->meshes + 1)
            want_type = LUMO_PKG_IVGD, want = v->ivgd, want_len = v->ivgd_len;
        else if (v->has_ivg && k == v->meshes + 2)
            want_type = LUMO_PKG_IVGS, want = v->ivgs, want_len = v->ivgs_len;
        else if (v->ordr && k == v->meshes + (v->has_ivg ? 3u : 1u))
            want_type = LUMO_PKG_ORDR, want = v->ordr, want_len = v->ordr_len;
        if (m.type != want_type || m.index != want_index || m.len != want_len || !want ||
            memcmp(m.data, want, m.len))
            problem("WELCOME message %u: type %08x index %u, %u bytes: not the package's", k, m.type, m.index,
                    m.len);
        if (s && (st = lumo_session_feed(s, m.type, m.index, m.data, m.len)))
            problem("the session refuses WELCOME message %u: %s", k, lumo_strerror(st));
        k++;
    }
    i = 1 + v->meshes + (v->has_ivg ? 2u : 0u) + (v->ordr ? 1u : 0u);
    if (k != i || k != w.count)
        problem("WELCOME has %u messages (count %u), want %u", k, w.count, i);
}

/* ---- the fetch: everything, checked ------------------------------------------------ */

typedef struct pending {
    uint8_t  channel;
    uint32_t mesh, cursor, amount, end;   /* end: what the protocol says comes */
} pending;

typedef struct fetch {
    const pkg_view *v;
    uint32_t max_payload, pipeline;
    uint8_t  form;
    uint32_t held[LUMO_MAX_MESHES], asked[LUMO_MAX_MESHES];
    uint8_t  ended[LUMO_MAX_MESHES];
    uint32_t rounds_held, rounds_asked, round_pos;   /* round_pos: bytes into a split round */
    uint8_t  ivg_ended;
    pending  q[16];
    uint32_t nq;
    uint8_t *got_geo[LUMO_MAX_MESHES];   /* the records as received */
    uint8_t *got_ivg;
    uint64_t record_bytes, resent, frames, requests, over_asked;
    lumo_session *session;
    int      amounts;   /* 0 random, 1 one vertex/round, 2 everything */
} fetch;

static uint32_t pick_amount(const fetch *f, uint8_t channel, uint32_t mesh)
{
    uint32_t bv = channel == LUMO_NET_GEOMETRY ? f->v->mesh[mesh].h.batch_vertices : 1;
    if (f->amounts == 1)
        return 1;
    if (f->amounts == 2)
        return 0x7fffffffu;
    switch (rnd() % 6) {
    case 0: return 1;
    case 1: return bv > 1 ? bv - 1 : 1;
    case 2: return bv;
    case 3: return bv * (uint32_t)(2 + rnd() % 4);
    case 4: return bv * 2 + 1;
    default: return 0x7fffffffu;
    }
}

/* The next request to send, or 0 when nothing is left to ask: every mesh in
 * turn, then the lighting. */
static size_t next_request(fetch *f, uint8_t *out)
{
    const pkg_view *v = f->v;
    uint32_t m;
    pending *p;

    if (f->nq >= f->pipeline)
        return 0;
    p = &f->q[f->nq];
    for (m = 0; m < v->meshes; m++)
        if (!f->ended[m] && f->asked[m] <= v->mesh[m].h.batch_count) {
            p->channel = LUMO_NET_GEOMETRY;
            p->mesh = m;
            p->cursor = f->asked[m];
            p->amount = pick_amount(f, LUMO_NET_GEOMETRY, m);
            p->end = p->cursor < v->mesh[m].h.batch_count ? geometry_end(&v->mesh[m], p->cursor, p->amount)
                                                           : p->cursor;
            /* asking at the end once gets END; asked past it: wait */
            f->asked[m] = p->end == p->cursor ? p->end + 1 : p->end;
            f->nq++;
            f->requests++;
            return make_request(LUMO_NET_GEOMETRY, m, p->cursor, p->amount, out);
        }
    if (v->has_ivg && f->form != LUMO_NET_FORM_NONE && !f->ivg_ended && f->rounds_asked <= v->rounds) {
        p->channel = LUMO_NET_LIGHTING;
        p->mesh = 0;
        p->cursor = f->rounds_asked;
        p->amount = pick_amount(f, LUMO_NET_LIGHTING, 0);
        p->end = p->cursor < v->rounds ? (p->amount > v->rounds - p->cursor ? v->rounds : p->cursor + p->amount)
                                       : p->cursor;
        f->rounds_asked = p->end == p->cursor ? p->end + 1 : p->end;
        f->nq++;
        f->requests++;
        return make_request(LUMO_NET_LIGHTING, 0, p->cursor, p->amount, out);
    }
    return 0;
}

static int fetch_done(const fetch *f)
{
    uint32_t m;
    for (m = 0; m < f->v->meshes; m++)
        if (!f->ended[m])
            return 0;
    return !f->v->has_ivg || f->form == LUMO_NET_FORM_NONE || f->ivg_ended;
}

static void pop_pending(fetch *f)
{
    memmove(f->q, f->q + 1, (f->nq - 1) * sizeof *f->q);
    f->nq--;
}

/* One frame of an answer, checked against the oldest pending request.
 * 0: fine, -1: the conversation is off (a problem was reported). */
static int on_answer(fetch *f, const lumo_net_frame *fr)
{
    const pkg_view *v = f->v;
    pending *p = &f->q[0];
    lumo_status st;

    if (f->nq == 0) {
        problem("frame type %u with no request outstanding", fr->type);
        return -1;
    }
    if (fr->len > f->max_payload) {
        problem("a %u-byte payload, more than max payload %u", fr->len, f->max_payload);
        return -1;
    }
    f->frames++;
    if (fr->type == LUMO_NET_END) {
        lumo_net_end e;
        if ((st = lumo_net_end_decode(fr, &e)) || e.channel != p->channel || e.mesh != p->mesh) {
            problem("END does not answer the request (channel %u mesh %u)", p->channel, p->mesh);
            return -1;
        }
        if (p->channel == LUMO_NET_GEOMETRY) {
            if (f->held[p->mesh] != v->mesh[p->mesh].h.batch_count)
                problem("END for mesh %u at %u of %u batches", p->mesh, f->held[p->mesh],
                        v->mesh[p->mesh].h.batch_count);
            f->ended[p->mesh] = 1;
        } else {
            if (f->rounds_held != v->rounds)
                problem("lighting END at round %u of %u", f->rounds_held, v->rounds);
            f->ivg_ended = 1;
        }
        pop_pending(f);
        return 0;
    }
    if (fr->type == LUMO_NET_ERROR) {
        lumo_net_error e;
        if (lumo_net_error_decode(fr, &e) == LUMO_OK)
            problem("ERROR %s: %.*s", lumo_strerror((lumo_status)e.status), (int)e.len, (const char *)e.text);
        else
            problem("a malformed ERROR");
        return -1;
    }
    if (fr->type != LUMO_NET_DATA) {
        problem("frame type %u in answer to a request", fr->type);
        return -1;
    }
    {
        lumo_net_data d;
        if ((st = lumo_net_data_decode(fr, &d))) {
            problem("DATA refused by the codec: %s", lumo_strerror(st));
            return -1;
        }
        if (d.channel != p->channel || (p->channel == LUMO_NET_GEOMETRY && d.mesh != p->mesh)) {
            problem("DATA channel %u mesh %u answers request channel %u mesh %u", d.channel, d.mesh, p->channel,
                    p->mesh);
            return -1;
        }
        if (d.channel == LUMO_NET_GEOMETRY) {
            const pmesh_view *m = &v->mesh[d.mesh];
            uint32_t h = f->held[d.mesh], k;
            if (d.first != h) {
                if (d.first < h)
                    f->resent += d.len;
                problem("mesh %u: DATA first %u, the client holds %u", d.mesh, d.first, h);
                return -1;
            }
            if (d.count == 0 || d.records != d.count || d.first + d.count > p->end) {
                problem("mesh %u: DATA %u+%u records past the answer's end %u (asked %u vertices from %u)", d.mesh,
                        d.first, d.count, p->end, p->amount, p->cursor);
                f->over_asked++;
                return -1;
            }
            if (d.len != m->rec[d.first + d.count] - m->rec[d.first] ||
                memcmp(d.bytes, m->s + m->rec[d.first], d.len)) {
                problem("mesh %u: records %u..%u are not the package's bytes", d.mesh, d.first,
                        d.first + d.count - 1);
                return -1;
            }
            if (f->got_geo[d.mesh])
                memcpy(f->got_geo[d.mesh] + m->rec[d.first] - m->h.header_bytes, d.bytes, d.len);
            if (f->session)
                for (k = 0; k < d.count; k++) {
                    uint32_t b = d.first + k;
                    if ((st = lumo_session_feed(f->session, LUMO_MSG_PMSB, d.mesh, m->s + m->rec[b],
                                                m->rec[b + 1] - m->rec[b])))
                        problem("the session refuses mesh %u batch %u: %s", d.mesh, b, lumo_strerror(st));
                }
            f->held[d.mesh] += d.count;
            f->record_bytes += d.len;
            if (f->held[d.mesh] == p->end)
                pop_pending(f);
            return 0;
        }
        {
            const uint8_t *bundle = v->bundle[f->form];
            const uint32_t *off = v->off[f->form];
            uint32_t r = f->rounds_held, pos = off[r] + f->round_pos, q = pos, n = 0;
            if (d.form != f->form || d.first != r) {
                if (d.first < r)
                    f->resent += d.len;
                problem("lighting DATA first %u form %u, the client holds %u rounds, form %u", d.first, d.form, r,
                        f->form);
                return -1;
            }
            if (pos + d.len > v->bundle_len[f->form] || memcmp(d.bytes, bundle + pos, d.len)) {
                problem("lighting: rounds from %u are not the package's bytes", r);
                return -1;
            }
            while (q < pos + d.len)
                q += ivg_record_bytes(bundle + q, f->form), n++;
            if (q != pos + d.len || n != d.records)
                problem("lighting DATA at round %u: %u records stated, %u carried", r, d.records, n);
            if (d.count == 0) {
                if (pos + d.len >= off[r + 1] || off[r + 1] - off[r] <= f->max_payload - LUMO_NET_DATA_HEAD)
                    problem("round %u split though it fits a frame, or a split frame ends it", r);
                f->round_pos += d.len;
            } else {
                if (r + d.count > p->end || pos + d.len != off[r + d.count]) {
                    problem("lighting DATA %u+%u rounds: past the answer's end %u or not whole rounds", r, d.count,
                            p->end);
                    f->over_asked++;
                    return -1;
                }
                f->rounds_held += d.count;
                f->round_pos = 0;
            }
            if (f->session) {
                /* the 8 bytes before the records are the IVGR head (form, records) */
                st = lumo_session_feed(f->session, LUMO_MSG_IVGR, 0, d.bytes - LUMO_NET_IVGR_HEAD,
                                       d.len + LUMO_NET_IVGR_HEAD);
                if (st)
                    problem("the session refuses the lighting records at round %u: %s", r, lumo_strerror(st));
            }
            if (f->got_ivg)
                memcpy(f->got_ivg + pos - BUNDLE_HEAD, d.bytes, d.len);
            f->record_bytes += d.len;
            if (f->rounds_held == p->end)
                pop_pending(f);
            return 0;
        }
    }
}

/* ---- full and resume --------------------------------------------------------------- */

typedef struct run_opts {
    uint32_t max_payload, pipeline, cuts, package;
    uint8_t  form;
    int      amounts;
    int      expect_loss;   /* serial: the server damages frames */
} run_opts;

static void fetch_init(fetch *f, const pkg_view *v, const run_opts *o, int keep)
{
    uint32_t m;

    memset(f, 0, sizeof *f);
    f->v = v;
    f->max_payload = o->max_payload;
    f->pipeline = o->pipeline ? o->pipeline : 1;
    f->form = o->form;
    f->amounts = o->amounts;
    if (!keep)
        return;
    for (m = 0; m < v->meshes; m++)
        f->got_geo[m] = calloc(1, v->mesh[m].len - v->mesh[m].h.header_bytes + 1);
    if (v->has_ivg && o->form != LUMO_NET_FORM_NONE)
        f->got_ivg = calloc(1, v->bundle_len[o->form] - BUNDLE_HEAD + 1);
}

static void fetch_free(fetch *f)
{
    uint32_t m;
    for (m = 0; m < LUMO_MAX_MESHES; m++)
        free(f->got_geo[m]);
    free(f->got_ivg);
}

/* After a cut: what was asked and not held is asked again. */
static uint64_t fetch_reset_link(fetch *f)
{
    uint32_t m;
    uint64_t partial = f->round_pos;

    for (m = 0; m < f->v->meshes; m++)
        f->asked[m] = f->ended[m] ? f->asked[m] : f->held[m];
    f->rounds_asked = f->ivg_ended ? f->rounds_asked : f->rounds_held;
    f->round_pos = 0;
    f->nq = 0;
    return partial;
}

/* The whole package received equals its chunks; the session holds it all. */
static void check_complete(const fetch *f, lumo_session *s, const char *mode)
{
    const pkg_view *v = f->v;
    uint64_t want = 0;
    uint32_t m;

    for (m = 0; m < v->meshes; m++) {
        uint32_t n = v->mesh[m].len - v->mesh[m].h.header_bytes;
        want += n;
        if (!f->ended[m] || f->held[m] != v->mesh[m].h.batch_count)
            problem("mesh %u: %u of %u batches", m, f->held[m], v->mesh[m].h.batch_count);
        if (f->got_geo[m] && memcmp(f->got_geo[m], v->mesh[m].s + v->mesh[m].h.header_bytes, n))
            problem("mesh %u: the records received are not its PMSH chunk minus the header", m);
    }
    if (v->has_ivg && f->form != LUMO_NET_FORM_NONE) {
        uint32_t n = v->bundle_len[f->form] - BUNDLE_HEAD;
        want += n;
        if (!f->ivg_ended || f->rounds_held != v->rounds)
            problem("lighting: %u of %u rounds", f->rounds_held, v->rounds);
        if (f->got_ivg && memcmp(f->got_ivg, v->bundle[f->form] + BUNDLE_HEAD, n))
            problem("the rounds received are not the %s bundle's records", f->form ? "IVGQ" : "IVGF");
    }
    if (f->record_bytes != want)
        problem("%llu record bytes received, the package holds %llu", (unsigned long long)f->record_bytes,
                (unsigned long long)want);
    if (s) {
        for (m = 0; m < v->meshes; m++) {
            lumo_session_progress p;
            if (lumo_session_mesh_progress(s, m, &p) || p.vertices != p.full_vertices)
                problem("the session's mesh %u is not complete", m);
        }
        if (v->has_ivg && f->form != LUMO_NET_FORM_NONE) {
            const lumo_ivg *g = lumo_session_ivg(s);
            if (!g || lumo_ivg_received_count(g) + lumo_ivg_solid_count(g) < lumo_ivg_vertex_count(g))
                problem("the session's IVG has %u of %u vertices", g ? lumo_ivg_received_count(g) : 0,
                        g ? lumo_ivg_vertex_count(g) : 0);
        }
    }
    check("%s: %llu record bytes, equal to the package's PMSH records%s; %llu requests, %llu frames", mode,
          (unsigned long long)f->record_bytes, v->has_ivg && f->form != LUMO_NET_FORM_NONE ? " and IVG rounds" : "",
          (unsigned long long)f->requests, (unsigned long long)f->frames);
}

/* Connect and say HELLO (resuming from f's cursors when resume_id is set);
 * the WELCOME checked (and fed to s on a fresh start). */
static int fetch_connect(conn *c, fetch *f, const run_opts *o, uint32_t resume_id, lumo_session *s)
{
    uint8_t out[1024];
    uint32_t cur[LUMO_MAX_MESHES];
    hello_opts h;
    lumo_net_frame fr;
    lumo_status st;
    uint32_t m;
    size_t n;

    if (conn_open(c, g_port, o->max_payload + LUMO_NET_OVERHEAD + 64)) {
        problem("connect to port %d: %s", g_port, strerror(errno));
        return -1;
    }
    memset(&h, 0, sizeof h);
    h.package = o->package;
    h.arena = (uint32_t)f->v->arena_need;
    h.max_payload = o->max_payload;
    h.form = o->form;
    if (resume_id) {
        for (m = 0; m < f->v->meshes; m++)
            cur[m] = f->held[m];
        h.resume_id = resume_id;
        h.mesh_count = f->v->meshes;
        h.cursors = cur;
    }
    n = make_hello(&h, out, sizeof out);
    if (!n || send_all(c->fd, out, n)) {
        problem("sending HELLO");
        return -1;
    }
    if ((st = conn_frame(c, o->max_payload, &fr, 5000)) || fr.type != LUMO_NET_WELCOME) {
        problem("no WELCOME (%s, frame type %u)", lumo_strerror(st), st ? 0 : fr.type);
        return -1;
    }
    if (resume_id) {
        lumo_net_welcome w;
        if (lumo_net_welcome_decode(&fr, &w) || w.package_id != resume_id)
            problem("resumed WELCOME names another package");
    } else {
        check_welcome(f->v, &fr, s);
    }
    return 0;
}

/* Requests and answers until everything is held, or the connection is cut
 * (1), or something is wrong (-1). */
static int fetch_pump(conn *c, fetch *f, double deadline)
{
    uint8_t out[64];
    lumo_net_frame fr;
    lumo_status st;
    size_t n;

    while (!fetch_done(f)) {
        while ((n = next_request(f, out)))
            if (send_all(c->fd, out, n))
                return 1;
        if (now_s() > deadline) {
            problem("no end before the deadline");
            return -1;
        }
        st = conn_frame(c, f->max_payload, &fr, 5000);
        if (st == LUMO_ERR_IO)
            return 1;
        if (st) {
            problem("a frame the codec refuses: %s", lumo_strerror(st));
            return -1;
        }
        if (on_answer(f, &fr))
            return -1;
    }
    return 0;
}

static void say_bye(conn *c)
{
    uint8_t out[32];
    size_t n = 0;

    conn_consume(c);
    lumo_net_bye_encode(out, sizeof out, &n);
    if (send_all(c->fd, out, n) || !wait_closed(c->fd, 5000))
        problem("the server did not close after BYE");
}

/* A client session with the arena WELCOME asks for (one allocation). */
typedef struct sess_box {
    lumo_session s;
    lumo_arena   a;
    uint8_t      mem[];
} sess_box;

static sess_box *session_new(const pkg_view *v)
{
    sess_box *b = malloc(sizeof *b + v->arena_need);

    if (!b)
        return NULL;
    lumo_arena_init(&b->a, b->mem, v->arena_need);
    if (lumo_session_init(&b->s, NULL, &b->a)) {
        free(b);
        return NULL;
    }
    return b;
}

static void mode_full(const pkg_view *v, const run_opts *o, const char *name)
{
    fetch f;
    conn c;
    sess_box *sb = session_new(v);
    double t0 = now_s();

    fetch_init(&f, v, o, 1);
    f.session = sb ? &sb->s : NULL;
    if (fetch_connect(&c, &f, o, 0, f.session) == 0) {
        check("%s: WELCOME: INFO, %u stream headers%s%s, arena need %zu (the SDK's)", name, v->meshes,
              v->has_ivg ? ", IVGD, IVGS" : "", v->ordr ? ", ORDR" : "", v->arena_need);
        if (fetch_pump(&c, &f, t0 + 60) == 0)
            say_bye(&c);
        else
            problem("the conversation broke off");
    } else {
        check("%s: WELCOME", name);
    }
    conn_close(&c);
    if (f.over_asked)
        problem("%llu answers carried more than asked", (unsigned long long)f.over_asked);
    check("%s: every answer exactly the batches/rounds asked (never more), frames <= max payload %u", name,
          o->max_payload);
    check_complete(&f, f.session, name);
    fetch_free(&f);
    free(sb);
}

static void mode_resume(const pkg_view *v, const run_opts *o)
{
    fetch f;
    conn c;
    uint64_t total = 0, partial = 0, cut_bytes = 0;
    uint32_t m, cuts = 0, tries = 0;
    double t0 = now_s();
    sess_box *sb = session_new(v);

    for (m = 0; m < v->meshes; m++)
        total += v->mesh[m].len;
    if (v->has_ivg && o->form != LUMO_NET_FORM_NONE)
        total += v->bundle_len[o->form];
    fetch_init(&f, v, o, 1);
    f.session = sb ? &sb->s : NULL;
    while (!fetch_done(&f) && tries++ < 10 * (o->cuts + 10) && now_s() - t0 < 60) {
        int r;
        if (fetch_connect(&c, &f, o, cuts || tries > 1 ? v->id : 0, f.session)) {
            conn_close(&c);
            break;
        }
        /* the cut: after a random number of bytes of answers */
        if (cuts < o->cuts) {
            conn_consume(&c);
            {
                uint64_t span = total / (o->cuts + 1) * 2 + 1, limit = 1 + rnd() % span;
                uint64_t at = c.in;
                /* read at most `limit` more bytes: a smaller buffer window */
                fetch *fp = &f;
                uint8_t out[64];
                size_t n;
                r = 0;
                while (!fetch_done(fp) && c.in - at < limit) {
                    lumo_net_frame fr;
                    size_t used = 0;
                    lumo_status st;
                    while ((n = next_request(fp, out)))
                        send_all(c.fd, out, n);
                    conn_consume(&c);
                    st = lumo_net_frame_decode(c.buf, c.len, o->max_payload, &fr, &used);
                    if (st == LUMO_OK) {
                        c.used = used;
                        if (on_answer(fp, &fr)) {
                            r = -1;
                            break;
                        }
                        continue;
                    }
                    if (st != LUMO_ERR_TRUNCATED) {
                        problem("a frame the codec refuses: %s", lumo_strerror(st));
                        r = -1;
                        break;
                    }
                    if (conn_fill(&c, 5000, (size_t)(limit - (c.in - at))) <= 0)
                        break;
                }
                cut_bytes += c.len - c.used;   /* a frame cut in the middle */
            }
            if (r < 0)
                break;
            cuts++;
            partial += fetch_reset_link(&f);
            conn_close(&c);
            continue;
        }
        r = fetch_pump(&c, &f, t0 + 60);
        if (r == 0)
            say_bye(&c);
        conn_close(&c);
        if (r < 0)
            break;
        partial += fetch_reset_link(&f);
    }
    if (cuts < o->cuts)
        problem("only %u of %u cuts made", cuts, o->cuts);
    if (f.resent)
        problem("%llu bytes of records the client held were sent again", (unsigned long long)f.resent);
    check("resume: %u cuts at random points, resumed with the cursors held: no record held sent again "
          "(%llu bytes of cut frames and %llu of split rounds asked again)",
          cuts, (unsigned long long)cut_bytes, (unsigned long long)partial);
    f.record_bytes -= partial;   /* a split round is asked again from its start */
    check_complete(&f, f.session, "resume");
    fetch_free(&f);
    free(sb);
}

/* ---- hostile ----------------------------------------------------------------------- */

/* Read until an ERROR frame: its status (LUMO_OK when the connection ended
 * without one, -1 on timeout). */
static int read_error(int fd, int timeout_ms, char *text, size_t cap)
{
    conn c;
    lumo_net_frame fr;
    double t0 = now_s();
    int st = -1;

    memset(&c, 0, sizeof c);
    c.fd = fd;
    c.cap = 1 << 20;
    c.buf = malloc(c.cap);
    text[0] = 0;
    while ((now_s() - t0) * 1000 < timeout_ms) {
        lumo_status s = conn_frame(&c, LUMO_NET_MAX_PAYLOAD, &fr, 200);
        if (s == LUMO_OK && fr.type == LUMO_NET_ERROR) {
            lumo_net_error e;
            if (lumo_net_error_decode(&fr, &e) == LUMO_OK) {
                snprintf(text, cap, "%.*s", (int)e.len, (const char *)e.text);
                st = (int)e.status;
            } else {
                st = LUMO_ERR_CORRUPT;
            }
            break;
        }
        if (s == LUMO_OK)
            continue;   /* WELCOME or DATA before the error */
        if (s == LUMO_ERR_IO) {
            struct pollfd pf = {fd, POLLIN, 0};
            char b;
            if (poll(&pf, 1, 0) == 1 && recv(fd, &b, 1, MSG_PEEK) <= 0) {
                st = LUMO_OK;   /* closed without ERROR */
                break;
            }
            continue;
        }
        st = s;
        break;
    }
    free(c.buf);
    return st;
}

typedef struct hostile_case {
    const char *name;
    uint8_t     bytes[70000];
    size_t      len;
    int         shut;          /* shutdown(SHUT_WR) after sending */
    int         after_hello;   /* say HELLO first (and read WELCOME) */
    int         want[3];       /* allowed statuses (0 ends the list) */
} hostile_case;

static hostile_case hc;

static void hostile_reset(const char *name, int after_hello)
{
    memset(&hc, 0, sizeof hc);
    hc.name = name;
    hc.after_hello = after_hello;
}

static void want(int a, int b, int c)
{
    hc.want[0] = a, hc.want[1] = b, hc.want[2] = c;
}

/* One hostile connection: it must end with ERROR of an allowed status, then
 * be closed. */
static void run_hostile(const pkg_view *v)
{
    uint8_t hello[1024];
    char text[300];
    hello_opts h;
    int fd = tcp_connect(g_port), st, k, ok = 0;

    if (fd < 0) {
        problem("connect: %s", strerror(errno));
        check("hostile: %s", hc.name);
        return;
    }
    if (hc.after_hello) {
        conn c;
        lumo_net_frame fr;
        size_t n;
        memset(&h, 0, sizeof h);
        h.arena = (uint32_t)v->arena_need;
        h.max_payload = 65536;
        h.form = v->has_ivg ? LUMO_IVG_FORM_QUANTIZED : LUMO_NET_FORM_NONE;
        n = make_hello(&h, hello, sizeof hello);
        send_all(fd, hello, n);
        memset(&c, 0, sizeof c);
        c.fd = fd;
        c.cap = 1 << 16;
        c.buf = malloc(c.cap);
        if (conn_frame(&c, 65536, &fr, 5000) || fr.type != LUMO_NET_WELCOME)
            problem("no WELCOME");
        free(c.buf);
    }
    if (hc.len && send_all(fd, hc.bytes, hc.len))
        problem("sending the frame");
    if (hc.shut)
        shutdown(fd, SHUT_WR);
    st = read_error(fd, 5000, text, sizeof text);
    for (k = 0; k < 3 && hc.want[k]; k++)
        ok |= st == hc.want[k];
    if (!ok)
        problem("got %s, want %s", st < 0 ? "no answer (timeout)" : st == 0 ? "a close without ERROR"
                                                                            : lumo_strerror((lumo_status)st),
                lumo_strerror((lumo_status)hc.want[0]));
    if (!wait_closed(fd, 5000))
        problem("not closed after ERROR");
    close(fd);
    check("hostile: %s -> ERROR %s \"%s\", closed", hc.name,
          st > 0 ? lumo_strerror((lumo_status)st) : "-", text);
}

/* The well-behaved client: one request answered per step. */
static void good_step(conn *c, fetch *f)
{
    uint8_t out[64];
    lumo_net_frame fr;
    size_t n;

    if (fetch_done(f))
        return;
    if ((n = next_request(f, out)) && send_all(c->fd, out, n)) {
        problem("good client: send");
        return;
    }
    while (f->nq) {
        lumo_status st = conn_frame(c, f->max_payload, &fr, 5000);
        if (st) {
            problem("good client: %s", lumo_strerror(st));
            f->nq = 0;
            return;
        }
        if (on_answer(f, &fr))
            return;
    }
}

static void mode_hostile(const pkg_view *v, const run_opts *o)
{
    fetch good;
    conn gc;
    uint8_t pay[2048];
    uint32_t i;
    size_t n;
    run_opts go = *o;

    go.pipeline = 1;
    go.amounts = 1;   /* one batch / round per request: it lasts the whole test */
    fetch_init(&good, v, &go, 1);
    if (fetch_connect(&gc, &good, &go, 0, NULL)) {
        check("hostile: the well-behaved client connects");
        return;
    }
    good_step(&gc, &good);
    check("hostile: a well-behaved client connects and goes on between the hostile ones");

    hostile_reset("bad magic", 0);
    n = make_raw(LUMO_NET_BYE, NULL, 0, hc.bytes);
    hc.bytes[0] = 'X';
    hc.len = n;
    want(LUMO_ERR_CORRUPT, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("protocol version 2", 0);
    hc.len = make_raw(LUMO_NET_BYE, NULL, 0, hc.bytes);
    hc.bytes[2] = 2;
    want(LUMO_ERR_VERSION, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("payload length 1 MiB (past the server's 64 KiB)", 0);
    hc.len = make_raw(LUMO_NET_HELLO, NULL, 0, hc.bytes);
    lumo_wire_put_le32(hc.bytes + 4, 1u << 20);
    want(LUMO_ERR_LIMIT, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("payload length 4 GiB - 1", 0);
    hc.len = make_raw(LUMO_NET_HELLO, NULL, 0, hc.bytes);
    lumo_wire_put_le32(hc.bytes + 4, 0xffffffffu);
    want(LUMO_ERR_LIMIT, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    {
        hello_opts h;
        memset(&h, 0, sizeof h);
        h.arena = (uint32_t)v->arena_need;
        h.max_payload = 65536;
        h.form = LUMO_NET_FORM_NONE;
        for (i = 0; i < 3; i++) {
            static const char *names[] = {"HELLO with a bit flipped in its payload",
                                          "HELLO with a bit flipped in its CRC",
                                          "HELLO with a bit flipped in its type"};
            hostile_reset(names[i], 0);
            hc.len = make_hello(&h, hc.bytes, sizeof hc.bytes);
            hc.bytes[i == 0 ? 13 : i == 1 ? hc.len - 2 : 3] ^= 0x10;
            want(LUMO_ERR_CHECKSUM, 0, 0);
            run_hostile(v);
            good_step(&gc, &good);
        }
        hostile_reset("HELLO cut short, then the end of the stream", 0);
        hc.len = make_hello(&h, hc.bytes, sizeof hc.bytes) / 2;
        hc.shut = 1;
        want(LUMO_ERR_TRUNCATED, 0, 0);
        run_hostile(v);
        good_step(&gc, &good);

        hostile_reset("HELLO with a 20-byte payload", 0);
        memset(pay, 0, sizeof pay);
        hc.len = make_raw(LUMO_NET_HELLO, pay, 20, hc.bytes);
        want(LUMO_ERR_TRUNCATED, LUMO_ERR_CORRUPT, 0);
        run_hostile(v);
        good_step(&gc, &good);

        hostile_reset("HELLO for package 99", 0);
        h.package = 99;
        hc.len = make_hello(&h, hc.bytes, sizeof hc.bytes);
        h.package = 0;
        want(LUMO_ERR_RANGE, 0, 0);
        run_hostile(v);
        good_step(&gc, &good);

        hostile_reset("HELLO with an arena too small for the scene", 0);
        h.arena = 1000;
        hc.len = make_hello(&h, hc.bytes, sizeof hc.bytes);
        h.arena = (uint32_t)v->arena_need;
        want(LUMO_ERR_NOMEM, 0, 0);
        run_hostile(v);
        good_step(&gc, &good);

        hostile_reset("HELLO with max payload 100", 0);
        memset(pay, 0, 28);
        lumo_wire_put_le32(pay + 4, (uint32_t)v->arena_need);
        lumo_wire_put_le32(pay + 8, 100);
        pay[16] = LUMO_NET_FORM_NONE;
        hc.len = make_raw(LUMO_NET_HELLO, pay, 28, hc.bytes);
        want(LUMO_ERR_RANGE, LUMO_ERR_LIMIT, LUMO_ERR_CORRUPT);
        run_hostile(v);
        good_step(&gc, &good);

        hostile_reset("HELLO with 100 mesh cursors (more than LUMO_MAX_MESHES)", 0);
        memset(pay, 0, 28 + 400);
        lumo_wire_put_le32(pay + 4, (uint32_t)v->arena_need);
        lumo_wire_put_le32(pay + 8, 65536);
        pay[16] = LUMO_NET_FORM_NONE;
        lumo_wire_put_le32(pay + 20, v->id);
        lumo_wire_put_le32(pay + 24, 100);
        hc.len = make_raw(LUMO_NET_HELLO, pay, 28 + 400, hc.bytes);
        want(LUMO_ERR_LIMIT, 0, 0);
        run_hostile(v);
        good_step(&gc, &good);

        hostile_reset("HELLO twice", 1);
        hc.len = make_hello(&h, hc.bytes, sizeof hc.bytes);
        want(LUMO_ERR_STATE, 0, 0);
        run_hostile(v);
        good_step(&gc, &good);
    }

    hostile_reset("REQUEST before HELLO", 0);
    hc.len = make_request(LUMO_NET_GEOMETRY, 0, 0, 100, hc.bytes);
    want(LUMO_ERR_STATE, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("BYE before HELLO", 0);
    lumo_net_bye_encode(hc.bytes, sizeof hc.bytes, &hc.len);
    want(LUMO_ERR_STATE, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("a WELCOME from the client", 0);
    memset(pay, 0, 12);
    hc.len = make_raw(LUMO_NET_WELCOME, pay, 12, hc.bytes);
    want(LUMO_ERR_STATE, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("unknown frame type 9", 0);
    hc.len = make_raw(9, pay, 16, hc.bytes);
    want(LUMO_ERR_UNSUPPORTED, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("unknown type 200 with a 60000-byte payload (streamed through its CRC)", 0);
    {
        static uint8_t big[60000];
        for (i = 0; i < sizeof big; i++)
            big[i] = (uint8_t)rnd();
        hc.len = make_raw(200, big, sizeof big, hc.bytes);
    }
    want(LUMO_ERR_UNSUPPORTED, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("a 2000-byte HELLO", 0);
    memset(pay, 0, sizeof pay);
    hc.len = make_raw(LUMO_NET_HELLO, pay, 2000, hc.bytes);
    want(LUMO_ERR_CORRUPT, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("a 2000-byte frame with a bad CRC", 0);
    hc.len = make_raw(LUMO_NET_REQUEST, pay, 2000, hc.bytes);
    hc.bytes[100] ^= 1;
    want(LUMO_ERR_CHECKSUM, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("64 KiB of garbage", 0);
    for (i = 0; i < 65536; i++) {
        uint8_t b = (uint8_t)rnd();
        hc.bytes[i] = b == 'L' ? 'x' : b;
    }
    hc.bytes[0] = 0;
    hc.len = 65536;
    want(LUMO_ERR_CORRUPT, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("REQUEST for mesh 999", 1);
    hc.len = make_request(LUMO_NET_GEOMETRY, 999, 0, 1, hc.bytes);
    want(LUMO_ERR_RANGE, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("REQUEST with a cursor past the end", 1);
    hc.len = make_request(LUMO_NET_GEOMETRY, 0, v->mesh[0].h.batch_count + 1, 1, hc.bytes);
    want(LUMO_ERR_RANGE, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("REQUEST for 0 vertices", 1);
    memset(pay, 0, 16);
    hc.len = make_raw(LUMO_NET_REQUEST, pay, 16, hc.bytes);
    want(LUMO_ERR_RANGE, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("REQUEST on channel 7", 1);
    memset(pay, 0, 16);
    pay[0] = 7;
    lumo_wire_put_le32(pay + 12, 1);
    hc.len = make_raw(LUMO_NET_REQUEST, pay, 16, hc.bytes);
    want(LUMO_ERR_RANGE, LUMO_ERR_CORRUPT, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("PRT REQUEST (channel 3) without HELLO's PRT flag", 1);
    hc.len = make_request(LUMO_NET_PRT, 0, 12, 1, hc.bytes);
    want(LUMO_ERR_RANGE, 0, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("REQUEST of 12 bytes", 1);
    hc.len = make_raw(LUMO_NET_REQUEST, pay, 12, hc.bytes);
    want(LUMO_ERR_TRUNCATED, LUMO_ERR_CORRUPT, 0);
    run_hostile(v);
    good_step(&gc, &good);

    hostile_reset("an ERROR from the client", 1);
    lumo_net_error_encode(LUMO_ERR_IO, "client gives up", hc.bytes, sizeof hc.bytes, &hc.len);
    {   /* the server closes without answering */
        int fd = tcp_connect(g_port);
        char text[300];
        hello_opts h;
        uint8_t b[1024];
        memset(&h, 0, sizeof h);
        h.arena = (uint32_t)v->arena_need;
        h.max_payload = 65536;
        h.form = LUMO_NET_FORM_NONE;
        n = make_hello(&h, b, sizeof b);
        send_all(fd, b, n);
        send_all(fd, hc.bytes, hc.len);
        if (read_error(fd, 5000, text, sizeof text) != LUMO_OK)
            problem("the server answered a client's ERROR with an ERROR, or did not close");
        close(fd);
        check("hostile: an ERROR from the client -> closed without a reply");
    }
    good_step(&gc, &good);

    while (!fetch_done(&good) && !g_bad)
        good_step(&gc, &good);
    say_bye(&gc);
    conn_close(&gc);
    check_complete(&good, NULL, "hostile: the well-behaved client beside them");
    fetch_free(&good);
}

/* A client that never reads and one that never talks, beside a
 * well-behaved one: both closed after the server's idle timeout (idle_s),
 * the well-behaved one finishes. */
static void mode_idle(const pkg_view *v, const run_opts *o, int idle_s)
{
    fetch good;
    conn gc;
    run_opts go = *o;
    int fd_r, fd_i, small = 4096, st, r_closed = 0, i_err = -1, bye = 0;
    uint32_t i;
    double t0, t_r = 0, t_i = 0;
    hello_opts h;
    uint8_t b[1024];
    char text[300] = "";
    size_t n;
    struct sockaddr_in a;

    go.pipeline = 1;
    go.amounts = 1;
    fetch_init(&good, v, &go, 1);
    if (fetch_connect(&gc, &good, &go, 0, NULL)) {
        check("idle: the well-behaved client connects");
        return;
    }
    /* the reader that never reads: a small receive window from the start */
    fd_r = socket(AF_INET, SOCK_STREAM, 0);
    setsockopt(fd_r, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)g_port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd_r, (struct sockaddr *)&a, sizeof a) < 0)
        problem("connect: %s", strerror(errno));
    fd_i = tcp_connect(g_port);
    t0 = now_s();
    memset(&h, 0, sizeof h);
    h.arena = (uint32_t)v->arena_need;
    h.max_payload = 65536;
    h.form = v->has_ivg ? LUMO_IVG_FORM_FLOAT : LUMO_NET_FORM_NONE;
    n = make_hello(&h, b, sizeof b);
    send_all(fd_r, b, n);
    fcntl(fd_r, F_SETFL, O_NONBLOCK);
    for (i = 0; i < 400; i++) {   /* the whole scene, again and again: far more than any buffer */
        uint32_t m = i % (v->meshes + (v->has_ivg ? 1u : 0u));
        n = make_request(m < v->meshes ? LUMO_NET_GEOMETRY : LUMO_NET_LIGHTING, m < v->meshes ? m : 0, 0,
                         0x7fffffff, b);
        if (send(fd_r, b, n, MSG_NOSIGNAL) < 0)
            break;
    }
    /* the well-behaved client goes on; the others are watched without
     * reading a byte */
    while (now_s() - t0 < idle_s + 8 && (!r_closed || i_err < 0 || !fetch_done(&good))) {
        struct pollfd pf[2] = {{fd_r, POLLRDHUP, 0}, {fd_i, POLLIN, 0}};
        good_step(&gc, &good);
        if (fetch_done(&good) && !bye) {
            say_bye(&gc);
            bye = 1;
        }
        poll(pf, 2, 20);
        if (!r_closed && (pf[0].revents & (POLLHUP | POLLERR | POLLRDHUP))) {
            r_closed = 1;
            t_r = now_s() - t0;
        }
        if (i_err < 0 && (pf[1].revents & POLLIN)) {
            i_err = read_error(fd_i, 1000, text, sizeof text);
            t_i = now_s() - t0;
        }
    }
    if (!r_closed)
        problem("the client that never reads is still open after %.1f s", now_s() - t0);
    else if (t_r < idle_s * 0.9 || t_r > idle_s + 4)
        problem("closed after %.2f s, the idle timeout is %d s", t_r, idle_s);
    close(fd_r);
    check("idle: a client that never reads -> closed (reset) after %.2f s (idle timeout %d s)", t_r, idle_s);
    st = i_err;
    if (st <= 0)
        problem("the silent client got no ERROR");
    else if (t_i < idle_s * 0.9 || t_i > idle_s + 2)
        problem("ERROR after %.2f s, the idle timeout is %d s", t_i, idle_s);
    if (!wait_closed(fd_i, 3000))
        problem("the silent client is still open");
    close(fd_i);
    check("idle: a client that sends nothing -> ERROR %s \"%s\" after %.2f s, closed",
          st > 0 ? lumo_strerror((lumo_status)st) : "-", text, t_i);
    if (!bye)
        problem("the well-behaved client did not finish");
    conn_close(&gc);
    check_complete(&good, NULL, "idle: the well-behaved client beside them");
    fetch_free(&good);
}

/* ---- many clients at once -------------------------------------------------------- */

typedef struct mclient {
    conn   c;
    fetch  f;
    int    state;   /* 0 waiting for WELCOME, 1 fetching, 2 BYE sent, 3 done, -1 failed */
} mclient;

static void raise_nofile(size_t need)
{
    struct rlimit rl;
    if (getrlimit(RLIMIT_NOFILE, &rl) == 0 && rl.rlim_cur < need) {
        rl.rlim_cur = rl.rlim_max < need ? rl.rlim_max : need;
        setrlimit(RLIMIT_NOFILE, &rl);
    }
}

static void mclient_send(mclient *m)
{
    uint8_t out[64];
    size_t n;

    while ((n = next_request(&m->f, out)))
        if (send_all(m->c.fd, out, n))
            m->state = -1;
    if (fetch_done(&m->f) && m->state == 1) {
        lumo_net_bye_encode(out, sizeof out, &n);
        send_all(m->c.fd, out, n);
        m->state = 2;
    }
}

/* Everything buffered: frames decoded and checked. */
static void mclient_read(mclient *m)
{
    for (;;) {
        ssize_t n;
        conn_consume(&m->c);
        for (;;) {
            lumo_net_frame fr;
            size_t used = 0;
            lumo_status st = lumo_net_frame_decode(m->c.buf, m->c.len, m->f.max_payload, &fr, &used);
            if (st == LUMO_ERR_TRUNCATED)
                break;
            if (st) {
                problem("client: a frame the codec refuses: %s", lumo_strerror(st));
                m->state = -1;
                return;
            }
            m->c.used = used;
            if (m->state == 0) {
                if (fr.type != LUMO_NET_WELCOME) {
                    problem("client: frame %u instead of WELCOME", fr.type);
                    m->state = -1;
                    return;
                }
                m->state = 1;
            } else if (m->state == 1) {
                if (on_answer(&m->f, &fr)) {
                    m->state = -1;
                    return;
                }
            } else {
                problem("client: a frame after BYE");
                m->state = -1;
                return;
            }
            conn_consume(&m->c);
        }
        if (m->state == 1)
            mclient_send(m);
        if (m->state < 0)
            return;
        n = recv(m->c.fd, m->c.buf + m->c.len, m->c.cap - m->c.len, MSG_DONTWAIT);
        if (n > 0) {
            m->c.len += (size_t)n;
            m->c.in += (uint64_t)n;
            continue;
        }
        if (n == 0) {
            if (m->state == 2)
                m->state = 3;
            else {
                problem("client: closed by the server in state %d", m->state);
                m->state = -1;
            }
        } else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
            problem("client: recv: %s", strerror(errno));
            m->state = -1;
        }
        return;
    }
}

static void mode_many(const pkg_view *v, const run_opts *o, uint32_t count)
{
    mclient *cl = calloc(count, sizeof *cl);
    struct epoll_event ev[256];
    uint8_t hello[1024];
    hello_opts h;
    uint32_t i, done = 0, failed = 0, open_ok = 0;
    uint64_t bytes = 0;
    double t0 = now_s(), t1;
    int ep = epoll_create1(0);
    size_t n;

    raise_nofile(count + 64);
    memset(&h, 0, sizeof h);
    h.arena = (uint32_t)v->arena_need;
    h.max_payload = o->max_payload;
    h.form = o->form;
    n = make_hello(&h, hello, sizeof hello);
    for (i = 0; i < count; i++) {
        mclient *m = &cl[i];
        struct epoll_event e;
        fetch_init(&m->f, v, o, 0);
        if (conn_open(&m->c, g_port, o->max_payload + LUMO_NET_OVERHEAD + 64)) {
            problem("client %u: connect: %s", i, strerror(errno));
            m->state = -1;
            continue;
        }
        fcntl(m->c.fd, F_SETFL, O_NONBLOCK);
        e.events = EPOLLIN;
        e.data.u32 = i;
        epoll_ctl(ep, EPOLL_CTL_ADD, m->c.fd, &e);
        open_ok++;
    }
    t1 = now_s();
    for (i = 0; i < count; i++)
        if (cl[i].state == 0 && send_all(cl[i].c.fd, hello, n))
            cl[i].state = -1;
    while (done + failed < count && now_s() - t0 < 50) {
        int k, ne = epoll_wait(ep, ev, 256, 200);
        for (k = 0; k < ne; k++) {
            mclient *m = &cl[ev[k].data.u32];
            if (m->state < 0 || m->state == 3)
                continue;
            mclient_read(m);
            if (m->state == 3 || m->state < 0) {
                epoll_ctl(ep, EPOLL_CTL_DEL, m->c.fd, NULL);
                close(m->c.fd);
                m->c.fd = -1;
            }
        }
        done = failed = 0;
        for (i = 0; i < count; i++)
            done += cl[i].state == 3, failed += cl[i].state < 0;
    }
    for (i = 0; i < count; i++) {
        if (cl[i].state == 3) {
            uint32_t m;
            for (m = 0; m < v->meshes; m++)
                if (cl[i].f.held[m] != v->mesh[m].h.batch_count)
                    problem("client %u: mesh %u incomplete", i, m);
            bytes += cl[i].f.record_bytes;
        }
        conn_close(&cl[i].c);
    }
    if (done != count)
        problem("%u of %u clients finished (%u failed, %u connected)", done, count, failed, open_ok);
    check("many: %u clients at once, every one to the end: %u finished in %.2f s (connected in %.2f s), "
          "%.1f MB of checked records",
          count, done, now_s() - t0, t1 - t0, (double)bytes / 1e6);
    close(ep);
    free(cl);
}

/* ---- the serial line ----------------------------------------------------------------- */

/* Random bytes, sometimes with a lone 'L' or a bogus "LS" header, before a
 * frame: the server must resynchronise on the frame after them. */
static size_t garbage(uint8_t *out)
{
    size_t n = 0, len;
    uint64_t r = rnd();

    if (r % 3)
        return 0;
    len = 1 + (r >> 8) % 24;
    while (n < len) {
        uint8_t b = (uint8_t)rnd();
        out[n++] = b == 'L' ? 'l' : b;
    }
    if ((r >> 20) % 4 == 0)
        out[n++] = 'L';   /* a lone half magic */
    if ((r >> 24) % 8 == 0) {   /* a bogus header: magic, version, type, a length */
        out[n++] = 'L', out[n++] = 'S', out[n++] = 1, out[n++] = 3;
        lumo_wire_put_le32(out + n, (uint32_t)((r >> 32) % 200));
        n += 4;
    }
    return n;
}

static void mode_serial(const pkg_view *v, const run_opts *o)
{
    fetch f;
    conn c;
    uint8_t out[2048];
    hello_opts h;
    int ready = 0;
    uint64_t resyncs = 0, skipped = 0, timeouts = 0, ignored = 0, sent_garbage = 0;
    double t0 = now_s(), last = now_s();
    size_t n;

    fetch_init(&f, v, o, 1);
    f.pipeline = 1;
    if (conn_open(&c, g_serial_port, o->max_payload + LUMO_NET_OVERHEAD + 64)) {
        problem("connect to the serial port %d", g_serial_port);
        check("serial");
        return;
    }
    memset(&h, 0, sizeof h);
    h.arena = (uint32_t)v->arena_need;
    h.max_payload = o->max_payload;
    h.form = o->form;
    n = garbage(out);
    n += make_hello(&h, out + n, sizeof out - n);
    sent_garbage += n;
    send_all(c.fd, out, n);
    while (!fetch_done(&f) && now_s() - t0 < 60) {
        lumo_net_frame fr;
        size_t used = 0;
        lumo_status st;
        int resend = 0;

        conn_consume(&c);
        st = lumo_net_frame_decode(c.buf, c.len, o->max_payload, &fr, &used);
        if (st == LUMO_ERR_TRUNCATED) {
            if (conn_fill(&c, 300, 0) <= 0 || now_s() - last > 0.6) {
                timeouts++;
                resend = 1;   /* lost: a dropped byte keeps a frame waiting */
                if (c.len) {
                    size_t k = lumo_net_resync(c.buf, c.len, 1);
                    skipped += k;
                    memmove(c.buf, c.buf + k, c.len - k);
                    c.len -= k;
                }
            }
        } else if (st) {
            size_t k = lumo_net_resync(c.buf, c.len, 1);
            resyncs++;
            skipped += k;
            memmove(c.buf, c.buf + k, c.len - k);
            c.len -= k;
            resend = 1;
        } else {
            c.used = used;
            last = now_s();
            if (fr.type == LUMO_NET_WELCOME) {
                if (!ready) {
                    check_welcome(v, &fr, NULL);
                    ready = 1;
                }
                resend = f.nq == 0;
            } else if (!ready || f.nq == 0) {
                ignored++;
            } else {
                /* answers to a request sent again come twice: what is
                 * already held (or out of turn) is dropped */
                const pending *p = &f.q[0];
                lumo_net_data d;
                int stale = 0;
                if (fr.type == LUMO_NET_DATA && lumo_net_data_decode(&fr, &d) == LUMO_OK)
                    stale = d.channel != p->channel ||
                            (d.channel == LUMO_NET_GEOMETRY ? d.mesh != p->mesh || d.first != f.held[d.mesh]
                                                            : d.first != f.rounds_held);
                if (fr.type == LUMO_NET_END) {
                    lumo_net_end e;
                    stale = lumo_net_end_decode(&fr, &e) || e.channel != p->channel ||
                            (p->channel == LUMO_NET_GEOMETRY ? f.held[p->mesh] != v->mesh[p->mesh].h.batch_count
                                                               : f.rounds_held != v->rounds);
                }
                if (stale) {
                    ignored++;
                } else {
                    int bad = g_bad;
                    if (on_answer(&f, &fr)) {
                        if (g_bad > bad && fr.type == LUMO_NET_DATA) {
                            /* a split round's duplicate: not an error on a serial line */
                            g_bad = bad;
                            ignored++;
                        }
                        f.nq = 0;
                    }
                    resend = f.nq == 0;
                }
            }
        }
        if (resend) {
            n = garbage(out);
            sent_garbage += n;
            if (!ready) {
                n += make_hello(&h, out + n, sizeof out - n);
            } else {
                fetch_reset_link(&f);
                {
                    size_t r = next_request(&f, out + n);
                    if (!r)
                        continue;
                    n += r;
                }
            }
            send_all(c.fd, out, n);
            last = now_s();
        }
    }
    say_bye(&c);
    conn_close(&c);
    if (o->expect_loss && resyncs + timeouts == 0)
        problem("the server damages frames (--loss), yet none was refused or lost");
    check("serial: every record through a lossy line: %llu frames refused and resynchronised over %llu bytes, "
          "%llu timeouts asked again, %llu stale frames dropped, %llu bytes sent with garbage",
          (unsigned long long)resyncs, (unsigned long long)skipped, (unsigned long long)timeouts,
          (unsigned long long)ignored, (unsigned long long)sent_garbage);
    f.record_bytes = 0;   /* repeated answers: compare the bytes, not their count */
    {
        uint32_t m;
        for (m = 0; m < v->meshes; m++)
            f.record_bytes += v->mesh[m].len - v->mesh[m].h.header_bytes;
        if (v->has_ivg && o->form != LUMO_NET_FORM_NONE)
            f.record_bytes += v->bundle_len[o->form] - BUNDLE_HEAD;
    }
    check_complete(&f, NULL, "serial");
    fetch_free(&f);
}

/* ---- --max-clients ------------------------------------------------------------------- */

static void mode_full_limit(const pkg_view *v, const run_opts *o, uint32_t count)
{
    conn *cs = calloc(count, sizeof *cs);
    uint8_t hello[1024];
    char text[300];
    hello_opts h;
    uint32_t i;
    int fd, st;
    size_t n;

    memset(&h, 0, sizeof h);
    h.arena = (uint32_t)v->arena_need;
    h.max_payload = o->max_payload;
    h.form = LUMO_NET_FORM_NONE;
    n = make_hello(&h, hello, sizeof hello);
    for (i = 0; i < count; i++) {
        lumo_net_frame fr;
        if (conn_open(&cs[i], g_port, 1 << 17) || send_all(cs[i].fd, hello, n) ||
            conn_frame(&cs[i], 1 << 16, &fr, 5000) || fr.type != LUMO_NET_WELCOME)
            problem("client %u of %u: no WELCOME", i, count);
    }
    fd = tcp_connect(g_port);
    st = read_error(fd, 5000, text, sizeof text);
    if (st != LUMO_ERR_LIMIT)
        problem("client %u got %s, want ERROR LIMIT", count + 1, st > 0 ? lumo_strerror((lumo_status)st) : "none");
    if (!wait_closed(fd, 3000))
        problem("the refused client is still open");
    close(fd);
    for (i = 0; i < count; i++)
        conn_close(&cs[i]);
    free(cs);
    check("--max-clients %u: client %u gets ERROR LIMIT \"%s\" and is closed", count, count + 1, text);
}

/* ---- link emulation -------------------------------------------------------------------- */

static void mode_timing(const pkg_view *v, const run_opts *o, double kbit, double latency_ms)
{
    fetch f;
    conn c;
    run_opts t = *o;
    double t0 = now_s(), t1, t2, expect_rate, expect_lat, need;

    t.pipeline = 1;
    t.amounts = 2;   /* everything at once: one request per mesh and one for the lighting */
    fetch_init(&f, v, &t, 1);
    if (fetch_connect(&c, &f, &t, 0, NULL)) {
        check("timing: WELCOME");
        return;
    }
    t1 = now_s();
    fetch_pump(&c, &f, t0 + 50);
    t2 = now_s();
    say_bye(&c);
    conn_close(&c);
    /* One request at a time: each waits a round trip (2 x latency), then
     * its bytes go at the rate. The bucket starts full and refills during
     * each wait, up to its burst (20 ms of the rate, at least 1500 bytes):
     * that much may leave at once. */
    {
        double bps = kbit * 1000.0 / 8.0, burst = bps * 0.02 < 1500 ? 1500 : bps * 0.02;
        double refill = bps * 2.0 * latency_ms / 1000.0 + 200.0;   /* per wait, and a little slack */
        double paced = (double)c.in - burst - (double)(f.requests + 1) * (refill < burst ? refill : burst);
        expect_rate = kbit > 0 && paced > 0 ? paced * 8.0 / (kbit * 1000.0) : 0;
    }
    expect_lat = (double)(f.requests + 1) * 2.0 * latency_ms / 1000.0;
    need = expect_rate + expect_lat;
    if (t1 - t0 < 2.0 * latency_ms / 1000.0 * 0.95)
        problem("WELCOME after %.3f s, before the round trip of 2 x %.0f ms", t1 - t0, latency_ms);
    /* the first burst (20 ms of the rate, at least 1500 bytes) may go at once */
    if (t2 - t0 < need * 0.95)
        problem("%llu bytes in %.3f s: faster than %.0f kbit/s with %.0f ms latency allow (%.3f s)",
                (unsigned long long)c.in, t2 - t0, kbit, latency_ms, need);
    if (t2 - t0 > need * 2.0 + 1.0 + (double)c.in * 8.0 / (kbit * 1000.0))
        problem("%llu bytes in %.3f s: much slower than the emulated link (%.3f s)", (unsigned long long)c.in,
                t2 - t0, need);
    check("timing: %llu bytes over %.0f kbit/s, %.0f ms latency, one request at a time: %.2f s (at least %.2f s "
          "on that link; WELCOME after %.0f ms)",
          (unsigned long long)c.in, kbit, latency_ms, t2 - t0, need, (t1 - t0) * 1000);
    check_complete(&f, NULL, "timing");
    fetch_free(&f);
}

/* ---- main ---------------------------------------------------------------------------- */

static void on_alarm(int sig)
{
    (void)sig;
    static const char msg[] = "serve_client: the whole run took too long\nRESULT: 0 passed, 1 failed\n";
    if (write(1, msg, sizeof msg - 1) < 0)
        _exit(2);
    _exit(2);
}

int main(int argc, char **argv)
{
    pkg_view v;
    run_opts o;
    const char *mode;
    double a1 = 0, a2 = 0;
    int i, idle = 0;

    if (argc < 4) {
        fprintf(stderr, "usage: serve_client MODE PORT[,SERIAL_PORT] PACKAGE [ARGS] [options]\n");
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    signal(SIGPIPE, SIG_IGN);
    signal(SIGALRM, on_alarm);
    alarm(120);
    mode = argv[1];
    if (sscanf(argv[2], "%d,%d", &g_port, &g_serial_port) < 1)
        return 2;
    if (pkg_load(&v, argv[3]))
        return 2;
    memset(&o, 0, sizeof o);
    o.max_payload = 65536;
    o.pipeline = 2;
    o.form = v.has_ivg ? LUMO_IVG_FORM_QUANTIZED : LUMO_NET_FORM_NONE;
    o.cuts = 20;
    i = 4;
    if (i < argc && argv[i][0] != '-')
        a1 = atof(argv[i++]);
    if (i < argc && argv[i][0] != '-')
        a2 = atof(argv[i++]);
    for (; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--max-payload"))
            o.max_payload = (uint32_t)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--pipeline"))
            o.pipeline = (uint32_t)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--seed"))
            g_rng = (uint64_t)atoll(argv[i + 1]);
        else if (!strcmp(argv[i], "--cuts"))
            o.cuts = (uint32_t)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--idle"))
            idle = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--expect-loss"))
            o.expect_loss = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--package"))
            o.package = (uint32_t)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--form"))
            o.form = !v.has_ivg || argv[i + 1][0] == 'n' ? LUMO_NET_FORM_NONE
                     : argv[i + 1][0] == 'f'            ? LUMO_IVG_FORM_FLOAT
                                                        : LUMO_IVG_FORM_QUANTIZED;
        else {
            fprintf(stderr, "serve_client: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    if (!strcmp(mode, "full"))
        mode_full(&v, &o, "full");
    else if (!strcmp(mode, "resume"))
        mode_resume(&v, &o);
    else if (!strcmp(mode, "hostile"))
        mode_hostile(&v, &o);
    else if (!strcmp(mode, "idle"))
        mode_idle(&v, &o, idle);
    else if (!strcmp(mode, "many"))
        mode_many(&v, &o, a1 > 0 ? (uint32_t)a1 : 100);
    else if (!strcmp(mode, "serial"))
        mode_serial(&v, &o);
    else if (!strcmp(mode, "full-limit"))
        mode_full_limit(&v, &o, a1 > 0 ? (uint32_t)a1 : 2);
    else if (!strcmp(mode, "timing"))
        mode_timing(&v, &o, a1, a2);
    else {
        fprintf(stderr, "serve_client: unknown mode %s\n", mode);
        return 2;
    }
    pkg_unload(&v);
    printf("RESULT: %d passed, %d failed\n", g_pass, g_fail);
    return g_fail ? 1 : 0;
}
