/* tools/lumo-server/main.c — lumo-server: streams .lumo packages to thin
 * clients piece by piece (docs/protocol.md; usage in docs/server.md). Any
 * start-up failure is one line on stderr and exit status 1. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/options.h"
#include "serve/index.h"
#include "serve/server.h"
#include "serve/usb.h"
#include "lumo_host/version_line.h"
#include "dynamic.h"

static const char usage[] =
    "usage: lumo-server PACKAGE.lumo... [options]\n"
    "Streams .lumo packages (format version 2) to thin clients over the lumo\n"
    "stream protocol (docs/protocol.md): each client asks for geometry batches\n"
    "and lighting rounds in the amounts it can take. A client's HELLO picks a\n"
    "package by its position on this command line (0 = the first).\n"
    "  --listen ADDR:PORT         TCP clients (default " SRV_DEFAULT_LISTEN "; PORT 0: any free\n"
    "                             port; 0.0.0.0:PORT for the whole network)\n"
    "  --serial-listen ADDR:PORT  also accept TCP connections that carry a raw serial\n"
    "                             line: the server resynchronises after garbage\n"
    "  --rate KBIT/S              emulate a link of this rate per client, 0..1e9 (0: none;\n"
    "                             115.2 for a 115200 baud line)\n"
    "  --latency MS               emulate this one-way latency per client, 0..60000 (requests\n"
    "                             and frames each wait this long)\n"
    "  --loss P                   serial listener: damage each frame with probability\n"
    "                             P (one byte flipped or dropped), seeded\n"
    "  --seed S                   seed of --loss, 0..4294967295 (default 1)\n"
    "  --max-clients N            clients at once (default 1024); more get ERROR LIMIT\n"
    "  --idle-timeout S           close a client that sends nothing, or reads nothing,\n"
    "                             for S seconds, 1..86400 (default 30)\n"
    "  --usb [VID:PID]            also serve thin clients plugged in by USB: every\n"
    "                             device with a lumo interface (class ff/4c/01), or\n"
    "                             those of VID:PID (hex); found by hotplug and by a\n"
    "                             scan every 500 ms (docs/protocol.md §8 \"USB\")\n"
    "  --port-file FILE           write \"TCP_PORT SERIAL_PORT\" once listening (scripts)\n"
    "  --quiet                    no line per client (start, stop and errors only)\n"
    "  --dynamic SCENE[,k=v...]   live lighting (docs/dynamic.md): photon streaming on\n"
    "                             SCENE (the first package's scene, its motion lines),\n"
    "                             changes served on the updates channel; settings\n"
    "                             vsl=N pool=N batch=N photon-rate=R tau=T commands=FIFO\n"
    "  -h, --help                 this text\n"
    "One line per client on stderr when it ends: peer, HELLO, requests, bytes\n"
    "sent, how it ended. SIGINT/SIGTERM: finish queued output (2 s at most), exit.\n";

static int fail(const char *msg)
{
    fprintf(stderr, "lumo-server: error: %s\n", msg);
    return 1;
}

/* --usb, --usb=VID:PID or --usb VID:PID (the next word when it is one). */
static int usb_option(srv_serve_options *o, const char *arg, int argc, char **argv)
{
    o->usb = 1;
    o->usb_any = 1;
    if (!arg && optind < argc && srv_usb_parse_id(argv[optind], &o->usb_vid, &o->usb_pid) == 0) {
        optind++;
        o->usb_any = 0;
        return 0;
    }
    if (!arg)
        return 0;
    o->usb_any = 0;
    return srv_usb_parse_id(arg, &o->usb_vid, &o->usb_pid);
}

int main(int argc, char **argv)
{
    if (host_version_option(argc, argv, "lumo-server"))
        return 0;
    enum { O_LISTEN = 256, O_SERIAL, O_RATE, O_LATENCY, O_LOSS, O_SEED, O_MAX, O_IDLE, O_PORTFILE, O_QUIET, O_USB,
           O_DYNAMIC };
    static const struct option longopts[] = {
        {"listen", required_argument, NULL, O_LISTEN},
        {"serial-listen", required_argument, NULL, O_SERIAL},
        {"rate", required_argument, NULL, O_RATE},
        {"latency", required_argument, NULL, O_LATENCY},
        {"loss", required_argument, NULL, O_LOSS},
        {"seed", required_argument, NULL, O_SEED},
        {"max-clients", required_argument, NULL, O_MAX},
        {"idle-timeout", required_argument, NULL, O_IDLE},
        {"port-file", required_argument, NULL, O_PORTFILE},
        {"quiet", no_argument, NULL, O_QUIET},
        {"usb", optional_argument, NULL, O_USB},
        {"dynamic", required_argument, NULL, O_DYNAMIC},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    srv_serve_options o;
    srv_pkg *pkgs;
    char msg[512], err[400];
    uint32_t npkgs, i, seed32;
    const char *dynamic = NULL;
    struct dynamic *dyn = NULL;
    int c;
    lumo_status st;

    memset(&o, 0, sizeof o);
    o.listen = SRV_DEFAULT_LISTEN;
    o.max_clients = SRV_DEFAULT_MAX;
    o.idle_timeout_s = SRV_DEFAULT_IDLE_S;
    o.drain_ms = SRV_DRAIN_MS;
    o.seed = 1;
    opterr = 0;
    while ((c = host_getopt(argc, argv, ":h", longopts)) != -1) {
        switch (c) {
        case 'h':
            fputs(usage, stdout);
            return 0;
        case O_LISTEN:
            o.listen = optarg;
            break;
        case O_SERIAL:
            o.serial_listen = optarg;
            break;
        case O_RATE:
            if (host_opt_double("--rate", optarg, 0, 1e9, &o.rate_kbit, msg, sizeof msg))
                return fail(msg);
            break;
        case O_LATENCY:
            if (host_opt_u32("--latency", optarg, 0, 60000, &o.latency_ms, msg, sizeof msg))
                return fail(msg);
            break;
        case O_LOSS:
            if (host_opt_double("--loss", optarg, 0, 1, &o.loss, msg, sizeof msg))
                return fail(msg);
            break;
        case O_SEED:
            if (host_opt_u32("--seed", optarg, 0, 0xffffffffu, &seed32, msg, sizeof msg))
                return fail(msg);
            o.seed = seed32;
            break;
        case O_MAX:
            if (host_opt_u32("--max-clients", optarg, 1, 1000000, &o.max_clients, msg, sizeof msg))
                return fail(msg);
            break;
        case O_IDLE:
            if (host_opt_u32("--idle-timeout", optarg, 1, 86400, &o.idle_timeout_s, msg, sizeof msg))
                return fail(msg);
            break;
        case O_PORTFILE:
            o.port_file = optarg;
            break;
        case O_QUIET:
            o.quiet = 1;
            break;
        case O_USB:
            if (usb_option(&o, optarg, argc, argv)) {
                snprintf(msg, sizeof msg, "--usb %s: not VID:PID in hex (e.g. 1209:0001)", optarg ? optarg : "");
                return fail(msg);
            }
            break;
        case O_DYNAMIC:
            dynamic = optarg;
            break;
        default:
            host_opt_getopt_error(c, argv[optind - 1], optopt, msg, sizeof msg);
            return fail(msg);
        }
    }
    if (optind >= argc)
        return fail("no package given (usage: lumo-server PACKAGE.lumo... [options]; see --help)");
    if (o.loss > 0 && !o.serial_listen)
        return fail("--loss damages the serial listener's frames: give --serial-listen too");
    npkgs = (uint32_t)(argc - optind);
    if (!(pkgs = calloc(npkgs, sizeof *pkgs)))
        return fail("out of memory");
    for (i = 0; i < npkgs; i++)
        if (host_opt_file(NULL, argv[optind + (int)i], "package", err, sizeof err) ||
            (st = srv_pkg_open(&pkgs[i], argv[optind + (int)i], err, sizeof err))) {
            while (i--)
                srv_pkg_close(&pkgs[i]);
            free(pkgs);
            return fail(err);
        }
    err[0] = 0;
    if (dynamic && !(dyn = dynamic_start(dynamic, &pkgs[0], &o, err, sizeof err)))
        st = LUMO_ERR_ARG;
    else
        st = srv_serve_run(pkgs, npkgs, &o, err, sizeof err);
    dynamic_stop(dyn);
    for (i = 0; i < npkgs; i++)
        srv_pkg_close(&pkgs[i]);
    free(pkgs);
    if (st)
        return fail(err[0] ? err : lumo_strerror(st));
    return 0;
}
