/* test_usb_bridge.c — lumo-server's USB bridge (serve/usb.h) without USB:
 * the two pumps against a simulated device over a real socketpair. Every
 * byte passes in order; no OUT transfer is a multiple of the packet size
 * (lumo/net_usb.h); a device that goes away ends its pump, shuts the
 * socket (the loop sees the end of that client only) and stops the other
 * pump; a socket the loop closes ends the bridge; VID:PID parsing; and
 * the watcher starts and hands out nothing where no device is. */
#include <pthread.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>
#include "test_common.h"
#include "lumo/net_usb.h"
#include "serve/usb.h"

#define MPS 512u

typedef struct fake_dev {
    /* IN: what the device has to send, handed out in chunks */
    const uint8_t *in;
    size_t in_len, in_at, chunk;
    /* OUT: what reached it, and every transfer's length */
    uint8_t out[1 << 16];
    size_t out_len;
    size_t xfer[256];
    unsigned nxfer;
    int multiples;        /* OUT transfers that were a multiple of MPS */
    unsigned gone_after;  /* transfers before it disappears (0: never) */
    unsigned transfers;
} fake_dev;

static int gone(fake_dev *d)
{
    return d->gone_after && ++d->transfers > d->gone_after;
}

static int fake_in(void *ctx, uint8_t *buf, size_t cap, size_t *done, unsigned ms)
{
    fake_dev *d = ctx;
    size_t k = d->in_len - d->in_at;
    (void)ms;

    *done = 0;
    if (gone(d))
        return SRV_USB_GONE;
    if (k == 0) {
        usleep(2000);   /* a timeout with nothing */
        return SRV_USB_OK;
    }
    k = k < d->chunk ? k : d->chunk;
    k = k < cap ? k : cap;
    memcpy(buf, d->in + d->in_at, k);
    d->in_at += k;
    *done = k;
    return SRV_USB_OK;
}

static int fake_out(void *ctx, const uint8_t *buf, size_t n, size_t *done, unsigned ms)
{
    fake_dev *d = ctx;
    (void)ms;

    *done = 0;
    if (gone(d))
        return SRV_USB_GONE;
    if (n % MPS == 0)
        d->multiples++;
    if (d->nxfer < 256)
        d->xfer[d->nxfer++] = n;
    memcpy(d->out + d->out_len, buf, n);
    d->out_len += n;
    *done = n;
    return SRV_USB_OK;
}

typedef struct pump_run {
    srv_usb_io io;
    int sock, out;   /* out: pump_out, else pump_in */
    srv_usb_end why;
    pthread_t th;
} pump_run;

static void *pump_thread(void *arg)
{
    pump_run *r = arg;
    r->why = r->out ? srv_usb_pump_out(&r->io, r->sock) : srv_usb_pump_in(&r->io, r->sock);
    return NULL;
}

static void start(pump_run *r, fake_dev *d, atomic_int *stop, int sock, int out)
{
    r->io = (srv_usb_io){fake_in, fake_out, d, MPS, stop};
    r->sock = sock;
    r->out = out;
    assert_int_equal(pthread_create(&r->th, NULL, pump_thread, r), 0);
}

static void pattern(uint8_t *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        p[i] = (uint8_t)(i * 131u + (i >> 8));
}

static void write_all(int fd, const uint8_t *p, size_t n)
{
    while (n) {
        ssize_t w = write(fd, p, n);
        assert_true(w > 0);
        p += w, n -= (size_t)w;
    }
}

/* The socket to OUT: lengths at the edges, the rule on every transfer,
 * and the end when the loop closes its socket. */
static void test_out_rule_and_socket_end(void **state)
{
    static fake_dev d;
    static uint8_t msg[512 + 1024 + 16384 + 512 + 1];
    static const size_t parts[] = {512, 1024, 16384 + 512, 1};
    atomic_int stop = 0;
    pump_run r;
    int sv[2];
    size_t at = 0, i;
    (void)state;

    memset(&d, 0, sizeof d);
    pattern(msg, sizeof msg);
    assert_int_equal(socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
    start(&r, &d, &stop, sv[1], 1);
    for (i = 0; i < 4; i++) {
        write_all(sv[0], msg + at, parts[i]);
        at += parts[i];
        usleep(20000);   /* one read of the pump per part */
    }
    close(sv[0]);   /* the loop closes the connection */
    pthread_join(r.th, NULL);
    assert_int_equal(r.why, SRV_USB_END_SOCKET);
    assert_int_equal(atomic_load(&stop), 1);
    assert_int_equal(d.out_len, at);
    assert_memory_equal(d.out, msg, at);
    assert_int_equal(d.multiples, 0);
    assert_true(d.nxfer >= 5);   /* 512 and 1024 went as 511+1 and 1023+1 */
    close(sv[1]);
}

/* IN to the socket, then the device goes: the peer reads every byte, then
 * the end of the stream; the other pump stops too. */
static void test_in_then_device_gone(void **state)
{
    static fake_dev d;
    static uint8_t msg[40000], got[40000];
    atomic_int stop = 0;
    pump_run rin, rout;
    int sv[2];
    size_t n = 0;
    ssize_t k;
    (void)state;

    memset(&d, 0, sizeof d);
    pattern(msg, sizeof msg);
    d.in = msg, d.in_len = sizeof msg, d.chunk = 3000;
    d.gone_after = 14;   /* the last call finds it gone */
    assert_int_equal(socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
    start(&rin, &d, &stop, sv[1], 0);
    start(&rout, &d, &stop, sv[1], 1);
    while ((k = read(sv[0], got + n, sizeof got - n)) > 0)
        n += (size_t)k;
    assert_int_equal(k, 0);   /* EOF: the loop closes this client */
    pthread_join(rin.th, NULL);
    pthread_join(rout.th, NULL);
    assert_int_equal(rin.why, SRV_USB_END_DEVICE);
    assert_int_equal(rout.why, SRV_USB_END_STOP);
    assert_int_equal(n, sizeof msg);
    assert_memory_equal(got, msg, n);
    close(sv[0]), close(sv[1]);
}

/* OUT finds the device gone on its first transfer. */
static void test_out_device_gone(void **state)
{
    static fake_dev d;
    uint8_t b[100];
    atomic_int stop = 0;
    pump_run r;
    int sv[2];
    (void)state;

    memset(&d, 0, sizeof d);
    memset(b, 7, sizeof b);
    d.gone_after = 1, d.transfers = 1;   /* the next transfer finds it gone */
    assert_int_equal(socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
    start(&r, &d, &stop, sv[1], 1);
    write_all(sv[0], b, sizeof b);
    pthread_join(r.th, NULL);
    assert_int_equal(r.why, SRV_USB_END_DEVICE);
    assert_int_equal(d.out_len, 0);
    assert_int_equal(read(sv[0], b, sizeof b), 0);   /* shut: the loop sees the end */
    close(sv[0]), close(sv[1]);
}

/* The stop flag (server shutdown) ends an idle bridge within the wake. */
static void test_stop_ends_idle_pumps(void **state)
{
    static fake_dev d;
    atomic_int stop = 0;
    pump_run rin, rout;
    int sv[2];
    struct timespec t0, t1;
    (void)state;

    memset(&d, 0, sizeof d);
    assert_int_equal(socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
    start(&rin, &d, &stop, sv[1], 0);
    start(&rout, &d, &stop, sv[1], 1);
    usleep(50000);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    atomic_store(&stop, 1);
    pthread_join(rin.th, NULL);
    pthread_join(rout.th, NULL);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    assert_int_equal(rin.why, SRV_USB_END_STOP);
    assert_int_equal(rout.why, SRV_USB_END_STOP);
    assert_true((t1.tv_sec - t0.tv_sec) * 1000 + (t1.tv_nsec - t0.tv_nsec) / 1000000 < 2 * SRV_USB_WAKE_MS + 100);
    close(sv[0]), close(sv[1]);
}

static void test_parse_id(void **state)
{
    uint16_t v = 0, p = 0;
    (void)state;

    assert_int_equal(srv_usb_parse_id("1209:0001", &v, &p), 0);
    assert_int_equal(v, 0x1209);
    assert_int_equal(p, 0x0001);
    assert_int_equal(srv_usb_parse_id("abCD:Ef01", &v, &p), 0);
    assert_int_equal(v, 0xabcd);
    assert_int_equal(p, 0xef01);
    assert_int_equal(srv_usb_parse_id("1209:1", &v, &p), -1);
    assert_int_equal(srv_usb_parse_id("1209:00011", &v, &p), -1);
    assert_int_equal(srv_usb_parse_id("12090001", &v, &p), -1);
    assert_int_equal(srv_usb_parse_id("zz09:0001", &v, &p), -1);
    assert_int_equal(srv_usb_parse_id("", &v, &p), -1);
    /* whole hex digits only: no sign, blank or 0x (sscanf's %4x took them) */
    assert_int_equal(srv_usb_parse_id("-fff:+fff", &v, &p), -1);
    assert_int_equal(srv_usb_parse_id(" 209:0001", &v, &p), -1);
    assert_int_equal(srv_usb_parse_id("0x12:0001", &v, &p), -1);
    assert_int_equal(srv_usb_parse_id("1209:000g", &v, &p), -1);
    assert_int_equal(srv_usb_parse_id(NULL, &v, &p), -1);
}

/* No device here (no usbfs at all on a build machine): the watcher either
 * starts and hands out nothing, or says in one line why USB cannot start. */
static void test_no_device(void **state)
{
    srv_usb *u = NULL;
    char err[200] = "", peer[64];
    lumo_status st = srv_usb_start(&u, 1, 0, 0, err, sizeof err);
    (void)state;

    if (st != LUMO_OK) {
        assert_int_equal(st, LUMO_ERR_IO);
        assert_non_null(strstr(err, "USB"));
        assert_null(u);
        return;
    }
    usleep((SRV_USB_POLL_MS + 200) * 1000);
    assert_int_equal(srv_usb_take(u, peer, sizeof peer), -1);
    srv_usb_stop(u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_out_rule_and_socket_end),
        cmocka_unit_test(test_in_then_device_gone),
        cmocka_unit_test(test_out_device_gone),
        cmocka_unit_test(test_stop_ends_idle_pumps),
        cmocka_unit_test(test_parse_id),
        cmocka_unit_test(test_no_device),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
