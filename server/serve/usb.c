/*
 * usb.c — lumo-server's USB watcher and bridges over libusb (serve/usb.h).
 * The pumps themselves are usb_bridge.c.
 */
#include "serve/usb.h"
#include "common/status_msg.h"
#include "lumo/net_usb.h"

#include <errno.h>
#include <fcntl.h>
#include <libusb-1.0/libusb.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

/* What the loop reads from the hand-off pipe: one write, atomic (< PIPE_BUF). */
typedef struct handoff {
    int  fd;
    char peer[60];
} handoff;

typedef struct bridge {
    struct bridge        *next;
    srv_usb              *u;
    uint8_t               bus, addr, iface, ep_in, ep_out;
    char                  peer[60];
    libusb_context       *ctx;      /* the bridge's own: it ends with the device */
    libusb_device_handle *h;
    int                   sock;     /* the bridge's end of the socketpair */
    atomic_int            stop, finished;
    srv_usb_io            io;
    pthread_t             th_in, th_out;
    int                   released; /* threads joined, device closed */
    int                   seen;     /* present in the last scan */
} bridge;

struct srv_usb {
    int             any_id;
    uint16_t        vid, pid;
    int             pipe[2];        /* hand-off: bridges to the loop */
    atomic_int      stop;
    pthread_t       watcher;
    libusb_context *watch;          /* hotplug arrivals, when libusb has them */
    libusb_hotplug_callback_handle hp;
    atomic_int      arrived;
    bridge         *bridges;
};

/* Four hex digits at t, nothing else (sscanf's %4x took a sign, blanks and
 * "0x": "-fff:+fff" read as f001:0fff). */
static int hex4(const char *t, uint16_t *out)
{
    unsigned v = 0;

    for (int i = 0; i < 4; i++) {
        char c = t[i];
        unsigned d = c >= '0' && c <= '9' ? (unsigned)(c - '0') : c >= 'a' && c <= 'f' ? (unsigned)(c - 'a' + 10)
                   : c >= 'A' && c <= 'F' ? (unsigned)(c - 'A' + 10) : 16u;
        if (d > 15)
            return -1;
        v = v << 4 | d;
    }
    *out = (uint16_t)v;
    return 0;
}

int srv_usb_parse_id(const char *t, uint16_t *vid, uint16_t *pid)
{
    uint16_t v, p;

    if (!t || strlen(t) != 9 || t[4] != ':' || hex4(t, &v) || hex4(t + 5, &p))
        return -1;
    *vid = v;
    *pid = p;
    return 0;
}

/* ---- finding the interface ------------------------------------------------------------ */

/* The lumo interface of a configuration: its number and bulk endpoints. */
static int find_interface(const struct libusb_config_descriptor *cfg, bridge *b)
{
    int i, e;

    for (i = 0; i < cfg->bNumInterfaces; i++) {
        const struct libusb_interface_descriptor *d;
        if (cfg->interface[i].num_altsetting < 1)
            continue;
        d = &cfg->interface[i].altsetting[0];
        if (d->bInterfaceClass != LUMO_USB_CLASS || d->bInterfaceSubClass != LUMO_USB_SUBCLASS ||
            d->bInterfaceProtocol != LUMO_USB_PROTOCOL)
            continue;
        b->ep_in = b->ep_out = 0;
        for (e = 0; e < d->bNumEndpoints; e++) {
            const struct libusb_endpoint_descriptor *ep = &d->endpoint[e];
            if ((ep->bmAttributes & 3) != LIBUSB_TRANSFER_TYPE_BULK)
                continue;
            if (ep->bEndpointAddress & LIBUSB_ENDPOINT_IN)
                b->ep_in = b->ep_in ? b->ep_in : ep->bEndpointAddress;
            else if (!b->ep_out)
                b->ep_out = ep->bEndpointAddress, b->io.mps = ep->wMaxPacketSize & 0x7ffu;
        }
        if (b->ep_in && b->ep_out) {
            b->iface = d->bInterfaceNumber;
            return 0;
        }
    }
    return -1;
}

/* Whether dev is a lumo client (the VID:PID asked, the interface). */
static int is_client(const srv_usb *u, libusb_device *dev, bridge *b)
{
    struct libusb_device_descriptor dd;
    struct libusb_config_descriptor *cfg;
    int r;

    if (libusb_get_device_descriptor(dev, &dd) || (!u->any_id && (dd.idVendor != u->vid || dd.idProduct != u->pid)))
        return 0;
    if (libusb_get_active_config_descriptor(dev, &cfg))
        return 0;
    r = find_interface(cfg, b) == 0;
    libusb_free_config_descriptor(cfg);
    if (r) {
        uint8_t path[8];
        int n = libusb_get_port_numbers(dev, path, sizeof path), k, at;
        at = snprintf(b->peer, sizeof b->peer, "usb:%u-", libusb_get_bus_number(dev));
        for (k = 0; k < n && at < (int)sizeof b->peer - 16; k++)
            at += snprintf(b->peer + at, sizeof b->peer - (size_t)at, k ? ".%u" : "%u", path[k]);
        snprintf(b->peer + at, sizeof b->peer - (size_t)at, " %04x:%04x", dd.idVendor, dd.idProduct);
    }
    return r;
}

/* ---- a bridge ------------------------------------------------------------------------ */

static int lu_in(void *ctx, uint8_t *buf, size_t cap, size_t *done, unsigned ms)
{
    bridge *b = ctx;
    int got = 0, r = libusb_bulk_transfer(b->h, b->ep_in, buf, (int)cap, &got, ms);

    *done = got > 0 ? (size_t)got : 0;
    return r == 0 || r == LIBUSB_ERROR_TIMEOUT || r == LIBUSB_ERROR_INTERRUPTED ? SRV_USB_OK : SRV_USB_GONE;
}

static int lu_out(void *ctx, const uint8_t *buf, size_t n, size_t *done, unsigned ms)
{
    bridge *b = ctx;
    int put = 0, r = libusb_bulk_transfer(b->h, b->ep_out, (uint8_t *)buf, (int)n, &put, ms);

    *done = put > 0 ? (size_t)put : 0;
    return r == 0 || r == LIBUSB_ERROR_TIMEOUT || r == LIBUSB_ERROR_INTERRUPTED ? SRV_USB_OK : SRV_USB_GONE;
}

static void *run_in(void *arg)
{
    bridge *b = arg;

    srv_usb_pump_in(&b->io, b->sock);
    atomic_fetch_add(&b->finished, 1);
    return NULL;
}

static void *run_out(void *arg)
{
    bridge *b = arg;

    srv_usb_pump_out(&b->io, b->sock);
    atomic_fetch_add(&b->finished, 1);
    return NULL;
}

/* The device bus:addr in a context of the bridge's own, opened and claimed. */
static int open_device(bridge *b)
{
    libusb_device **list;
    ssize_t n, i;

    if (libusb_init(&b->ctx))
        return -1;
    if ((n = libusb_get_device_list(b->ctx, &list)) < 0)
        return -1;
    for (i = 0; i < n && !b->h; i++)
        if (libusb_get_bus_number(list[i]) == b->bus && libusb_get_device_address(list[i]) == b->addr &&
            libusb_open(list[i], &b->h) != 0)
            break;
    libusb_free_device_list(list, 1);
    if (!b->h)
        return -1;
    libusb_set_auto_detach_kernel_driver(b->h, 1);
    return libusb_claim_interface(b->h, b->iface) ? -1 : 0;
}

/* Threads and the loop's end of the socket. -1 when they cannot be had
 * (nothing left running), 0 once handed to the loop. */
static int start_bridge(srv_usb *u, bridge *b)
{
    int sv[2];
    handoff m;

    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv))
        return -1;
    fcntl(sv[0], F_SETFL, O_NONBLOCK);
    fcntl(sv[1], F_SETFL, O_NONBLOCK);
    b->sock = sv[1];
    b->io = (srv_usb_io){lu_in, lu_out, b, b->io.mps ? b->io.mps : LUMO_USB_MPS_FS, &b->stop};
    if (pthread_create(&b->th_in, NULL, run_in, b)) {
        close(sv[0]), close(sv[1]);
        b->sock = -1;
        return -1;
    }
    if (pthread_create(&b->th_out, NULL, run_out, b)) {
        atomic_store(&b->stop, 1);
        pthread_join(b->th_in, NULL);
        close(sv[0]), close(sv[1]);
        b->sock = -1;
        return -1;
    }
    m.fd = sv[0];
    snprintf(m.peer, sizeof m.peer, "%s", b->peer);
    if (write(u->pipe[1], &m, sizeof m) != (ssize_t)sizeof m)
        close(sv[0]);   /* the pumps see the socket close and end */
    return 0;
}

/* Threads joined, interface released, device closed: the bridge stays in
 * the list, as a mark, until the device leaves. */
static void release(bridge *b)
{
    if (b->released)
        return;
    b->released = 1;
    atomic_store(&b->stop, 1);
    if (b->sock >= 0) {
        pthread_join(b->th_in, NULL);
        pthread_join(b->th_out, NULL);
        close(b->sock);
        b->sock = -1;
    }
    if (b->h) {
        libusb_release_interface(b->h, b->iface);
        libusb_close(b->h);
        b->h = NULL;
    }
    if (b->ctx)
        libusb_exit(b->ctx);
    b->ctx = NULL;
}

/* A new client at bus:addr: bridged, or marked as refused (claimed by
 * another program, gone already) so it is not tried again. */
static void add_device(srv_usb *u, libusb_device *dev, const bridge *found)
{
    bridge *b = calloc(1, sizeof *b);

    if (!b)
        return;
    *b = *found;
    b->u = u;
    b->sock = -1;
    b->seen = 1;
    b->bus = libusb_get_bus_number(dev);
    b->addr = libusb_get_device_address(dev);
    atomic_init(&b->stop, 0);
    atomic_init(&b->finished, 0);
    if (open_device(b) || start_bridge(u, b) < 0) {
        fprintf(stderr, "lumo-server: %s: cannot claim interface %u: left alone\n", b->peer, b->iface);
        release(b);
    }
    b->next = u->bridges;
    u->bridges = b;
}

/* ---- the watcher --------------------------------------------------------------------- */

static bridge *known(srv_usb *u, uint8_t bus, uint8_t addr)
{
    bridge *b;

    for (b = u->bridges; b; b = b->next)
        if (b->bus == bus && b->addr == addr)
            return b;
    return NULL;
}

/* Every device present: new clients bridged, marks of those gone dropped. */
static void scan(srv_usb *u)
{
    libusb_context *ctx;
    libusb_device **list;
    bridge **pb, *b;
    ssize_t n, i;

    if (libusb_init(&ctx))
        return;
    for (b = u->bridges; b; b = b->next)
        b->seen = 0;
    n = libusb_get_device_list(ctx, &list);
    for (i = 0; i < n; i++) {
        bridge probe;
        memset(&probe, 0, sizeof probe);
        if ((b = known(u, libusb_get_bus_number(list[i]), libusb_get_device_address(list[i]))) != NULL)
            b->seen = 1;
        else if (is_client(u, list[i], &probe))
            add_device(u, list[i], &probe);
    }
    if (n >= 0)
        libusb_free_device_list(list, 1);
    libusb_exit(ctx);
    for (pb = &u->bridges; (b = *pb) != NULL;) {
        if (atomic_load(&b->finished) == 2)
            release(b);
        if (b->released && !b->seen) {
            *pb = b->next;
            free(b);
        } else {
            pb = &b->next;
        }
    }
}

static int LIBUSB_CALL on_arrival(libusb_context *ctx, libusb_device *dev, libusb_hotplug_event ev, void *arg)
{
    srv_usb *u = arg;

    (void)ctx, (void)dev, (void)ev;
    atomic_store(&u->arrived, 1);
    return 0;
}

/* Until the next scan: a hotplug arrival, or SRV_USB_POLL_MS. */
static void wait_a_while(srv_usb *u)
{
    struct timeval tv = {0, (long)SRV_USB_POLL_MS * 1000};

    if (u->watch)
        libusb_handle_events_timeout_completed(u->watch, &tv, NULL);
    else
        poll(NULL, 0, (int)SRV_USB_POLL_MS);
}

static void *watcher(void *arg)
{
    srv_usb *u = arg;

    while (!atomic_load(&u->stop)) {
        atomic_store(&u->arrived, 0);
        scan(u);
        if (!atomic_load(&u->arrived))
            wait_a_while(u);
    }
    return NULL;
}

/* Hotplug where libusb has it (arrivals only make the next scan come sooner). */
static void start_hotplug(srv_usb *u)
{
    if (!libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG) || libusb_init(&u->watch))
        return;
    if (libusb_hotplug_register_callback(u->watch, LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED, 0,
                                         u->any_id ? LIBUSB_HOTPLUG_MATCH_ANY : u->vid,
                                         u->any_id ? LIBUSB_HOTPLUG_MATCH_ANY : u->pid, LIBUSB_HOTPLUG_MATCH_ANY,
                                         on_arrival, u, &u->hp)) {
        libusb_exit(u->watch);
        u->watch = NULL;
    }
}

lumo_status srv_usb_start(srv_usb **out, int any_id, uint16_t vid, uint16_t pid, char *err, size_t errlen)
{
    libusb_context *probe;
    srv_usb *u;
    int r;

    *out = NULL;
    if ((r = libusb_init(&probe)))
        return srv_fail(err, errlen, LUMO_ERR_IO, "USB: libusb cannot start: %s (no USB on this machine?)",
                        libusb_strerror(r));
    libusb_exit(probe);
    if (!(u = calloc(1, sizeof *u)))
        return srv_fail(err, errlen, LUMO_ERR_NOMEM, "USB: out of memory");
    u->any_id = any_id, u->vid = vid, u->pid = pid;
    if (pipe2(u->pipe, O_CLOEXEC | O_NONBLOCK)) {
        free(u);
        return srv_fail(err, errlen, LUMO_ERR_IO, "USB: pipe: %s", strerror(errno));
    }
    start_hotplug(u);
    if (pthread_create(&u->watcher, NULL, watcher, u)) {
        u->watcher = 0;
        srv_usb_stop(u);
        return srv_fail(err, errlen, LUMO_ERR_IO, "USB: cannot start the watcher thread");
    }
    *out = u;
    return LUMO_OK;
}

int srv_usb_event_fd(const srv_usb *u)
{
    return u->pipe[0];
}

int srv_usb_take(srv_usb *u, char *peer, size_t cap)
{
    handoff m;

    if (read(u->pipe[0], &m, sizeof m) != (ssize_t)sizeof m)
        return -1;
    m.peer[sizeof m.peer - 1] = 0;
    snprintf(peer, cap, "%s", m.peer);
    return m.fd;
}

void srv_usb_stop(srv_usb *u)
{
    int fd;
    char peer[64];

    if (!u)
        return;
    atomic_store(&u->stop, 1);
    if (u->watch)
        libusb_interrupt_event_handler(u->watch);
    if (u->watcher)
        pthread_join(u->watcher, NULL);
    while (u->bridges) {
        bridge *b = u->bridges;
        u->bridges = b->next;
        release(b);
        free(b);
    }
    while ((fd = srv_usb_take(u, peer, sizeof peer)) >= 0)
        close(fd);
    if (u->watch) {
        libusb_hotplug_deregister_callback(u->watch, u->hp);
        libusb_exit(u->watch);
    }
    close(u->pipe[0]);
    close(u->pipe[1]);
    free(u);
}
