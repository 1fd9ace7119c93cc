/*
 * tools/lumo-client — the Linux thin client: connects to lumo-server (or
 * replays a recorded session), streams a scene through the SDK's session
 * and the protocol driver exactly as a device does (docs/protocol.md,
 * docs/client-session.md), and writes PNG frames as the scene refines
 * (seed 000 Fig. 1).
 */
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "lumo/net.h"
#include "lumo/net_client.h"
#include "lumo/session.h"
#include "lumo_host/png_io.h"
#include "../../net/host/net_socket.h"
#include "../lumo-render/render_backend.h"
#include "../lumo-render/session_scene.h"

static const char usage[] =
    "usage: lumo-client (--connect HOST:PORT | --replay FILE) [options]\n"
    "  --connect HOST:PORT     stream from lumo-server over TCP\n"
    "  --replay FILE           replay a session recorded with --record (no network)\n"
    "  --record FILE           write every byte received to FILE (for --replay)\n"
    "  --package N             which of the server's packages (default 0)\n"
    "  --out DIR               where frames and progress.csv go (default .)\n"
    "  --frames-at PERCENTS    draw a frame when the scene reaches these percentages\n"
    "                          (comma-separated; geometry and lighting count half each;\n"
    "                          default 100); frame-first.png is always drawn as soon as\n"
    "                          every base mesh and the grid's corners are in\n"
    "  --backend soft|osmesa|egl  renderer (default soft)\n"
    "  --size WxH              frame size (default 320x240)\n"
    "  --per-vertex            light per vertex, as a weak device would (default: per pixel)\n"
    "  --order interleaved|geometry|lighting  what to ask for first (default interleaved)\n"
    "  --vertices N            fixed geometry request size (default: adaptive)\n"
    "  --rounds K              fixed lighting request size in rounds (default: adaptive)\n"
    "  --target-ms T           adaptive: aim each answer at T ms (default 250)\n"
    "  --pipeline N            requests in flight, 1..8 (default 4)\n"
    "  --no-smoothing          push-pull without smoothing (cheaper on weak clients)\n"
    "  --float                 ask for the binary32 IVG form instead of the quantized one\n"
    "  --arena MIB             arena for the scene (default 256)\n"
    "  --quiet                 no progress line\n";

typedef struct options {
    const char *connect, *replay, *record, *out, *backend;
    double at[64];
    int nat, quiet, no_smoothing, use_float, per_vertex;
    uint32_t package, arena_mib;
    lumo_net_policy policy;
    render_opts ro;
} options;

static int parse_percents(const char *s, options *o)
{
    char *end;

    o->nat = 0;
    while (*s && o->nat < 64) {
        double p = strtod(s, &end);
        if (end == s || !(p > 0 && p <= 100) || (o->nat && p <= o->at[o->nat - 1]))
            return -1;
        o->at[o->nat++] = p;
        s = *end == ',' ? end + 1 : end;
        if (*end && *end != ',')
            return -1;
    }
    return o->nat ? 0 : -1;
}

static int parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *v)
{
    char *end;
    unsigned long n = strtoul(s, &end, 10);

    if (*end || end == s || n < lo || n > hi)
        return -1;
    *v = (uint32_t)n;
    return 0;
}

static int parse_args(int argc, char **argv, options *o)
{
    enum { O_CONNECT = 256, O_REPLAY, O_RECORD, O_PACKAGE, O_OUT, O_AT, O_BACKEND, O_SIZE, O_ORDER,
           O_VERTS, O_ROUNDS, O_TARGET, O_PIPE, O_NOSMOOTH, O_FLOAT, O_PV, O_ARENA, O_QUIET, O_HELP };
    static const struct option longs[] = {
        {"connect", 1, 0, O_CONNECT}, {"replay", 1, 0, O_REPLAY}, {"record", 1, 0, O_RECORD},
        {"package", 1, 0, O_PACKAGE}, {"out", 1, 0, O_OUT}, {"frames-at", 1, 0, O_AT},
        {"backend", 1, 0, O_BACKEND}, {"size", 1, 0, O_SIZE}, {"order", 1, 0, O_ORDER},
        {"vertices", 1, 0, O_VERTS}, {"rounds", 1, 0, O_ROUNDS}, {"target-ms", 1, 0, O_TARGET}, {"pipeline", 1, 0, O_PIPE},
        {"no-smoothing", 0, 0, O_NOSMOOTH}, {"per-vertex", 0, 0, O_PV}, {"float", 0, 0, O_FLOAT}, {"arena", 1, 0, O_ARENA},
        {"quiet", 0, 0, O_QUIET}, {"help", 0, 0, O_HELP}, {0, 0, 0, 0}};
    unsigned w, h;
    char tail;
    int c;

    memset(o, 0, sizeof *o);
    o->out = ".", o->backend = "soft", o->arena_mib = 256;
    o->at[0] = 100, o->nat = 1;
    o->ro.width = 320, o->ro.height = 240, o->ro.format = LUMO_PIXEL_XRGB8888, o->ro.depth_bits = 32;
    while ((c = getopt_long(argc, argv, "h", longs, NULL)) != -1) {
        switch (c) {
        case O_CONNECT: o->connect = optarg; break;
        case O_REPLAY: o->replay = optarg; break;
        case O_RECORD: o->record = optarg; break;
        case O_PACKAGE: if (parse_u32(optarg, 0, 0x7fffffff, &o->package)) return -1; break;
        case O_OUT: o->out = optarg; break;
        case O_AT: if (parse_percents(optarg, o)) return -1; break;
        case O_BACKEND: o->backend = optarg; break;
        case O_SIZE:
            if (sscanf(optarg, "%ux%u%c", &w, &h, &tail) != 2 || !w || !h || w > LUMO_MAX_FRAME_DIM ||
                h > LUMO_MAX_FRAME_DIM)
                return -1;
            o->ro.width = (uint16_t)w, o->ro.height = (uint16_t)h;
            break;
        case O_ORDER:
            if (!strcmp(optarg, "interleaved")) o->policy.order = LUMO_NET_ORDER_INTERLEAVED;
            else if (!strcmp(optarg, "geometry")) o->policy.order = LUMO_NET_ORDER_GEOMETRY_FIRST;
            else if (!strcmp(optarg, "lighting")) o->policy.order = LUMO_NET_ORDER_LIGHTING_FIRST;
            else return -1;
            break;
        case O_VERTS: if (parse_u32(optarg, 1, 1u << 28, &o->policy.vertices)) return -1; break;
        case O_ROUNDS: if (parse_u32(optarg, 1, 1u << 20, &o->policy.rounds)) return -1; break;
        case O_TARGET: if (parse_u32(optarg, 1, 60000, &o->policy.target_ms)) return -1; break;
        case O_PIPE: if (parse_u32(optarg, 1, 8, &o->policy.pipeline)) return -1; break;
        case O_NOSMOOTH: o->no_smoothing = 1; break;
        case O_PV: o->per_vertex = 1; break;
        case O_FLOAT: o->use_float = 1; break;
        case O_ARENA: if (parse_u32(optarg, 1, 4095, &o->arena_mib)) return -1; break;
        case O_QUIET: o->quiet = 1; break;
        default: return -1;
        }
    }
    return optind == argc && (!o->connect != !o->replay) ? 0 : -1;
}

/* ---- the client_link: a socket, or a recorded byte stream ------------------------------------ */

typedef struct client_link {
    int fd;
    int replay;          /* reading a recording: nothing is sent */
    FILE *record;
    uint64_t bytes_in, bytes_out;
} client_link;

static int link_send(client_link *l, const uint8_t *p, size_t n)
{
    if (l->replay)
        return 0;
    l->bytes_out += n;
    return host_net_write_all(l->fd, p, n);
}

/* Read what is there into buf (blocking until at least one byte): bytes
 * read, 0 at the end, -1 on error. */
static ssize_t link_read(client_link *l, uint8_t *buf, size_t cap)
{
    ssize_t n;

    do
        n = read(l->fd, buf, cap);
    while (n < 0 && errno == EINTR);
    if (n > 0) {
        l->bytes_in += (uint64_t)n;
        if (l->record && fwrite(buf, 1, (size_t)n, l->record) != (size_t)n)
            return -1;
    }
    return n;
}

/* ---- frames --------------------------------------------------------------------- */

typedef struct client {
    options o;
    client_link l;
    lumo_session ses;
    lumo_net_client drv;
    host_scene scene;
    FILE *csv;
    uint32_t t0;
    int next_at;
    int first_done;          /* the first picture has been drawn */
    uint32_t first_ms;
    uint64_t first_bytes;
    double last_fps;
} client;

/* The share of the scene held, in percent: geometry and lighting half each
 * (all geometry when there is no IVG). */
static double held_percent(const lumo_net_progress *p)
{
    double g = p->full_vertices ? (double)p->vertices / p->full_vertices : 1.0;
    double l = p->full_rounds ? (double)p->rounds / p->full_rounds : -1.0;

    return 100.0 * (l < 0 ? g : (g + l) / 2);
}

/* The first picture: every mesh has its base and the grid its corners (or
 * there is no grid): what seed 000 shows after a few percent of the bytes. */
static int first_picture_ready(const client *c)
{
    uint32_t m;

    if (c->drv.state != LUMO_NET_READY && c->drv.state != LUMO_NET_DONE)
        return 0;
    for (m = 0; m < c->drv.mesh_count; m++)
        if (c->drv.held[m] == 0)
            return 0;
    return !c->drv.has_ivg || c->drv.rounds_held > 0;
}

static int draw_frame(client *c, double percent, const lumo_net_progress *p, const char *tag)
{
    const lumo_ivg *ivg = lumo_session_ivg(&c->ses);
    lumo_raster_mesh mesh;
    lumo_raster_scene rs;
    host_renderer *r;
    host_load_stats st;
    char err[256], name[1024];
    uint8_t *rgb;
    uint32_t t;
    int rc;

    if (host_scene_from_session(&c->ses, &c->scene, &st))
        return -1;
    mesh = host_mesh_raster(&c->scene.mesh);
    memset(&rs, 0, sizeof rs);
    rs.lights = c->scene.lights;
    rs.light_count = c->scene.light_count;
    rs.exposure = LUMO_Q16_ONE;
    rs.flags = c->o.per_vertex ? 0 : LUMO_RASTER_PER_PIXEL;
    if (ivg && p->rounds) {
        rs.indirect = lumo_raster_ivg_irradiance;
        rs.indirect_ctx = ivg;
    }
    if (!(r = host_renderer_open(c->o.backend, &mesh, ivg, &c->o.ro, err, sizeof err))) {
        fprintf(stderr, "lumo-client: error: %s\n", err);
        return -1;
    }
    rgb = malloc((size_t)c->o.ro.width * c->o.ro.height * 3);
    t = host_net_clock_ms(NULL);
    rc = !rgb || host_renderer_draw(r, &c->scene.camera, &rs, rgb);
    c->last_fps = 1000.0 / ((host_net_clock_ms(NULL) - t) + 0.5);
    if (tag)
        snprintf(name, sizeof name, "%s/frame-%s.png", c->o.out, tag);
    else
        snprintf(name, sizeof name, "%s/frame-%06.2f.png", c->o.out, percent);
    if (!rc && host_png_write_rgb8(name, rgb, c->o.ro.width, c->o.ro.height, err, sizeof err)) {
        fprintf(stderr, "lumo-client: error: %s\n", err);
        rc = 1;
    }
    if (!rc && c->csv)
        fprintf(c->csv, "%.2f,%llu,%llu,%u,%u,%u,%u,%u,%u,%s\n", percent, (unsigned long long)c->l.bytes_in,
                (unsigned long long)p->bytes, p->vertices, p->full_vertices, mesh.tri_count, p->rounds,
                p->full_rounds, host_net_clock_ms(NULL) - c->t0, name);
    free(rgb);
    host_renderer_close(r);
    return rc ? -1 : 0;
}

static void progress_line(const client *c, const lumo_net_progress *p)
{
    if (c->o.quiet)
        return;
    fprintf(stderr, "\rlumo-client: %8.1f KB  %u/%u vertices  IVG %5.1f%%  %.0f fps  ",
            c->l.bytes_in / 1024.0, p->vertices, p->full_vertices,
            p->full_rounds ? 100.0 * p->rounds / p->full_rounds : 0.0, c->last_fps);
}

/* Frames for every threshold the scene has now passed. */
static int frames_due(client *c)
{
    lumo_net_progress p;
    double have;

    lumo_net_client_progress(&c->drv, &p);
    have = p.done ? 100.0 : held_percent(&p);
    if (!c->first_done && first_picture_ready(c)) {
        c->first_done = 1;
        c->first_ms = host_net_clock_ms(NULL) - c->t0;
        c->first_bytes = c->l.bytes_in;
        if (draw_frame(c, have, &p, "first"))
            return -1;
    }
    while (c->next_at < c->o.nat && have >= c->o.at[c->next_at] - 1e-9) {
        if (draw_frame(c, c->o.at[c->next_at], &p, NULL))
            return -1;
        c->next_at++;
    }
    progress_line(c, &p);
    return 0;
}

/* ---- the conversation ----------------------------------------------------------- */

static int send_pending(client *c, uint8_t *out, size_t cap)
{
    size_t n;
    lumo_status st;

    do {
        if ((st = lumo_net_client_next(&c->drv, out, cap, &n))) {
            fprintf(stderr, "lumo-client: error: %s\n", lumo_strerror(st));
            return -1;
        }
        if (n && link_send(&c->l, out, n)) {
            fprintf(stderr, "lumo-client: error: send: %s\n", strerror(errno));
            return -1;
        }
    } while (n && c->drv.state != LUMO_NET_DONE);
    return 0;
}

static const char *frame_name(uint8_t type)
{
    static const char *names[] = {"?", "HELLO", "WELCOME", "REQUEST", "DATA", "END", "ERROR", "BYE"};
    return type < sizeof names / sizeof names[0] ? names[type] : "unknown";
}

/* Decode and apply every whole frame in rx[0..*len); keep the rest. */
static int take_frames(client *c, uint8_t *rx, size_t *len)
{
    size_t at = 0, used;
    lumo_net_frame f;
    lumo_status st;

    for (;;) {
        st = lumo_net_frame_decode(rx + at, *len - at, c->drv.cfg.max_payload, &f, &used);
        if (st == LUMO_ERR_TRUNCATED)
            break;
        if (st) {
            fprintf(stderr, "\nlumo-client: error: a frame from the server: %s\n", lumo_strerror(st));
            return -1;
        }
        if ((st = lumo_net_client_on_frame(&c->drv, &f))) {
            fprintf(stderr, "\nlumo-client: error: %s frame: %s\n", frame_name(f.type), lumo_strerror(st));
            return -1;
        }
        at += used;
        if (frames_due(c))
            return -1;
    }
    memmove(rx, rx + at, *len - at);
    *len -= at;
    return 0;
}

static int converse(client *c)
{
    size_t cap = c->drv.cfg.max_payload + LUMO_NET_OVERHEAD, len = 0, n;
    uint8_t *rx = malloc(cap), out[1024];
    int rc = -1;

    if (!rx)
        return -1;
    if (lumo_net_client_hello(&c->drv, out, sizeof out, &n) || link_send(&c->l, out, n))
        goto done;
    while (c->drv.state != LUMO_NET_DONE) {
        ssize_t got;
        if (send_pending(c, out, sizeof out))
            goto done;
        if (c->drv.state == LUMO_NET_DONE)
            break;
        if ((got = link_read(&c->l, rx + len, cap - len)) <= 0) {
            fprintf(stderr, "\nlumo-client: error: %s before the scene was complete\n",
                    got == 0 ? "the connection closed" : strerror(errno));
            goto done;
        }
        len += (size_t)got;
        if (take_frames(c, rx, &len))
            goto done;
    }
    rc = frames_due(c);
done:
    free(rx);
    return rc;
}

static int open_link(client *c)
{
    char err[256];

    if (c->o.replay) {
        c->l.replay = 1;
        if ((c->l.fd = open(c->o.replay, O_RDONLY)) < 0) {
            fprintf(stderr, "lumo-client: error: %s: %s\n", c->o.replay, strerror(errno));
            return -1;
        }
    } else if ((c->l.fd = host_net_connect(c->o.connect, err, sizeof err)) < 0) {
        fprintf(stderr, "lumo-client: error: %s\n", err);
        return -1;
    }
    if (c->o.record && !(c->l.record = fopen(c->o.record, "wb"))) {
        fprintf(stderr, "lumo-client: error: %s: %s\n", c->o.record, strerror(errno));
        return -1;
    }
    return 0;
}

static int start(client *c, void **arena_mem)
{
    lumo_session_config scfg = {{0, LUMO_SESSION_LOD_ALL}, c->o.no_smoothing ? 0u : LUMO_IVG_SMOOTH};
    lumo_net_client_config ncfg;
    static lumo_arena arena;
    size_t bytes = (size_t)c->o.arena_mib << 20;
    char path[1024];

    if (!(*arena_mem = malloc(bytes)))
        return -1;
    lumo_arena_init(&arena, *arena_mem, bytes);
    memset(&ncfg, 0, sizeof ncfg);
    ncfg.package = c->o.package;
    ncfg.arena_bytes = (uint32_t)(bytes > 0xffffffffu ? 0xffffffffu : bytes);
    ncfg.max_payload = 1u << 20;
    ncfg.width = c->o.ro.width, ncfg.height = c->o.ro.height;
    ncfg.ivg_form = c->o.use_float ? LUMO_IVG_FORM_FLOAT : LUMO_IVG_FORM_QUANTIZED;
    ncfg.smoothing = !c->o.no_smoothing;
    ncfg.policy = c->o.policy;
    ncfg.clock = host_net_clock_ms;
    ncfg.replay = c->o.replay != NULL;   /* apply what was recorded; ask nothing */
    if (lumo_session_init(&c->ses, &scfg, &arena) || lumo_net_client_init(&c->drv, &c->ses, &ncfg))
        return -1;
    mkdir(c->o.out, 0777);
    snprintf(path, sizeof path, "%s/progress.csv", c->o.out);
    if ((c->csv = fopen(path, "w")))
        fprintf(c->csv, "percent,bytes_in,data_bytes,vertices,full_vertices,triangles,rounds,full_rounds,ms,frame\n");
    c->t0 = host_net_clock_ms(NULL);
    return 0;
}

int main(int argc, char **argv)
{
    static client c;
    lumo_net_progress p;
    void *arena_mem = NULL;
    int rc;

    if (parse_args(argc, argv, &c.o)) {
        fputs(usage, stderr);
        return 2;
    }
    if (start(&c, &arena_mem) || open_link(&c)) {
        free(arena_mem);
        return 1;
    }
    rc = converse(&c);
    lumo_net_client_progress(&c.drv, &p);
    if (!c.o.quiet)
        fputc('\n', stderr);
    if (rc == 0)
        printf("lumo-client: %s: %u vertices, IVG %u/%u rounds, %llu bytes in, %llu out, %u ms; "
               "first picture after %u ms, %llu bytes\n",
               c.o.connect ? c.o.connect : c.o.replay, p.vertices, p.rounds, p.full_rounds,
               (unsigned long long)c.l.bytes_in, (unsigned long long)c.l.bytes_out,
               host_net_clock_ms(NULL) - c.t0, c.first_ms, (unsigned long long)c.first_bytes);
    if (c.l.record)
        fclose(c.l.record);
    if (c.csv)
        fclose(c.csv);
    host_scene_free(&c.scene);
    close(c.l.fd);
    free(arena_mem);
    return rc ? 1 : 0;
}
