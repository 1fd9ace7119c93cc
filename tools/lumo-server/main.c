/* tools/lumo-server/main.c — lumo-server: streams .lumo packages to thin
 * clients piece by piece (docs/protocol.md; usage in docs/server.md). Any
 * start-up failure is one line on stderr and exit status 1. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "serve/index.h"
#include "serve/server.h"
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
    "  --rate KBIT/S              emulate a link of this rate per client (0: none)\n"
    "  --latency MS               emulate this one-way latency per client (requests\n"
    "                             and frames each wait this long)\n"
    "  --loss P                   serial listener: damage each frame with probability\n"
    "                             P (one byte flipped or dropped), seeded\n"
    "  --seed S                   seed of --loss (default 1)\n"
    "  --max-clients N            clients at once (default 1024); more get ERROR LIMIT\n"
    "  --idle-timeout S           close a client that sends nothing, or reads nothing,\n"
    "                             for S seconds (default 30)\n"
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

static int parse_u32(const char *t, unsigned long lo, unsigned long hi, uint32_t *out)
{
    char *end;
    unsigned long v;

    errno = 0;
    v = strtoul(t, &end, 10);
    if (end == t || *end || errno || v < lo || v > hi || t[0] == '-')
        return -1;
    *out = (uint32_t)v;
    return 0;
}

static int parse_double(const char *t, double lo, double hi, double *out)
{
    char *end;
    double v = strtod(t, &end);

    if (end == t || *end || !isfinite(v) || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int main(int argc, char **argv)
{
    if (host_version_option(argc, argv, "lumo-server"))
        return 0;
    enum { O_LISTEN = 256, O_SERIAL, O_RATE, O_LATENCY, O_LOSS, O_SEED, O_MAX, O_IDLE, O_PORTFILE, O_QUIET, O_DYNAMIC };
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
    while ((c = getopt_long(argc, argv, "h", longopts, NULL)) != -1) {
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
            if (parse_double(optarg, 0, 1e9, &o.rate_kbit))
                return fail("--rate wants kbit/s, a number >= 0 (e.g. 115.2 for a 115200 baud line)");
            break;
        case O_LATENCY:
            if (parse_u32(optarg, 0, 60000, &o.latency_ms))
                return fail("--latency wants milliseconds, 0..60000");
            break;
        case O_LOSS:
            if (parse_double(optarg, 0, 1, &o.loss))
                return fail("--loss wants a probability per frame, 0..1");
            break;
        case O_SEED:
            if (parse_u32(optarg, 0, 0xffffffffu, &seed32))
                return fail("--seed wants an integer 0..4294967295");
            o.seed = seed32;
            break;
        case O_MAX:
            if (parse_u32(optarg, 1, 1000000, &o.max_clients))
                return fail("--max-clients wants 1..1000000");
            break;
        case O_IDLE:
            if (parse_u32(optarg, 1, 86400, &o.idle_timeout_s))
                return fail("--idle-timeout wants seconds, 1..86400");
            break;
        case O_PORTFILE:
            o.port_file = optarg;
            break;
        case O_QUIET:
            o.quiet = 1;
            break;
        case O_DYNAMIC:
            dynamic = optarg;
            break;
        default:
            snprintf(msg, sizeof msg, "unknown or incomplete option '%s' (see --help)", argv[optind - 1]);
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
        if ((st = srv_pkg_open(&pkgs[i], argv[optind + (int)i], err, sizeof err))) {
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
