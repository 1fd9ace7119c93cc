/*
 * cut_proxy.c — a TCP proxy for tests/client/client_test.sh that cuts the
 * connection between lumo-client and lumo-server at random points.
 *
 *   cut_proxy --upstream HOST:PORT --port-file FILE --stats FILE
 *             [--cuts N] [--span BYTES] [--seed S] [--max-conns N]
 *
 * Listens on 127.0.0.1 (a free port, written to --port-file) and serves one
 * client connection at a time, each through its own connection upstream.
 * The first N connections are cut after a random number of server-to-client
 * bytes (1 .. --span, splitmix64 of --seed): the client's side gets those
 * bytes, then the end of the stream, and the upstream side is closed. The
 * server-to-client stream is followed frame by frame (docs/protocol.md §1:
 * 8-byte header with the payload length, payload, CRC), and each connection
 * adds a line to --stats:
 *
 *   conn K bytes B welcome W data D end E other O partial P cut C
 *
 * B the bytes forwarded to the client, W/D/E/O the bytes of whole WELCOME,
 * DATA, END and other frames among them, P the bytes of the frame cut
 * mid-way (0 when the cut fell between frames), C 1 when it was cut. After
 * --max-conns connections it stops listening and exits; it also exits 120 s
 * after it started, on SIGTERM, and when nothing happens for 30 s.
 */
#include <errno.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

typedef struct follow {
    uint8_t  head[8];
    uint32_t have;      /* bytes of the current frame seen */
    uint64_t frame_len; /* its size once the header is in */
    uint64_t by_type[4];
} follow;

static uint64_t g_rng;

static uint64_t rnd(void)
{
    uint64_t z = (g_rng += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static int type_slot(uint8_t t)
{
    return t == 2 ? 0 : t == 4 ? 1 : t == 5 ? 2 : 3;
}

/* Account the n bytes p forwarded to the client. */
static void follow_bytes(follow *f, const uint8_t *p, size_t n)
{
    while (n) {
        if (f->have < 8) {
            f->head[f->have++] = *p++, n--;
            if (f->have == 8)
                f->frame_len = 12u + ((uint64_t)f->head[4] | (uint64_t)f->head[5] << 8 |
                                      (uint64_t)f->head[6] << 16 | (uint64_t)f->head[7] << 24);
            continue;
        }
        {
            uint64_t left = f->frame_len - f->have, take = n < left ? n : left;
            f->have += (uint32_t)take, p += take, n -= take;
            if (f->have == f->frame_len) {
                f->by_type[type_slot(f->head[3])] += f->frame_len;
                f->have = 0;
            }
        }
    }
}

static int connect_to(const char *addr)
{
    char host[256], *colon;
    struct addrinfo hints, *res;
    int fd;

    snprintf(host, sizeof host, "%s", addr);
    if (!(colon = strrchr(host, ':')))
        return -1;
    *colon = 0;
    memset(&hints, 0, sizeof hints);
    hints.ai_socktype = SOCK_STREAM;
    if (getaddrinfo(host, colon + 1, &hints, &res))
        return -1;
    fd = socket(res->ai_family, SOCK_STREAM, 0);
    if (fd >= 0 && connect(fd, res->ai_addr, res->ai_addrlen) < 0) {
        close(fd);
        fd = -1;
    }
    freeaddrinfo(res);
    return fd;
}

static int write_all(int fd, const uint8_t *p, size_t n)
{
    while (n) {
        ssize_t w = send(fd, p, n, MSG_NOSIGNAL);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        p += w, n -= (size_t)w;
    }
    return 0;
}

/* Relay one client until either side ends or the cut; then account it. */
static void serve(int cfd, const char *upstream, uint64_t budget, int conn, FILE *stats)
{
    static uint8_t buf[1 << 16];
    follow f;
    uint64_t fwd = 0;
    int sfd = connect_to(upstream), cut = 0;
    struct pollfd p[2];

    memset(&f, 0, sizeof f);
    if (sfd < 0) {
        close(cfd);
        return;
    }
    for (;;) {
        ssize_t n;
        p[0].fd = cfd, p[0].events = POLLIN, p[1].fd = sfd, p[1].events = POLLIN;
        if (poll(p, 2, 30000) <= 0)
            break;
        if (p[0].revents) {   /* client -> server: as it comes */
            if ((n = read(cfd, buf, sizeof buf)) <= 0 || write_all(sfd, buf, (size_t)n))
                break;
        }
        if (p[1].revents) {   /* server -> client: up to the cut */
            if ((n = read(sfd, buf, sizeof buf)) <= 0)
                break;
            if (budget && fwd + (uint64_t)n >= budget) {
                n = (ssize_t)(budget - fwd);
                cut = 1;
            }
            if (write_all(cfd, buf, (size_t)n))
                break;
            follow_bytes(&f, buf, (size_t)n);
            fwd += (uint64_t)n;
            if (cut)
                break;
        }
    }
    close(sfd);
    /* the client reads what it was given, then the end of the stream; its
     * own bytes are drained so that closing sends no reset */
    shutdown(cfd, SHUT_WR);
    p[0].fd = cfd, p[0].events = POLLIN;
    while (poll(p, 1, 2000) > 0 && read(cfd, buf, sizeof buf) > 0)
        ;
    close(cfd);
    fprintf(stats, "conn %d bytes %llu welcome %llu data %llu end %llu other %llu partial %u cut %d\n", conn,
            (unsigned long long)fwd, (unsigned long long)f.by_type[0], (unsigned long long)f.by_type[1],
            (unsigned long long)f.by_type[2], (unsigned long long)f.by_type[3], f.have, cut);
    fflush(stats);
}

int main(int argc, char **argv)
{
    const char *upstream = NULL, *port_file = NULL, *stats_path = NULL;
    uint64_t span = 100000;
    int cuts = 0, max_conns = 1000, i, lfd, one = 1, conn;
    struct sockaddr_in a;
    socklen_t al = sizeof a;
    FILE *pf, *stats;
    time_t t0 = time(NULL);

    g_rng = 1;
    for (i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--upstream")) upstream = argv[i + 1];
        else if (!strcmp(argv[i], "--port-file")) port_file = argv[i + 1];
        else if (!strcmp(argv[i], "--stats")) stats_path = argv[i + 1];
        else if (!strcmp(argv[i], "--cuts")) cuts = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--span")) span = strtoull(argv[i + 1], NULL, 10);
        else if (!strcmp(argv[i], "--seed")) g_rng = strtoull(argv[i + 1], NULL, 10);
        else if (!strcmp(argv[i], "--max-conns")) max_conns = atoi(argv[i + 1]);
        else break;
    }
    if (i != argc || !upstream || !port_file || !stats_path || !span) {
        fprintf(stderr, "usage: cut_proxy --upstream HOST:PORT --port-file FILE --stats FILE [--cuts N] "
                        "[--span BYTES] [--seed S] [--max-conns N]\n");
        return 2;
    }
    alarm(120);
    lfd = socket(AF_INET, SOCK_STREAM, 0);
    setsockopt(lfd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(lfd, (struct sockaddr *)&a, sizeof a) || listen(lfd, 8) ||
        getsockname(lfd, (struct sockaddr *)&a, &al) || !(stats = fopen(stats_path, "w"))) {
        perror("cut_proxy");
        return 1;
    }
    if (!(pf = fopen(port_file, "w")))
        return 1;
    fprintf(pf, "%u\n", ntohs(a.sin_port));
    fclose(pf);
    for (conn = 0; conn < max_conns && time(NULL) - t0 < 120; conn++) {
        struct pollfd p = {lfd, POLLIN, 0};
        int cfd;
        if (poll(&p, 1, 30000) <= 0 || (cfd = accept(lfd, NULL, NULL)) < 0)
            break;
        serve(cfd, upstream, conn < cuts ? 1 + rnd() % span : 0, conn, stats);
    }
    close(lfd);
    fclose(stats);
    return 0;
}
