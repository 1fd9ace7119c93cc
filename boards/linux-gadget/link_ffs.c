/*
 * link_ffs.c — the link of boards/board.h over a USB FunctionFS function
 * (boards/linux-gadget: a Linux board with a device-mode USB port;
 * docs/porting.md §9). The rest of the board is the Linux board's
 * (boards/host/board.c).
 *
 * LUMO_FFS=DIR names the mounted FunctionFS instance (default
 * /dev/ffs-lumo). On first use the link writes the descriptors and the
 * string to DIR/ep0 (ffs_desc.h), after which the kernel creates DIR/ep1
 * (bulk OUT) and DIR/ep2 (bulk IN) and the gadget can be bound to a UDC
 * (boards/linux-gadget/gadget.sh). Three threads of its own:
 *
 *  - ep0: the function's events. ENABLE (the host configured the device)
 *    opens a new connection: its number goes up and the bytes received
 *    before it are dropped; DISABLE and UNBIND (unplugged, the UDC
 *    unbound) close it. Control requests to the interface are stalled.
 *  - OUT: reads ep1 into a ring (the reads block in the kernel; this thread
 *    keeps board_link_read's timeout apart from them).
 *  - the caller's: board_link_write writes ep2 in transfers cut by
 *    lumo_net_usb_transfer (no transfer a multiple of the packet size, so
 *    none needs a ZLP); board_link_read takes from the ring and returns
 *    BOARD_LINK_NEW once per new connection.
 *
 * While no connection is open, writes are dropped (as a serial line loses
 * bytes) and reads time out; the client asks again, and resumes with HELLO
 * on BOARD_LINK_NEW. While one is open, reads wait OPEN_WAIT_MS at least. Desktop-side code for a Linux device: POSIX threads.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <linux/usb/ch9.h>
#include <linux/usb/functionfs.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "board.h"
#include "ffs_desc.h"
#include "lumo/net_usb.h"

#define RING_BYTES (64u << 10)
/* While a connection is open a read waits this long at least, whatever the
 * caller's timeout: USB bulk is reliable (CRC and retries in the
 * controllers), so a silence there is a slow peer, not a loss, and asking
 * again would send a request twice. The caller's timeout applies while no
 * connection is open (then nothing arrives and what is written is lost). */
#define OPEN_WAIT_MS 10000u

typedef struct ffs_link {
    int ep0, ep_out, ep_in;
    pthread_mutex_t mu;
    pthread_cond_t cv;          /* ring filled or drained, connection changed */
    uint32_t conn, seen;        /* connection number; the one the caller knows */
    int up;
    uint8_t ring[RING_BYTES];
    size_t head, len;
} ffs_link;

static ffs_link g_ffs = {-1, -1, -1, PTHREAD_MUTEX_INITIALIZER, PTHREAD_COND_INITIALIZER, 0, 0, 0, {0}, 0, 0};
static int g_state;   /* 0: not tried, 1: running, -1: none */

static void say(const char *what, const char *detail)
{
    fprintf(stderr, "gadget: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
}

/* ---- ep0: events ----------------------------------------------------------------- */

static void set_up(ffs_link *l, int up)
{
    pthread_mutex_lock(&l->mu);
    if (up && !l->up) {
        l->conn++;
        l->head = l->len = 0;   /* the old connection's bytes */
    }
    l->up = up;
    pthread_cond_broadcast(&l->cv);
    pthread_mutex_unlock(&l->mu);
}

/* A control request to the function: none is defined, stall it (the
 * transfer in the other direction, as FunctionFS asks). */
static void stall(const ffs_link *l, const struct usb_ctrlrequest *r)
{
    ssize_t k = (r->bRequestType & USB_DIR_IN) ? read(l->ep0, NULL, 0) : write(l->ep0, NULL, 0);
    (void)k;
}

static void *ep0_thread(void *arg)
{
    ffs_link *l = arg;
    struct usb_functionfs_event ev[4];

    for (;;) {
        ssize_t n = read(l->ep0, ev, sizeof ev), i;
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        for (i = 0; i < n / (ssize_t)sizeof ev[0]; i++) {
            if (ev[i].type == FUNCTIONFS_ENABLE)
                set_up(l, 1), say("connected", NULL);
            else if (ev[i].type == FUNCTIONFS_DISABLE || ev[i].type == FUNCTIONFS_UNBIND)
                set_up(l, 0), say("disconnected", NULL);
            else if (ev[i].type == FUNCTIONFS_SETUP)
                stall(l, &ev[i].u.setup);
        }
    }
    set_up(l, 0);
    return NULL;
}

/* ---- OUT: into the ring ---------------------------------------------------------- */

static void ring_put(ffs_link *l, const uint8_t *p, size_t n, uint32_t conn)
{
    pthread_mutex_lock(&l->mu);
    while (n) {
        size_t tail = (l->head + l->len) % RING_BYTES, k = RING_BYTES - tail;
        while (l->len == RING_BYTES && l->conn == conn)
            pthread_cond_wait(&l->cv, &l->mu);   /* the client is behind: hold the host */
        if (l->conn != conn)
            break;   /* bytes of a connection that has ended */
        if (k > RING_BYTES - l->len)
            k = RING_BYTES - l->len;
        if (k > n)
            k = n;
        memcpy(l->ring + tail, p, k);
        l->len += k, p += k, n -= k;
        pthread_cond_broadcast(&l->cv);
    }
    pthread_mutex_unlock(&l->mu);
}

static void *out_thread(void *arg)
{
    ffs_link *l = arg;
    static uint8_t buf[LUMO_USB_TRANSFER];   /* a multiple of every packet size */

    for (;;) {
        uint32_t conn;
        ssize_t n;

        pthread_mutex_lock(&l->mu);
        while (!l->up)
            pthread_cond_wait(&l->cv, &l->mu);
        conn = l->conn;
        pthread_mutex_unlock(&l->mu);
        n = read(l->ep_out, buf, sizeof buf);
        if (n > 0)
            ring_put(l, buf, (size_t)n, conn);
        else if (n < 0 && errno != EINTR)
            nanosleep(&(struct timespec){0, 10000000L}, NULL);   /* disabled: wait for the next ENABLE */
    }
    return NULL;
}

/* ---- start ------------------------------------------------------------------------ */

static int open_ep(const char *dir, const char *name, int flags)
{
    char path[256];

    snprintf(path, sizeof path, "%s/%s", dir, name);
    return open(path, flags);
}

static int write_descriptors(ffs_link *l)
{
    uint8_t d[FFS_DESC_BYTES], s[FFS_STRINGS_BYTES];
    size_t dn = ffs_descriptors(d, sizeof d), sn = ffs_strings(s, sizeof s);

    if (!dn || !sn)
        return errno = ENOSPC, -1;
    return write(l->ep0, d, dn) == (ssize_t)dn && write(l->ep0, s, sn) == (ssize_t)sn ? 0 : -1;
}

static int start(ffs_link *l)
{
    const char *dir = getenv("LUMO_FFS");
    pthread_t t;

    if (!dir)
        dir = "/dev/ffs-lumo";
    if ((l->ep0 = open_ep(dir, "ep0", O_RDWR)) < 0)
        return say("cannot open ep0 (is FunctionFS mounted? LUMO_FFS)", dir), -1;
    if (write_descriptors(l))
        return say("ep0 refused the descriptors", strerror(errno)), -1;
    if ((l->ep_out = open_ep(dir, "ep1", O_RDWR)) < 0 || (l->ep_in = open_ep(dir, "ep2", O_RDWR)) < 0)
        return say("no endpoint files after the descriptors", strerror(errno)), -1;
    if (pthread_create(&t, NULL, ep0_thread, l) || pthread_detach(t) || pthread_create(&t, NULL, out_thread, l) ||
        pthread_detach(t))
        return say("cannot start the link's threads", NULL), -1;
    say("descriptors written: bind the gadget to a UDC", dir);
    return 0;
}

static ffs_link *link_get(void)
{
    if (g_state == 0)
        g_state = start(&g_ffs) ? -1 : 1;
    return g_state == 1 ? &g_ffs : NULL;
}

/* ---- the board's link -------------------------------------------------------------- */

/* Open, and the caller has been told of it (BOARD_LINK_NEW): what it
 * writes before that belongs to the conversation of an older connection
 * (a HELLO written then would reach the new one twice). */
static int writable(ffs_link *l)
{
    int w;

    pthread_mutex_lock(&l->mu);
    w = l->up && l->conn == l->seen;
    pthread_mutex_unlock(&l->mu);
    return w;
}

/* A write failed: the connection ended under it (the endpoint disabled
 * before ep0's DISABLE event was read), or the link is broken. */
static int write_lost(ffs_link *l, int err)
{
    if (err == ESHUTDOWN || err == ECONNRESET || err == ENODEV)
        return 1;
    nanosleep(&(struct timespec){0, 20000000L}, NULL);   /* let ep0's thread see it */
    return !writable(l);
}

int board_link_write(const uint8_t *buf, size_t n)
{
    ffs_link *l = link_get();

    if (!l)
        return -1;
    while (n && writable(l)) {
        size_t k = lumo_net_usb_transfer(n, LUMO_USB_TRANSFER, LUMO_USB_MPS_FS);
        ssize_t w = write(l->ep_in, buf, k);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return write_lost(l, w < 0 ? errno : EIO) ? 0 : -1;   /* unplugged: lost, as on a line */
        buf += w;
        n -= (size_t)w;
    }
    return 0;
}

static void deadline_in(struct timespec *t, uint32_t ms)
{
    clock_gettime(CLOCK_REALTIME, t);
    t->tv_sec += (time_t)(ms / 1000u);
    t->tv_nsec += (long)(ms % 1000u) * 1000000L;
    if (t->tv_nsec >= 1000000000L)
        t->tv_sec++, t->tv_nsec -= 1000000000L;
}

int32_t board_link_read(uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    ffs_link *l = link_get();
    struct timespec until;
    int32_t got = 0;

    if (!l)
        return -1;
    pthread_mutex_lock(&l->mu);
    deadline_in(&until, l->up && timeout_ms < OPEN_WAIT_MS ? OPEN_WAIT_MS : timeout_ms);
    while (l->len == 0 && !(l->up && l->conn != l->seen))
        if (pthread_cond_timedwait(&l->cv, &l->mu, &until) == ETIMEDOUT)
            break;
    if (l->up && l->conn != l->seen) {
        l->seen = l->conn;
        got = BOARD_LINK_NEW;
    } else {
        while (l->len && (size_t)got < cap && got < 0x7fffffff) {
            size_t k = RING_BYTES - l->head;
            if (k > l->len)
                k = l->len;
            if (k > cap - (size_t)got)
                k = cap - (size_t)got;
            memcpy(buf + got, l->ring + l->head, k);
            l->head = (l->head + k) % RING_BYTES, l->len -= k, got += (int32_t)k;
        }
        pthread_cond_broadcast(&l->cv);
    }
    pthread_mutex_unlock(&l->mu);
    return got;
}
