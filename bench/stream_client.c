/*
 * bench/stream_client.c — the measuring client of `make bench-stream`
 * (bench/stream.sh): lumo-server seen from the client, without drawing.
 *
 *   lumo-bench-stream run HOST:PORT [options]
 *       One client through the SDK's protocol driver and session, exactly as
 *       lumo-client streams (lumo/net_client.h), but no renderer: prints one
 *       line of key=value with microsecond times from just before connect():
 *       welcome, first picture (every base mesh and the grid's corners, as
 *       lumo-client defines it), geometry complete, lighting complete, full
 *       scene; bytes; requests; and the client's own work: time (wall and
 *       this thread's CPU) inside lumo_net_client_on_frame for DATA (records
 *       applied + push-pull) and
 *       inside lumo_session_update alone (push-pull; the driver's calls, timed
 *       through the linker's --wrap: wall time summed, and this thread's CPU
 *       time summed and its median call).
 *       Options as lumo-client: --order interleaved|geometry|lighting,
 *       --vertices N, --rounds K, --pipeline N, --target-ms T, --float,
 *       --no-smoothing, --package N; and --no-ivg (HELLO asks for no lighting),
 *       --max-payload B (default 1 MiB as lumo-client), --arena MIB,
 *       --trace (every request and DATA frame on stderr, with its time).
 *
 *   lumo-bench-stream load HOST:PORT CLIENTS REPEATS [--max-payload B]
 *       CLIENTS connections at once, each fetching the whole scene REPEATS
 *       times (every mesh and the lighting from cursor 0 in one request each,
 *       two fetches in flight) then BYE: the codec's framing only, payloads
 *       skipped unchecked, so the client costs little beside the server.
 *       Prints clients, bytes, seconds, MB/s.
 *
 * Every wait is bounded (an alarm for the whole run).
 */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>
#include "../net/host/net_socket.h"
#include "lumo_host/options.h"
#include "lumo/arena.h"
#include "lumo/ivg.h"
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo/net.h"
#include "lumo/net_client.h"
#include "lumo/session.h"
#include "lumo/wire.h"

static int64_t now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static uint32_t clock_ms(void *ctx)
{
    (void)ctx;
    return (uint32_t)(now_us() / 1000);
}

/* push-pull: every call the driver makes, timed (-Wl,--wrap=lumo_session_update) */
/* This thread's CPU time (µs): what a call cost, whatever else runs on the
 * machine (a shared host descheduling us does not count). */
static int64_t cpu_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

#define PP_KEEP 65536
static int64_t g_pp_us, g_pp_cpu_us;
static uint32_t g_pp_calls;
static uint32_t g_pp_each[PP_KEEP];   /* each call's CPU µs, for the median */
int __real_lumo_session_update(lumo_session *s);
int __wrap_lumo_session_update(lumo_session *s);
int __wrap_lumo_session_update(lumo_session *s)
{
    int64_t t = now_us(), c = cpu_us(), d;
    int r = __real_lumo_session_update(s);
    g_pp_us += now_us() - t;
    d = cpu_us() - c;
    g_pp_cpu_us += d;
    if (g_pp_calls < PP_KEEP)
        g_pp_each[g_pp_calls] = (uint32_t)d;
    g_pp_calls++;
    return r;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* The median push-pull call (CPU µs). */
static uint32_t pp_median(void)
{
    uint32_t n = g_pp_calls < PP_KEEP ? g_pp_calls : PP_KEEP;

    if (!n)
        return 0;
    qsort(g_pp_each, n, sizeof *g_pp_each, cmp_u32);
    return g_pp_each[n / 2];
}

/* A TCP connection to "HOST:PORT" through the desktop transport (net/host). */
static int tcp_connect(const char *spec)
{
    char err[256];
    return host_net_connect(spec, err, sizeof err);
}

/* ---- run: one client through the driver -------------------------------------------- */

typedef struct run_opts {
    const char *addr;
    lumo_net_policy policy;
    int use_float, no_ivg, no_smoothing, trace;
    uint32_t max_payload, arena_mib, package;
} run_opts;

/* The numeric options of run, each a u32 in [lo, hi] of run_opts. */
static const struct u32_opt {
    const char *name;
    uint32_t    lo, hi;
    size_t      at;   /* offsetof in run_opts */
} k_u32_opts[] = {
    {"--vertices", 1, 1u << 28, offsetof(run_opts, policy.vertices)},
    {"--rounds", 1, 1u << 20, offsetof(run_opts, policy.rounds)},
    {"--pipeline", 1, 8, offsetof(run_opts, policy.pipeline)},
    {"--target-ms", 1, 60000, offsetof(run_opts, policy.target_ms)},
    {"--max-payload", 4096, 1u << 24, offsetof(run_opts, max_payload)},
    {"--package", 0, 0x7fffffff, offsetof(run_opts, package)},
    {"--arena", 1, 4095, offsetof(run_opts, arena_mib)},
};

/* Option a with value v when it is one of k_u32_opts: 1 taken, 0 not one
 * of them, -1 refused (through the strict parser, lumo_host/options.h). */
static int take_u32(run_opts *o, const char *a, const char *v, char *err, size_t errlen)
{
    for (size_t k = 0; k < sizeof k_u32_opts / sizeof k_u32_opts[0]; k++) {
        const struct u32_opt *u = &k_u32_opts[k];
        uint32_t *field = (uint32_t *)(void *)((char *)o + u->at);
        if (!strcmp(a, u->name))
            return host_opt_u32(u->name, v, u->lo, u->hi, field, err, errlen) ? -1 : 1;
    }
    return 0;
}

static int parse_run(int argc, char **argv, run_opts *o, char *err, size_t errlen)
{
    int i, k;

    memset(o, 0, sizeof *o);
    o->max_payload = 1u << 20;
    o->arena_mib = 256;
    if (argc < 3)
        return snprintf(err, errlen, "run needs the server's HOST:PORT"), -1;
    o->addr = argv[2];
    for (i = 3; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--float")) o->use_float = 1;
        else if (!strcmp(a, "--no-ivg")) o->no_ivg = 1;
        else if (!strcmp(a, "--no-smoothing")) o->no_smoothing = 1;
        else if (!strcmp(a, "--trace")) o->trace = 1;
        else if (!v) return snprintf(err, errlen, "%s: unknown option or one without its value", a), -1;
        else if (!strcmp(a, "--order")) {
            static const char *const orders[] = {"interleaved", "geometry", "lighting"};
            static const lumo_net_order order_of[] = {LUMO_NET_ORDER_INTERLEAVED, LUMO_NET_ORDER_GEOMETRY_FIRST,
                                                      LUMO_NET_ORDER_LIGHTING_FIRST};
            if (host_opt_choice("--order", v, orders, 3, &k, err, errlen))
                return -1;
            o->policy.order = order_of[k];
            i++;
        }
        else if ((k = take_u32(o, a, v, err, errlen)) != 0) {
            if (k < 0)
                return -1;
            i++;
        }
        else return snprintf(err, errlen, "%s: unknown option", a), -1;
    }
    return 0;
}

static int geometry_done(const lumo_net_client *d)
{
    uint32_t m;

    for (m = 0; m < d->mesh_count; m++)
        if (d->held[m] < d->batches[m])
            return 0;
    return 1;
}

static int lighting_done(const lumo_net_client *d)
{
    return !d->has_ivg || d->rounds_held >= d->rounds_total;
}

static int first_picture(const lumo_net_client *d)
{
    uint32_t m;

    for (m = 0; m < d->mesh_count; m++)
        if (d->held[m] == 0)
            return 0;
    return !d->has_ivg || d->rounds_held > 0;
}

static int mode_run(int argc, char **argv)
{
    static lumo_session ses;
    static lumo_net_client drv;
    static lumo_arena arena;
    lumo_session_config scfg;
    lumo_net_client_config ncfg;
    run_opts o;
    size_t bytes, cap, len = 0, n;
    uint8_t *mem, *rx, out[1024];
    uint64_t in = 0, outb = 0, geo_bytes = 0, light_bytes = 0;
    int64_t geo_apply_us = 0, light_apply_us = 0, geo_cpu_us = 0, light_cpu_us = 0;
    uint32_t requests = 0, frames = 0, data_frames = 0;
    int64_t t0, t_welcome = -1, t_first = -1, t_geo = -1, t_light = -1, t_full = -1, apply_us = 0;
    int fd, rc = 1;
    char err[256];

    if (parse_run(argc, argv, &o, err, sizeof err)) {
        fprintf(stderr, "lumo-bench-stream run: error: %s\n", err);
        return 2;
    }
    bytes = (size_t)o.arena_mib << 20;
    cap = o.max_payload + LUMO_NET_OVERHEAD;
    if (!(mem = malloc(bytes)) || !(rx = malloc(cap)))
        return 1;
    lumo_arena_init(&arena, mem, bytes);
    memset(&scfg, 0, sizeof scfg);
    scfg.lod.ppm = LUMO_SESSION_LOD_ALL;
    scfg.ivg_flags = o.no_smoothing ? 0u : LUMO_IVG_SMOOTH;
    memset(&ncfg, 0, sizeof ncfg);
    ncfg.package = o.package;
    ncfg.arena_bytes = (uint32_t)(bytes > 0xffffffffu ? 0xffffffffu : bytes);
    ncfg.max_payload = o.max_payload;
    ncfg.width = 320, ncfg.height = 240;
    ncfg.ivg_form = o.no_ivg ? LUMO_NET_FORM_NONE : o.use_float ? LUMO_IVG_FORM_FLOAT : LUMO_IVG_FORM_QUANTIZED;
    ncfg.smoothing = !o.no_smoothing;
    ncfg.policy = o.policy;
    ncfg.first_picture = 1;   /* lumo-server over TCP, as lumo-client does (protocol.md §2 HELLO) */
    ncfg.clock = clock_ms;
    if (lumo_session_init(&ses, &scfg, &arena) || lumo_net_client_init(&drv, &ses, &ncfg)) {
        fprintf(stderr, "lumo-bench-stream: session/driver init failed\n");
        return 1;
    }
    t0 = now_us();
    if ((fd = tcp_connect(o.addr)) < 0) {
        fprintf(stderr, "lumo-bench-stream: cannot connect to %s\n", o.addr);
        return 1;
    }
    if (lumo_net_client_hello(&drv, out, sizeof out, &n) || host_net_write_all(fd, out, n))
        goto done;
    outb += n;
    while (drv.state != LUMO_NET_DONE) {
        size_t at = 0, used;
        ssize_t got;
        lumo_status st;

        do {   /* every request the driver wants to send now */
            if ((st = lumo_net_client_next(&drv, out, sizeof out, &n))) {
                fprintf(stderr, "lumo-bench-stream: %s\n", lumo_strerror(st));
                goto done;
            }
            if (n && host_net_write_all(fd, out, n))
                goto done;
            if (o.trace && n == LUMO_NET_OVERHEAD + 16)
                fprintf(stderr, "%8.1f ms  request %s mesh %u cursor %u amount %u (%u in flight)\n",
                        (now_us() - t0) / 1e3, out[8] == LUMO_NET_GEOMETRY ? "geometry" : "lighting",
                        lumo_wire_le32(out + 12), lumo_wire_le32(out + 16), lumo_wire_le32(out + 20), drv.npending);
            outb += n;
            requests += n == LUMO_NET_OVERHEAD + 16;
        } while (n && drv.state != LUMO_NET_DONE);
        if (drv.state == LUMO_NET_DONE)
            break;
        do
            got = read(fd, rx + len, cap - len);
        while (got < 0 && errno == EINTR);
        if (got <= 0) {
            fprintf(stderr, "lumo-bench-stream: connection ended before the scene was complete\n");
            goto done;
        }
        len += (size_t)got;
        in += (uint64_t)got;
        for (;;) {
            lumo_net_frame f;
            int64_t t, t2, c1, c2;
            st = lumo_net_frame_decode(rx + at, len - at, drv.cfg.max_payload, &f, &used);
            if (st == LUMO_ERR_TRUNCATED)
                break;
            if (st) {
                fprintf(stderr, "lumo-bench-stream: frame: %s\n", lumo_strerror(st));
                goto done;
            }
            t = now_us(), c1 = cpu_us();
            if ((st = lumo_net_client_on_frame(&drv, &f))) {
                fprintf(stderr, "lumo-bench-stream: frame type %u: %s\n", f.type, lumo_strerror(st));
                goto done;
            }
            t2 = now_us(), c2 = cpu_us();
            frames++;
            if (f.type == LUMO_NET_DATA) {
                if (o.trace)
                    fprintf(stderr, "%8.1f ms  DATA %s mesh %u first %u count %u, %u bytes, applied in %.2f ms\n",
                            (t - t0) / 1e3, f.payload[0] == LUMO_NET_GEOMETRY ? "geometry" : "lighting",
                            lumo_wire_le32(f.payload + 4), lumo_wire_le32(f.payload + 8),
                            lumo_wire_le32(f.payload + 12), f.len, (t2 - t) / 1e3);
                data_frames++;
                apply_us += t2 - t;
                if (f.payload[0] == LUMO_NET_GEOMETRY) {
                    geo_bytes += f.len - LUMO_NET_DATA_HEAD;
                    geo_apply_us += t2 - t;
                    geo_cpu_us += c2 - c1;
                } else {
                    light_bytes += f.len - LUMO_NET_DATA_HEAD;
                    light_apply_us += t2 - t;
                    light_cpu_us += c2 - c1;
                }
            }
            if (f.type == LUMO_NET_WELCOME && t_welcome < 0)
                t_welcome = t2 - t0;
            if (drv.state == LUMO_NET_READY || drv.state == LUMO_NET_DONE) {
                if (t_first < 0 && first_picture(&drv))
                    t_first = t2 - t0;
                if (t_geo < 0 && geometry_done(&drv))
                    t_geo = t2 - t0;
                if (t_light < 0 && lighting_done(&drv))
                    t_light = t2 - t0;
                if (t_full < 0 && t_geo >= 0 && t_light >= 0)
                    t_full = t2 - t0;
            }
            at += used;
        }
        memmove(rx, rx + at, len - at);
        len -= at;
    }
    rc = 0;
done:
    if (rc == 0) {
        lumo_net_progress p;
        lumo_net_client_progress(&drv, &p);
        printf("welcome_us=%lld first_us=%lld geometry_us=%lld lighting_us=%lld full_us=%lld bytes_in=%llu "
               "bytes_out=%llu geometry_bytes=%llu lighting_bytes=%llu requests=%u frames=%u data_frames=%u "
               "vertices=%u rounds=%u apply_us=%lld geometry_apply_us=%lld lighting_apply_us=%lld "
               "geometry_apply_cpu_us=%lld lighting_apply_cpu_us=%lld pushpull_us=%lld "
               "pushpull_calls=%u pushpull_cpu_us=%lld pushpull_cpu_median_us=%u rtt_ms=%u\n",
               (long long)t_welcome, (long long)t_first, (long long)t_geo, (long long)t_light, (long long)t_full,
               (unsigned long long)in, (unsigned long long)outb, (unsigned long long)geo_bytes,
               (unsigned long long)light_bytes, requests, frames, data_frames, p.vertices, p.rounds,
               (long long)apply_us, (long long)geo_apply_us, (long long)light_apply_us, (long long)geo_cpu_us,
               (long long)light_cpu_us, (long long)g_pp_us, g_pp_calls,
               (long long)g_pp_cpu_us, pp_median(), drv.costs.rtt_ms);
    }
    close(fd);
    free(rx);
    free(mem);
    return rc;
}

/* ---- load: many lean clients at once ------------------------------------------------ */

#define LOAD_INFLIGHT 2   /* whole-scene fetches in flight per client (<= 16 requests) */

typedef struct lclient {
    int fd, state;                 /* 0 WELCOME awaited, 1 fetching, 2 BYE sent, 3 done, -1 failed */
    uint32_t sent, done;           /* fetches asked / completed */
    uint32_t answer;               /* answers of the current fetch completed */
    uint32_t got;                  /* batches / rounds of the current answer */
    uint8_t head[LUMO_NET_HEADER + LUMO_NET_DATA_HEAD];
    uint32_t head_len, need;       /* head bytes held / wanted */
    uint32_t skip;                 /* payload + CRC bytes still to skip */
    uint8_t *welcome;              /* the first WELCOME's frame (scene sizes) */
    uint32_t welcome_len;
} lclient;

static struct {
    uint32_t meshes, batches[LUMO_MAX_MESHES], rounds;
    int known;
} g_scene;

/* The scene's sizes from a WELCOME: fed to a session as the driver does. */
static int learn_scene(const uint8_t *frame, uint32_t len)
{
    static lumo_session s;
    static lumo_arena a;
    static uint8_t *mem;
    lumo_session_config cfg;
    lumo_net_frame f;
    lumo_net_welcome w;
    lumo_net_msg m;
    lumo_pmesh_header h;
    size_t used, at = 0;
    uint32_t i;
    const lumo_pkg_info *info;

    if (!mem && !(mem = malloc(64u << 20)))
        return -1;
    lumo_arena_init(&a, mem, 64u << 20);
    memset(&cfg, 0, sizeof cfg);
    cfg.lod.ppm = LUMO_SESSION_LOD_ALL;
    if (lumo_session_init(&s, &cfg, &a) || lumo_net_frame_decode(frame, len, 1u << 24, &f, &used) ||
        lumo_net_welcome_decode(&f, &w))
        return -1;
    while (lumo_net_welcome_next(&w, &at, &m) == LUMO_OK)
        if (lumo_session_feed(&s, m.type, m.index, m.data, m.len))
            return -1;
    if (!(info = lumo_session_info(&s)))
        return -1;
    g_scene.meshes = info->mesh_count;
    for (i = 0; i < g_scene.meshes; i++) {
        if (lumo_session_stream_header(&s, i, &h))
            return -1;
        g_scene.batches[i] = h.batch_count;
    }
    g_scene.rounds = lumo_session_ivg_order(&s) ? lumo_session_ivg_order(&s)->rounds : 0;
    g_scene.known = 1;
    return 0;
}

static uint32_t answers_per_fetch(void)
{
    return g_scene.meshes + (g_scene.rounds ? 1u : 0u);
}

static int send_fetch(lclient *c)
{
    uint8_t out[(LUMO_NET_OVERHEAD + 16) * (LUMO_MAX_MESHES + 1)];
    size_t n = 0, k;
    uint32_t m;
    lumo_net_request r;

    memset(&r, 0, sizeof r);
    for (m = 0; m < g_scene.meshes; m++) {
        r.channel = LUMO_NET_GEOMETRY, r.mesh = m, r.cursor = 0, r.amount = 0x7fffffffu;
        if (lumo_net_request_encode(&r, out + n, sizeof out - n, &k))
            return -1;
        n += k;
    }
    if (g_scene.rounds) {
        r.channel = LUMO_NET_LIGHTING, r.mesh = 0, r.cursor = 0, r.amount = 0x7fffffffu;
        if (lumo_net_request_encode(&r, out + n, sizeof out - n, &k))
            return -1;
        n += k;
    }
    c->sent++;
    return host_net_write_all(c->fd, out, n);
}

/* A frame head is complete: account for it. 0 fine, -1 off the protocol. */
static int on_head(lclient *c, uint32_t reps)
{
    if (c->head[3] == LUMO_NET_DATA && c->state == 1) {
        const uint8_t *d = c->head + LUMO_NET_HEADER;
        uint32_t total = d[0] == LUMO_NET_GEOMETRY ? g_scene.batches[lumo_wire_le32(d + 4)] : g_scene.rounds;
        c->got += lumo_wire_le32(d + 12);
        if (c->got >= total) {
            c->got = 0;
            if (++c->answer == answers_per_fetch()) {
                c->answer = 0;
                c->done++;
                if (c->sent < reps && send_fetch(c))
                    return -1;
                if (c->done == reps) {
                    uint8_t bye[LUMO_NET_OVERHEAD];
                    size_t n;
                    lumo_net_bye_encode(bye, sizeof bye, &n);
                    if (host_net_write_all(c->fd, bye, n))
                        return -1;
                    c->state = 2;
                }
            }
        }
        return 0;
    }
    return -1;
}

static void start_fetching(lclient *c, uint32_t reps)
{
    uint32_t k;

    c->state = 1;
    for (k = 0; k < LOAD_INFLIGHT && k < reps; k++)
        if (send_fetch(c))
            c->state = -1;
}

static void load_bytes(lclient *c, const uint8_t *p, size_t n, uint32_t reps, uint32_t max_payload)
{
    while (n && c->state >= 0) {
        if (c->skip) {   /* a payload (and CRC) nobody reads, or the WELCOME captured */
            uint32_t k = n < c->skip ? (uint32_t)n : c->skip;
            if (c->welcome) {
                memcpy(c->welcome + c->welcome_len, p, k);
                c->welcome_len += k;
            }
            c->skip -= k, p += k, n -= k;
            if (!c->skip && c->state == 0) {   /* the WELCOME is over */
                if (c->welcome && !g_scene.known && learn_scene(c->welcome, c->welcome_len))
                    c->state = -1;
                free(c->welcome);
                c->welcome = NULL;
                if (c->state == 0 && g_scene.known)
                    start_fetching(c, reps);
                else
                    c->state = -1;
            }
            continue;
        }
        if (c->head_len < c->need) {
            uint32_t k = c->need - c->head_len;
            if (k > n)
                k = (uint32_t)n;
            memcpy(c->head + c->head_len, p, k);
            c->head_len += k, p += k, n -= k;
            if (c->head_len < c->need)
                return;
        }
        if (c->need == LUMO_NET_HEADER) {
            uint8_t type = c->head[3];
            uint32_t len = lumo_wire_le32(c->head + 4);
            if (c->head[0] != LUMO_NET_MAGIC0 || c->head[1] != LUMO_NET_MAGIC1 || len > max_payload) {
                c->state = -1;
                return;
            }
            if (type == LUMO_NET_WELCOME && c->state == 0) {
                c->skip = len + LUMO_NET_TRAILER;
                if (!g_scene.known && (c->welcome = malloc(len + LUMO_NET_OVERHEAD))) {
                    memcpy(c->welcome, c->head, LUMO_NET_HEADER);
                    c->welcome_len = LUMO_NET_HEADER;
                }
                c->head_len = 0;
                continue;
            }
            if (type != LUMO_NET_DATA || len < LUMO_NET_DATA_HEAD || c->state != 1) {
                c->state = -1;
                return;
            }
            c->need = LUMO_NET_HEADER + LUMO_NET_DATA_HEAD;
            continue;
        }
        /* a DATA head: count what it carries, skip its records */
        if (on_head(c, reps)) {
            c->state = -1;
            return;
        }
        c->skip = lumo_wire_le32(c->head + 4) - LUMO_NET_DATA_HEAD + LUMO_NET_TRAILER;
        c->need = LUMO_NET_HEADER;
        c->head_len = 0;
    }
}

static int mode_load(int argc, char **argv)
{
    static uint8_t buf[256 << 10];
    struct epoll_event ev[256];
    uint32_t count, reps, max_payload = 64u << 10, i, finished = 0, failed = 0;
    uint8_t hello[256];
    lumo_net_hello h;
    lclient *cl;
    uint64_t bytes = 0;
    int64_t t0, t1;
    size_t hn;
    int ep;
    struct rlimit rl;

    char err[256];

    if (argc < 5) {
        fprintf(stderr, "lumo-bench-stream load: error: load HOST:PORT CLIENTS REPS [--max-payload N]\n");
        return 2;
    }
    if (host_opt_u32("CLIENTS", argv[3], 1, 100000, &count, err, sizeof err) ||
        host_opt_u32("REPS", argv[4], 1, 100000, &reps, err, sizeof err)) {
        fprintf(stderr, "lumo-bench-stream load: error: %s\n", err);
        return 2;
    }
    for (i = 5; (int)i + 1 < argc; i += 2)
        if (!strcmp(argv[i], "--max-payload") &&
            host_opt_u32("--max-payload", argv[i + 1], 4096, 1u << 24, &max_payload, err, sizeof err)) {
            fprintf(stderr, "lumo-bench-stream load: error: %s\n", err);
            return 2;
        }
    if (getrlimit(RLIMIT_NOFILE, &rl) == 0 && rl.rlim_cur < count + 64) {
        rl.rlim_cur = rl.rlim_max < count + 64 ? rl.rlim_max : count + 64;
        setrlimit(RLIMIT_NOFILE, &rl);
    }
    memset(&h, 0, sizeof h);
    h.arena_bytes = 256u << 20;
    h.max_payload = max_payload;
    h.width = 320, h.height = 240;
    h.ivg_form = LUMO_IVG_FORM_QUANTIZED;
    h.flags = LUMO_NET_FLAG_SMOOTHING;
    if (lumo_net_hello_encode(&h, NULL, hello, sizeof hello, &hn))
        return 1;
    if (!(cl = calloc(count, sizeof *cl)) || (ep = epoll_create1(0)) < 0)
        return 1;
    for (i = 0; i < count; i++) {
        struct epoll_event e;
        cl[i].need = LUMO_NET_HEADER;
        if ((cl[i].fd = tcp_connect(argv[2])) < 0) {
            fprintf(stderr, "lumo-bench-stream load: client %u: cannot connect: %s\n", i, strerror(errno));
            cl[i].state = -1;
            continue;
        }
        fcntl(cl[i].fd, F_SETFL, O_NONBLOCK);
        e.events = EPOLLIN;
        e.data.u32 = i;
        epoll_ctl(ep, EPOLL_CTL_ADD, cl[i].fd, &e);
    }
    t0 = now_us();
    for (i = 0; i < count; i++)
        if (cl[i].state == 0 && host_net_write_all(cl[i].fd, hello, hn))
            cl[i].state = -1;
    while (finished + failed < count && now_us() - t0 < 100000000) {
        int k, ne = epoll_wait(ep, ev, 256, 500);
        for (k = 0; k < ne; k++) {
            lclient *c = &cl[ev[k].data.u32];
            for (;;) {
                ssize_t n = recv(c->fd, buf, sizeof buf, MSG_DONTWAIT);
                if (n > 0) {
                    bytes += (uint64_t)n;
                    load_bytes(c, buf, (size_t)n, reps, max_payload);
                    if (c->state < 0)
                        break;
                    continue;
                }
                if (n == 0)
                    c->state = c->state == 2 ? 3 : -1;
                else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
                    c->state = -1;
                break;
            }
            if (c->state == 3 || c->state < 0) {
                epoll_ctl(ep, EPOLL_CTL_DEL, c->fd, NULL);
                close(c->fd);
                c->fd = -1;
                if (c->state == 3)
                    finished++;
                else
                    failed++;
            }
        }
    }
    t1 = now_us();
    printf("clients=%u repeats=%u finished=%u failed=%u bytes=%llu seconds=%.3f mb_per_s=%.1f\n", count, reps,
           finished, failed, (unsigned long long)bytes, (t1 - t0) / 1e6, (double)bytes / 1e6 / ((t1 - t0) / 1e6));
    free(cl);
    return failed || finished != count ? 1 : 0;
}

static void on_alarm(int sig)
{
    static const char msg[] = "lumo-bench-stream: the run took too long\n";
    (void)sig;
    if (write(2, msg, sizeof msg - 1) < 0)
        _exit(3);
    _exit(3);
}

int main(int argc, char **argv)
{
    signal(SIGPIPE, SIG_IGN);
    signal(SIGALRM, on_alarm);
    alarm(120);
    if (argc >= 3 && !strcmp(argv[1], "run"))
        return mode_run(argc, argv);
    if (argc >= 5 && !strcmp(argv[1], "load"))
        return mode_load(argc, argv);
    fprintf(stderr, "usage: lumo-bench-stream run HOST:PORT [options] | load HOST:PORT CLIENTS REPEATS\n");
    return 2;
}
