/*
 * converse.c — lumo-client's conversation over a link: HELLO, then the
 * driver's requests out and the frames in, each handed to the protocol
 * driver (lumo/net_client.h) and, when it took it, to the recorder and the
 * pictures, until the scene is complete.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "lumo/net.h"
#include "client.h"

static const char *frame_name(uint8_t type)
{
    static const char *names[] = {"?", "HELLO", "WELCOME", "REQUEST", "DATA", "END", "ERROR", "BYE"};
    return type < sizeof names / sizeof names[0] ? names[type] : "unknown";
}

static int is_replay(const client *c)
{
    return c->l.ops == &link_replay;
}

/* Errors start on a line of their own after the progress line. */
static const char *nl(const client *c)
{
    return c->o.quiet ? "" : "\n";
}

/* Where a failure happened, for a person: the frame after the last taken
 * and its byte offset in the received stream (a replay file's offset). */
static void say_where(const client *c, const char *what, lumo_status st)
{
    if (is_replay(c))
        fprintf(stderr, "%slumo-client: error: %s: %s at byte %llu (after frame %u): %s; the frames before it "
                "were applied, pictures drawn from them: %u\n", nl(c), c->l.target, what,
                (unsigned long long)c->taken_bytes, c->taken, lumo_strerror(st), c->frames_drawn);
    else
        fprintf(stderr, "%slumo-client: error: %s after frame %u (byte %llu of the stream): %s\n", nl(c), what,
                c->taken, (unsigned long long)c->taken_bytes, lumo_strerror(st));
}

/* The server is told why the client ends (docs/protocol.md §3). */
static void send_error(client *c, lumo_status st, const char *text)
{
    uint8_t out[LUMO_NET_OVERHEAD + 8 + LUMO_NET_MAX_TEXT];
    size_t n;

    if (!is_replay(c) && lumo_net_error_encode((uint32_t)st, text, out, sizeof out, &n) == LUMO_OK)
        (void)c->l.ops->send(&c->l, out, n);
}

static int send_hello(client *c)
{
    uint8_t out[512];
    size_t n;
    lumo_status st;

    if ((st = lumo_net_client_hello(&c->drv, out, sizeof out, &n))) {
        fprintf(stderr, "lumo-client: error: HELLO: %s\n", lumo_strerror(st));
        return -1;
    }
    return c->l.ops->send(&c->l, out, n);
}

/* The driver's requests (and BYE at the end). -1 when the driver failed
 * (said), 1 when the link failed. */
static int send_pending(client *c)
{
    uint8_t out[256];
    size_t n;
    lumo_status st;

    do {
        if ((st = lumo_net_client_next(&c->drv, out, sizeof out, &n))) {
            fprintf(stderr, "%slumo-client: error: %s\n", nl(c), lumo_strerror(st));
            return -1;
        }
        if (n && c->drv.state == LUMO_NET_DONE && c->o.updates_s) {
            c->bye_held = 1;   /* the updates phase ends the conversation */
            break;
        }
        if (n && c->l.ops->send(&c->l, out, n))
            return 1;
    } while (n && c->drv.state != LUMO_NET_DONE);
    return 0;
}

/* One whole frame f (its bytes at p, n of them) to the driver; then to the
 * recorder and the pictures. */
static int take(client *c, const lumo_net_frame *f, const uint8_t *p, size_t n)
{
    int resumed = f->type == LUMO_NET_WELCOME && c->drv.package_id != 0;
    lumo_status st;

    if ((st = lumo_net_client_on_frame(&c->drv, f))) {
        char what[64];
        snprintf(what, sizeof what, "%s frame", frame_name(f->type));
        say_where(c, what, st);
        send_error(c, st, "the client refused a frame");
        return -1;
    }
    /* a resumed connection's WELCOME is checked, not applied: not recorded */
    if (!resumed && record_frame(c->record, p, n)) {
        fprintf(stderr, "%slumo-client: error: %s: %s\n", nl(c), c->o.record, strerror(errno));
        return -1;
    }
    c->taken++;
    c->taken_bytes += n;
    c->failures = 0;   /* the link works: retries count again from here */
    c->resyncing = 0;
    c->silences = 0;
    return frames_due(c);
}

/* Lossy links: something was lost; ask again (HELLO, or the marker and the
 * requests behind it). Once per loss: while a marker is in flight and
 * nothing has been taken since, only `force` (silence) sends another. */
static int ask_again(client *c, int force)
{
    uint8_t out[512];
    size_t n;
    lumo_status st;

    if (c->resyncing && !force)
        return 0;
    if ((st = lumo_net_client_resync(&c->drv, out, sizeof out, &n))) {
        fprintf(stderr, "%slumo-client: error: %s\n", nl(c), lumo_strerror(st));
        return -1;
    }
    c->resyncs++;
    c->resyncing = 1;
    return n && c->l.ops->send(&c->l, out, n) ? 1 : 0;
}

/* Lossy links: skip from a refused frame at rx[at] to the next magic. */
static size_t skip(client *c, const uint8_t *rx, size_t len, size_t at)
{
    size_t next = lumo_net_resync(rx, len, at + 1);

    c->garbage += next - at;
    return next;
}

/* Decode and take every whole frame in rx[0..*len); keep the rest. */
static int take_frames(client *c, uint8_t *rx, size_t *len)
{
    size_t at = 0, used;
    lumo_net_frame f;
    lumo_status st;

    for (;;) {
        st = lumo_net_frame_decode(rx + at, *len - at, c->drv.cfg.max_payload, &f, &used);
        if (st == LUMO_ERR_TRUNCATED)
            break;
        if (st && c->l.ops->lossy) {
            c->refused++;
            at = skip(c, rx, *len, at);
            if (ask_again(c, 0) < 0)
                return -1;
            continue;
        }
        if (st) {
            say_where(c, is_replay(c) ? "a damaged frame" : "a frame from the server", st);
            send_error(c, st, "the client refused a frame");
            return -1;
        }
        if (c->l.ops->lossy && !lumo_net_client_expects(&c->drv, &f)) {
            c->stale++;   /* answers a request sent before a loss */
            at += used;
            continue;
        }
        if (take(c, &f, rx + at, used))
            return -1;
        at += used;
        if (c->drv.state == LUMO_NET_DONE)
            break;
    }
    memmove(rx, rx + at, *len - at);
    *len -= at;
    return 0;
}

/* The link ended before the scene was complete. */
static void say_ended(client *c, long got, size_t len)
{
    if (is_replay(c) && got == 0)
        fprintf(stderr, "%slumo-client: error: %s: the recording ends%s at byte %llu (after frame %u) before the "
                "scene is complete; the frames before it were applied, pictures drawn from them: %u\n", nl(c),
                c->l.target, len ? " inside a frame" : "", (unsigned long long)(c->taken_bytes + len), c->taken,
                c->frames_drawn);
    else
        fprintf(stderr, "%slumo-client: error: %s: %s before the scene was complete (after frame %u)\n", nl(c),
                c->l.target, got == 0 ? "the connection closed" : got == LINK_TIMEOUT ? "nothing arrived for 60 s"
                                                                                    : c->l.err, c->taken);
}

/* Silences in a row (no frame taken in between) before a lossy link gives up. */
#define MAX_SILENCES 10u

/* How long a lossy link may stay silent while something is awaited before
 * it counts as lost: a few round trips, at least 300 ms. */
static int silence_ms(const client *c)
{
    uint32_t rtt = c->drv.costs.rtt_ms;
    uint32_t ms = rtt ? 300 + 4 * rtt : 1000;

    return (int)(ms > 10000 ? 10000 : ms);
}

/* Lossy links: nothing came for silence_ms: the bytes left are a damaged
 * frame's (a dropped byte keeps it waiting for one that never comes) or
 * nothing; skip to the next magic after their start and ask again. */
static int on_silence(client *c, uint8_t *rx, size_t *len)
{
    c->timeouts++;
    if (++c->silences > MAX_SILENCES) {
        fprintf(stderr, "%slumo-client: error: %s: nothing taken through %u silences in a row (%d ms each): is it "
                "a lumo serial line?\n", nl(c), c->l.target, MAX_SILENCES, silence_ms(c));
        return -1;
    }
    if (*len) {
        size_t next = skip(c, rx, *len, 0);
        memmove(rx, rx + next, *len - next);
        *len -= next;
    }
    return ask_again(c, 1);
}

static void sleep_ms(uint32_t ms)
{
    struct timespec ts = {(time_t)(ms / 1000), (long)(ms % 1000) * 1000000L};
    while (nanosleep(&ts, &ts) && errno == EINTR)
        ;
}

/* The connection dropped (or failed): the bytes of a frame it cut are
 * dropped, the link opened again after 50 ms, 100, 200 ... 2 s, at most
 * --retries times in a row without a frame taken in between, and the
 * driver resumes. 0, or -1 (said) when the retries are spent. */
static int resume(client *c, size_t *len, const char *why)
{
    char reason[320];

    snprintf(reason, sizeof reason, "%s", why);
    c->cuts++;
    c->cut_bytes += *len;
    *len = 0;
    c->l.ops->close(&c->l);
    lumo_net_client_reset_link(&c->drv);
    while (c->failures < c->o.retries) {
        uint32_t wait = 50u << (c->failures < 6 ? c->failures : 6);
        c->failures++;
        sleep_ms(wait > 2000 ? 2000 : wait);
        if (c->l.ops->open(&c->l) == 0 && send_hello(c) == 0)
            return 0;
        snprintf(reason, sizeof reason, "%s", c->l.err);
        c->l.ops->close(&c->l);
    }
    fprintf(stderr, "%slumo-client: error: %s: connection lost after frame %u (%s); %u reconnections in a row "
            "failed\n", nl(c), c->l.target, c->taken, reason, c->failures);
    return -1;
}

/* The receive buffer: room for one frame of the largest payload taken. */
typedef struct rx_buf {
    uint8_t *b;
    size_t cap, len;
} rx_buf;

/* The link failed (send or read): resumed when it can be, else said. */
static int link_failed(client *c, rx_buf *rx, long got)
{
    if (!c->l.ops->resumable) {
        if (got > 0)
            fprintf(stderr, "%slumo-client: error: %s: %s\n", nl(c), c->l.target, c->l.err);
        else
            say_ended(c, got, rx->len);
        return -1;
    }
    return resume(c, &rx->len, got > 0 ? c->l.err : got == 0 ? "the connection closed"
                                        : got == LINK_TIMEOUT ? "nothing for 60 s" : c->l.err);
}

/* One turn: the driver's frames out, what the link has in. -1 on failure. */
static int turn(client *c, rx_buf *rx)
{
    long got;
    int s;

    if ((s = send_pending(c)) < 0)
        return -1;
    if (s > 0)
        return link_failed(c, rx, 1);
    if (c->drv.state == LUMO_NET_DONE)
        return 0;
    got = c->l.ops->read(&c->l, rx->b + rx->len, rx->cap - rx->len,
                         is_replay(c) ? -1 : c->l.ops->lossy ? silence_ms(c) : 60000);
    if (got == LINK_TIMEOUT && c->l.ops->lossy) {
        if ((s = on_silence(c, rx->b, &rx->len)) < 0 || (s > 0 && link_failed(c, rx, 1)))
            return -1;
        return take_frames(c, rx->b, &rx->len);   /* what followed the skipped bytes */
    }
    if (got <= 0)
        return link_failed(c, rx, got);
    rx->len += (size_t)got;
    return take_frames(c, rx->b, &rx->len);
}

int converse(client *c)
{
    rx_buf rx = {NULL, c->drv.cfg.max_payload + LUMO_NET_OVERHEAD, 0};
    int rc = -1;

    if (!(rx.b = malloc(rx.cap)))
        return -1;
    if (c->l.ops->open(&c->l))
        fprintf(stderr, "lumo-client: error: %s\n", c->l.err);
    else if (send_hello(c))
        fprintf(stderr, "lumo-client: error: %s: %s\n", c->l.target, c->l.err);
    else {
        while (c->drv.state != LUMO_NET_DONE)
            if (turn(c, &rx))
                break;
        rc = c->drv.state == LUMO_NET_DONE ? frames_due(c) : -1;
        if (rc == 0 && c->bye_held)
            rc = updates_phase(c, rx.b, rx.cap, &rx.len);
    }
    c->l.ops->close(&c->l);
    free(rx.b);
    return rc;
}
