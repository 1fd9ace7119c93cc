/*
 * updates.c — lumo-client --updates: once the scene is complete, keep the
 * connection and pull the lighting updates of a dynamic scene
 * (docs/protocol.md §9, docs/dynamic.md) with the updates poller
 * (lumo/net_updates.h), drawing a frame every --update-every ms, then BYE.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/net_updates.h"
#include "../../net/host/net_socket.h"
#include "client.h"

static int send_request(client *c, lumo_net_updates *u, uint32_t now)
{
    uint8_t out[64];
    size_t n = 0;
    lumo_status st = lumo_net_updates_next(u, now, out, sizeof out, &n);
    if (st) {
        fprintf(stderr, "\nlumo-client: error: updates: %s\n", lumo_strerror(st));
        return -1;
    }
    if (n && c->l.ops->send(&c->l, out, n)) {
        fprintf(stderr, "\nlumo-client: error: %s: %s\n", c->l.target, c->l.err);
        return -1;
    }
    return 0;
}

/* Every whole frame in rx to the poller; the rest kept. */
static int take(client *c, lumo_net_updates *u, uint8_t *rx, size_t *len, uint32_t now)
{
    size_t at = 0, used;
    lumo_net_frame f;
    for (;;) {
        lumo_status st = lumo_net_frame_decode(rx + at, *len - at, c->drv.cfg.max_payload, &f, &used);
        if (st == LUMO_ERR_TRUNCATED)
            break;
        if (!st && !lumo_net_updates_takes(&f) && f.type != LUMO_NET_ERROR)
            st = LUMO_ERR_STATE;
        if (st || (st = lumo_net_updates_on_frame(u, &f, now))) {
            fprintf(stderr, "\nlumo-client: error: updates: a frame from the server: %s (the last good lighting "
                    "kept)\n", lumo_strerror(st));
            return -1;
        }
        c->taken++;
        c->taken_bytes += used;
        at += used;
    }
    memmove(rx, rx + at, *len - at);
    *len -= at;
    return 0;
}

static void bye(client *c)
{
    uint8_t out[16];
    size_t n;
    if (lumo_net_bye_encode(out, sizeof out, &n) == LUMO_OK)
        (void)c->l.ops->send(&c->l, out, n);
}

int updates_phase(client *c, uint8_t *rx, size_t cap, size_t *len)
{
    lumo_net_updates u;
    uint8_t form = c->o.use_float ? LUMO_IVG_FORM_FLOAT : LUMO_IVG_FORM_QUANTIZED;
    uint32_t t0 = host_net_clock_ms(NULL), next_draw = t0, frame = 0, total = c->o.updates_s * 1000u;
    int rc = 0;
    if (lumo_net_updates_init(&u, &c->ses, form, c->o.update_amount, c->o.update_every_ms))
        return -1;
    for (uint32_t now = t0; !rc && now - t0 < total; now = host_net_clock_ms(NULL)) {
        if ((rc = send_request(c, &u, now)))
            break;
        if ((int32_t)(now - next_draw) >= 0) {
            rc = draw_update_frame(c, frame++, (now - t0) / 1000.0, u.records);
            next_draw += c->o.update_every_ms;
            continue;
        }
        uint32_t wait = next_draw - now;
        long got = c->l.ops->read(&c->l, rx + *len, cap - *len, (int)(wait < 50 ? wait : 50));
        if (got == LINK_TIMEOUT)
            continue;
        if (got <= 0) {
            fprintf(stderr, "\nlumo-client: error: %s: the connection ended during the updates\n", c->l.target);
            return -1;
        }
        *len += (size_t)got;
        rc = take(c, &u, rx, len, host_net_clock_ms(NULL));
    }
    if (!rc)
        bye(c);
    printf("lumo-client: updates: %u records in %u answers over %u s, %u frames drawn\n", u.records, u.answers,
           c->o.updates_s, frame);
    return rc;
}
