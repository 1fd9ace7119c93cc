/*
 * tools/lumo-client — the Linux thin client: streams a scene from lumo-server
 * (TCP, or a serial line carried over TCP), from a package on a stock HTTP
 * server (Range requests), or from a recording, through the SDK's session
 * and the protocol driver exactly as a device does (docs/protocol.md,
 * docs/client-session.md), and writes PNG frames as the scene refines
 * (seed 000 Fig. 1). The parts: client.h.
 */
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/net.h"
#include "lumo/net_client.h"
#include "lumo/session.h"
#include "lumo_host/options.h"
#include "../../net/host/net_socket.h"
#include "client.h"
#include "../lumo-render/scene_convert.h"
#include "lumo_host/version_line.h"

static const char usage[] =
    "usage: lumo-client (--connect HOST:PORT | --serial HOST:PORT | --http URL | --replay FILE) [options]\n"
    "Streams a scene piece by piece (docs/protocol.md) and writes PNG frames as it refines.\n"
    "  --connect HOST:PORT     lumo-server over TCP; a dropped connection is opened again\n"
    "                          and resumed from the cursors held (see --retries)\n"
    "  --serial HOST:PORT      lumo-server's --serial-listen: the frames over a lossy byte\n"
    "                          stream; garbage and damaged frames are skipped (resynchronised\n"
    "                          on the next frame) and what was lost is asked again\n"
    "  --http URL              a .lumo package on a plain HTTP/1.1 server (Range requests):\n"
    "                          the client reads the package's table and answers its own\n"
    "                          requests from byte ranges, as lumo-server would\n"
    "  --replay FILE           replay a session recorded with --record (no network)\n"
    "  --record FILE           write every frame taken, as received, to FILE (for --replay)\n"
    "  --retries N             reconnections in a row after a dropped connection (default 5,\n"
    "                          waits 50 ms doubling to 2 s; 0: none)\n"
    "  --package N             which of the server's packages (default 0)\n"
    "  --out DIR               where frames and progress.csv go (default .)\n"
    "  --frames-at PERCENTS    draw a frame when the scene reaches these percentages\n"
    "                          (comma-separated; geometry and lighting count half each;\n"
    "                          default 100); frame-first.png is always drawn as soon as\n"
    "                          every base mesh and the grid's corners are in\n"
    "  --backend soft|osmesa|egl  renderer (default soft)\n"
    "  --size WxH              frame size (default 320x240)\n"
    "  --per-vertex | --per-pixel  light per vertex, as a weak device would, or per pixel\n"
    "                          (default: per pixel)\n"
    "  --shadows N             shadow maps of N x N texels per face for every light\n"
    "                          (point: 6 faces; default 0: no shadows; any backend)\n"
    "  --camera EYE:TARGET:UP:FOVY  draw from this camera (default: the package's)\n"
    "  --fit                   draw from a camera fitted to the scene's bounds\n"
    "  --order interleaved|geometry|lighting  what to ask for first (default interleaved)\n"
    "  --vertices N            fixed geometry request size (default: adaptive)\n"
    "  --rounds K              fixed lighting request size in rounds (default: adaptive)\n"
    "  --target-ms T           adaptive: aim each answer at T ms (default 250)\n"
    "  --pipeline N            requests in flight, 1..8 (default: 4, up to 8 while the\n"
    "                          answers in flight take less than a round trip)\n"
    "  --max-payload BYTES     the largest frame payload taken, 4096.. (default 1048576)\n"
    "  --no-smoothing          push-pull without smoothing (cheaper on weak clients)\n"
    "  --smoothing-budget MS   drop smoothing for the rest of the session the first time\n"
    "                          a smoothed push-pull takes longer than MS\n"
    "  --float                 ask for the binary32 IVG form instead of the quantized one\n"
    "  --arena MIB             arena for the scene (default 256)\n"
    "  --quiet                 no progress line\n"
    "  --updates S             --connect: once the scene is complete, pull the lighting\n"
    "                          updates of a dynamic scene for S seconds (docs/dynamic.md),\n"
    "                          a frame (frame-update-NNN.png) every --update-every ms\n"
    "  --update-every MS       poll and draw interval of --updates (default 250)\n"
    "  --prt                   with --per-vertex: stream each mesh's PRT with its geometry\n"
    "                          (docs/protocol.md §10) and relight with it under the package's\n"
    "                          environment (PRTL), else its lights as distant lights\n"
    "  --rotate DEG            with --prt: turn the lighting DEG degrees about +y a frame drawn\n"
    "  -h, --help              this text\n"
    "The last line on stdout sums the run up; any failure is one 'lumo-client: error:' line\n"
    "on stderr and exit status 1 (the frames drawn until then are kept).\n";

/* The refusal of the last option, for main (one command line per run). */
static char g_err[400];

static int parse_u32(const char *opt, const char *s, uint32_t lo, uint32_t hi, uint32_t *v)
{
    return host_opt_u32(opt, s, lo, hi, v, g_err, sizeof g_err);
}

static int parse_size(const char *s, options *o)
{
    uint32_t w, h;

    if (host_opt_size("--size", s, LUMO_MAX_FRAME_DIM, LUMO_MAX_FRAME_DIM, &w, &h, g_err, sizeof g_err))
        return -1;
    o->ro.width = (uint16_t)w, o->ro.height = (uint16_t)h;
    return 0;
}

static int parse_order(const char *s, options *o)
{
    static const char *const k_orders[] = {"interleaved", "geometry", "lighting"};
    static const lumo_net_order k_values[] = {LUMO_NET_ORDER_INTERLEAVED, LUMO_NET_ORDER_GEOMETRY_FIRST,
                                              LUMO_NET_ORDER_LIGHTING_FIRST};
    int i;

    if (host_opt_choice("--order", s, k_orders, 3, &i, g_err, sizeof g_err))
        return -1;
    o->policy.order = k_values[i];
    return 0;
}

enum { O_CONNECT = 256, O_SERIAL, O_HTTP, O_REPLAY, O_RECORD, O_RETRIES, O_PACKAGE, O_OUT, O_AT, O_BACKEND,
       O_SIZE, O_PV, O_PP, O_ORDER, O_VERTS, O_ROUNDS, O_TARGET, O_PIPE, O_MAXPAY, O_NOSMOOTH, O_SMOOTHB, O_FLOAT, O_ARENA,
       O_QUIET, O_CAMERA, O_FIT, O_UPDATES, O_UPDEVERY, O_SHADOWS, O_PRT, O_ROTATE };

static int take_option(int c, const char *arg, options *o)
{
    switch (c) {
    case O_CONNECT: o->connect = arg; return 0;
    case O_SERIAL: o->serial = arg; return 0;
    case O_HTTP: o->http = arg; return 0;
    case O_REPLAY: o->replay = arg; return 0;
    case O_RECORD: o->record = arg; return 0;
    case O_RETRIES: return parse_u32("--retries", arg, 0, 1000, &o->retries);
    case O_PACKAGE: return parse_u32("--package", arg, 0, 0x7fffffff, &o->package);
    case O_OUT: o->out = arg; return 0;
    case O_AT:
        if (host_opt_list("--frames-at", arg, 0, 100, 1, o->at, 64, &o->nat, g_err, sizeof g_err))
            return -1;
        if (o->at[0] > 0)
            return 0;
        snprintf(g_err, sizeof g_err, "--frames-at %.64s: percentages must be above 0 (frame-first.png is "
                 "always drawn)", arg);
        return -1;
    case O_BACKEND: o->backend = arg; return 0;
    case O_SIZE: return parse_size(arg, o);
    case O_PV: o->per_vertex = 1; return 0;
    case O_PP: o->per_vertex = 0; return 0;
    case O_SHADOWS: return host_opt_shadows(arg, &o->ro.shadow_size, g_err, sizeof g_err);
    case O_CAMERA: o->camera = arg; return 0;
    case O_FIT: o->fit = 1; return 0;
    case O_ORDER: return parse_order(arg, o);
    case O_VERTS: return parse_u32("--vertices", arg, 1, 1u << 28, &o->policy.vertices);
    case O_ROUNDS: return parse_u32("--rounds", arg, 1, 1u << 20, &o->policy.rounds);
    case O_TARGET: return parse_u32("--target-ms", arg, 1, 60000, &o->policy.target_ms);
    case O_PIPE: return parse_u32("--pipeline", arg, 1, 8, &o->policy.pipeline);
    case O_MAXPAY: return parse_u32("--max-payload", arg, LUMO_NET_MIN_PAYLOAD, LUMO_NET_MAX_PAYLOAD, &o->max_payload);
    case O_NOSMOOTH: o->no_smoothing = 1; return 0;
    case O_SMOOTHB: return parse_u32("--smoothing-budget", arg, 1, 60000, &o->policy.smooth_budget_ms);
    case O_FLOAT: o->use_float = 1; return 0;
    case O_ARENA: return parse_u32("--arena", arg, 1, 4095, &o->arena_mib);
    case O_QUIET: o->quiet = 1; return 0;
    case O_UPDATES: return parse_u32("--updates", arg, 1, 86400, &o->updates_s);
    case O_UPDEVERY: return parse_u32("--update-every", arg, 10, 60000, &o->update_every_ms);
    case O_PRT: o->prt = 1; return 0;
    case O_ROTATE: return host_opt_double("--rotate", arg, -360, 360, &o->rotate, g_err, sizeof g_err);
    default: snprintf(g_err, sizeof g_err, "unhandled option %d", c); return -1;
    }
}

/* 0, 1 for --help, -1 for a bad command line. */
static int parse_args(int argc, char **argv, options *o)
{
    static const struct option longs[] = {
        {"connect", 1, 0, O_CONNECT}, {"serial", 1, 0, O_SERIAL}, {"http", 1, 0, O_HTTP},
        {"replay", 1, 0, O_REPLAY},
        {"record", 1, 0, O_RECORD},
        {"retries", 1, 0, O_RETRIES},
        {"package", 1, 0, O_PACKAGE}, {"out", 1, 0, O_OUT}, {"frames-at", 1, 0, O_AT},
        {"backend", 1, 0, O_BACKEND}, {"size", 1, 0, O_SIZE}, {"per-vertex", 0, 0, O_PV}, {"per-pixel", 0, 0, O_PP},
        {"order", 1, 0, O_ORDER}, {"vertices", 1, 0, O_VERTS}, {"rounds", 1, 0, O_ROUNDS},
        {"target-ms", 1, 0, O_TARGET}, {"pipeline", 1, 0, O_PIPE}, {"max-payload", 1, 0, O_MAXPAY},
        {"no-smoothing", 0, 0, O_NOSMOOTH}, {"smoothing-budget", 1, 0, O_SMOOTHB}, {"float", 0, 0, O_FLOAT}, {"arena", 1, 0, O_ARENA},
        {"quiet", 0, 0, O_QUIET}, {"camera", 1, 0, O_CAMERA}, {"fit", 0, 0, O_FIT},
        {"updates", 1, 0, O_UPDATES}, {"update-every", 1, 0, O_UPDEVERY}, {"shadows", 1, 0, O_SHADOWS},
        {"prt", 0, 0, O_PRT}, {"rotate", 1, 0, O_ROTATE},
        {"help", 0, 0, 'h'}, {0, 0, 0, 0}};
    int c;

    memset(o, 0, sizeof *o);
    o->out = ".", o->backend = "soft", o->arena_mib = 256, o->retries = 5, o->max_payload = 1u << 20;
    o->at[0] = 100, o->nat = 1;
    o->update_every_ms = 250, o->update_amount = 65536;
    o->ro.width = 320, o->ro.height = 240, o->ro.format = LUMO_PIXEL_XRGB8888, o->ro.depth_bits = 32;
    opterr = 0;
    while ((c = host_getopt(argc, argv, ":h", longs)) != -1) {
        if (c == 'h')
            return 1;
        if (c == '?' || c == ':')
            return host_opt_getopt_error(c, argv[optind - 1], optopt, g_err, sizeof g_err);
        if (take_option(c, optarg, o))
            return -1;
    }
    if (optind != argc)
        snprintf(g_err, sizeof g_err, "unexpected argument '%.128s' (try --help)", argv[optind]);
    else if ((!!o->connect + !!o->serial + !!o->http + !!o->replay) != 1)
        snprintf(g_err, sizeof g_err, "give exactly one of --connect, --serial, --http or --replay (try --help)");
    else if (o->updates_s && !o->connect)
        snprintf(g_err, sizeof g_err, "--updates pulls from lumo-server over TCP: give --connect");
    else if (o->prt && (!o->per_vertex || strcmp(o->backend, "soft")))
        snprintf(g_err, sizeof g_err, "--prt relights per vertex on the soft backend: give --per-vertex "
                 "(the GL multipass is lumo-render's)");
    else if (o->rotate != 0 && !o->prt)
        snprintf(g_err, sizeof g_err, "--rotate goes with --prt (try --help)");
    else if (o->prt && (o->http || o->serial))
        snprintf(g_err, sizeof g_err, "--prt streams from lumo-server: give --connect or --replay");
    else
        return 0;
    return -1;
}

static const char *source(const options *o, const link_ops **ops)
{
    if (o->serial)
        return *ops = &link_serial, o->serial;
    if (o->http)
        return *ops = &link_http, o->http;
    if (o->replay)
        return *ops = &link_replay, o->replay;
    return *ops = &link_tcp, o->connect;
}

/* The session in its arena, the driver, the link (not opened yet), the
 * recorder and progress.csv. */
static int start(client *c, void **arena_mem)
{
    lumo_session_config scfg = {{0, LUMO_SESSION_LOD_ALL}, c->o.no_smoothing ? 0u : LUMO_IVG_SMOOTH};
    lumo_net_client_config ncfg;
    static lumo_arena arena;
    size_t bytes = (size_t)c->o.arena_mib << 20;
    char err[320];

    c->l.target = source(&c->o, &c->l.ops);
    c->l.fd = -1;
    if (!(*arena_mem = malloc(bytes)))
        return -1;
    lumo_arena_init(&arena, *arena_mem, bytes);
    memset(&ncfg, 0, sizeof ncfg);
    ncfg.package = c->o.package;
    ncfg.arena_bytes = (uint32_t)(bytes > 0xffffffffu ? 0xffffffffu : bytes);
    ncfg.max_payload = c->o.max_payload;
    ncfg.width = c->o.ro.width, ncfg.height = c->o.ro.height;
    ncfg.ivg_form = c->o.use_float ? LUMO_IVG_FORM_FLOAT : LUMO_IVG_FORM_QUANTIZED;
    ncfg.smoothing = !c->o.no_smoothing;
    ncfg.policy = c->o.policy;
    ncfg.clock = host_net_clock_ms;
    ncfg.replay = c->o.replay != NULL;   /* apply what was recorded; ask nothing */
    /* lumo-server over TCP sends the first picture with its WELCOME (a round
     * trip less); a serial line re-asks after losses and an HTTP server
     * answers only ranges, so they ask for it as any other request. */
    ncfg.first_picture = c->o.connect != NULL;
    ncfg.prt = (uint8_t)c->o.prt;
    if (lumo_session_init(&c->ses, &scfg, &arena) || lumo_net_client_init(&c->drv, &c->ses, &ncfg))
        return -1;
    if (c->o.record && record_open(&c->record, c->o.record, err, sizeof err)) {
        fprintf(stderr, "lumo-client: error: %s\n", err);
        return -1;
    }
    if (draws_open(c))
        return -1;
    c->t0 = host_net_clock_ms(NULL);
    return 0;
}

static void summary(const client *c)
{
    lumo_net_progress p;

    lumo_net_client_progress(&c->drv, &p);
    printf("lumo-client: %s: %u vertices, IVG %u/%u rounds, %llu bytes in, %llu out, %u ms; "
           "first picture after %u ms, %llu bytes",
           c->l.target, p.vertices, p.rounds, p.full_rounds, (unsigned long long)c->l.bytes_in,
           (unsigned long long)c->l.bytes_out, host_net_clock_ms(NULL) - c->t0, c->first_ms,
           (unsigned long long)c->first_bytes);
    if (c->cuts)
        printf("; %u cuts resumed, %llu bytes of frames cut mid-way", c->cuts, (unsigned long long)c->cut_bytes);
    if (c->l.ops->lossy)
        printf("; %u frames refused, %u silences, %u times asked again, %llu bytes skipped, %u stale frames dropped",
               c->refused, c->timeouts, c->resyncs, (unsigned long long)c->garbage, c->stale);
    if (c->l.note[0])
        printf("; %s", c->l.note);
    printf("\n");
}

int main(int argc, char **argv)
{
    if (host_version_option(argc, argv, "lumo-client"))
        return 0;
    static client c;
    void *arena_mem = NULL;
    int rc;

    signal(SIGPIPE, SIG_IGN);   /* a dropped connection is a failed write, resumed */
    if ((rc = parse_args(argc, argv, &c.o))) {
        if (rc > 0)
            fputs(usage, stdout);
        else
            fprintf(stderr, "lumo-client: error: %s\n", g_err);
        return rc > 0 ? 0 : 2;
    }
    if (c.o.camera && host_camera_from_string(c.o.camera, &c.o.view)) {
        fprintf(stderr, "lumo-client: error: --camera %s: not EYE:TARGET:UP:FOVY with eye != target, "
                "UP not along the view, FOVY in [1, 179] (docs/scene-format.md)\n", c.o.camera);
        return 2;
    }
    if (start(&c, &arena_mem)) {
        free(arena_mem);
        return 1;
    }
    rc = converse(&c);
    if (!c.o.quiet)
        fputc('\n', stderr);
    if (rc == 0)
        summary(&c);
    if (c.record)
        fclose(c.record);
    draws_close(&c);
    free(arena_mem);
    return rc ? 1 : 0;
}
