/*
 * test_net_fake.h — an in-process fake lumo-server for the protocol driver's
 * tests (tests/unit/test_net_client.c) and its fuzz target
 * (tests/fuzz/fuzz_net_client.c), built from the real pieces and nothing of
 * server/serve/:
 *
 *  - a package read into memory and opened with lumo_package_open, every
 *    progressive stream's records walked with lumo_pmesh_next_record, the
 *    IVG's rounds from its IVGS (lumo_package_ivg_order);
 *  - the WELCOME of docs/protocol.md §2 (INFO, each PMSH's header,
 *    IVGD, IVGS, ORDR) with the arena need lumo_session_message_need gives,
 *    and for a package with PRTV chunks the WELCOME of a client asking for
 *    PRT (§10: each PRTV's 12-byte header and the PRTL after them);
 *  - answers planned by brute force from the protocol's words, not with
 *    lumo_net_geometry_end: geometry, as many whole batches from the cursor
 *    as hold at most the amount of vertices (counted batch by batch, the last
 *    one short), at least one; lighting, rounds [cursor, cursor + amount)
 *    cut at the last; each answer in as few DATA frames as the client's max
 *    payload allows (whole records; whole rounds, a round too large split at
 *    record boundaries with count 0 until the frame that ends it); PRT,
 *    bytes [C, min(S, F + (H + n) * (2 + 2P))) of the chunk in spans of the
 *    largest size the payload takes, cut anywhere (a receiver must take
 *    any cut; lumo-server prefers record ends); END at the end of a
 *    channel.
 *
 * Test code: C99 (the fuzz build), heap allowed, no cmocka (callers assert).
 */
#ifndef LUMO_TEST_NET_FAKE_H
#define LUMO_TEST_NET_FAKE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/ivg.h"
#include "lumo/net.h"
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo/session.h"
#include "lumo/wire.h"

#define FAKE_QUEUE 64u

typedef struct fake_mesh {
    const uint8_t    *stream;   /* the PMSH chunk */
    uint32_t          len;
    lumo_pmesh_header h;
    uint32_t         *rec;      /* batch_count + 1 record offsets */
} fake_mesh;

typedef struct fake_pkg {
    uint8_t       *data;
    size_t         size;
    lumo_package   pkg;
    uint32_t       id;          /* header CRC (bytes 20..23) */
    uint32_t       meshes;
    fake_mesh      mesh[LUMO_MAX_MESHES];
    int            has_ivg;
    lumo_ivg_order order;
    const uint8_t *bundle[2];   /* [LUMO_IVG_FORM_FLOAT] IVGF, [..._QUANTIZED] IVGQ */
    uint32_t       bundle_len[2];
    uint8_t       *welcome;     /* the WELCOME frame */
    size_t         welcome_len;
    uint32_t       need;        /* arena bytes it states */
    int            has_prt;     /* PRT (§10): the PRTV chunks, the PRT WELCOME */
    const uint8_t *prt[LUMO_MAX_MESHES];
    uint32_t       prt_len[LUMO_MAX_MESHES];
    uint8_t       *welcome_prt;
    size_t         welcome_prt_len;
    uint32_t       need_prt;
} fake_pkg;

static inline void fake_pkg_free(fake_pkg *k)
{
    uint32_t m;

    for (m = 0; m < k->meshes; m++)
        free(k->mesh[m].rec);
    free(k->welcome);
    free(k->welcome_prt);
    free(k->data);
    memset(k, 0, sizeof *k);
}

static inline lumo_status fake_welcome(fake_pkg *k, int prt)
{
    lumo_net_msg msgs[LUMO_NET_MAX_WELCOME_MSGS];
    uint32_t n = 0, m, i;
    size_t need = LUMO_ARENA_SLACK, cap = LUMO_NET_OVERHEAD + 12, b;
    const uint8_t *d;
    uint32_t len;
    lumo_status st;

    if ((st = lumo_package_find(&k->pkg, LUMO_PKG_INFO, 0, &d, &len)))
        return st;
    msgs[n].type = LUMO_PKG_INFO, msgs[n].index = 0, msgs[n].len = len, msgs[n++].data = d;
    for (m = 0; m < k->meshes; m++) {
        msgs[n].type = LUMO_PKG_PMSH, msgs[n].index = m, msgs[n].len = k->mesh[m].h.header_bytes;
        msgs[n++].data = k->mesh[m].stream;
    }
    if (k->has_ivg) {
        if (lumo_package_find(&k->pkg, LUMO_PKG_IVGD, 0, &d, &len) == LUMO_OK)
            msgs[n].type = LUMO_PKG_IVGD, msgs[n].index = 0, msgs[n].len = len, msgs[n++].data = d;
        if (lumo_package_find(&k->pkg, LUMO_PKG_IVGS, 0, &d, &len) == LUMO_OK)
            msgs[n].type = LUMO_PKG_IVGS, msgs[n].index = 0, msgs[n].len = len, msgs[n++].data = d;
    }
    if (lumo_package_find(&k->pkg, LUMO_PKG_ORDR, 0, &d, &len) == LUMO_OK)
        msgs[n].type = LUMO_PKG_ORDR, msgs[n].index = 0, msgs[n].len = len, msgs[n++].data = d;
    for (m = 0; prt && m < k->meshes; m++)
        if (k->prt[m])
            msgs[n].type = LUMO_MSG_PRTV, msgs[n].index = m, msgs[n].len = 12, msgs[n++].data = k->prt[m];
    if (prt && lumo_package_find(&k->pkg, LUMO_MSG_PRTL, 0, &d, &len) == LUMO_OK)
        msgs[n].type = LUMO_MSG_PRTL, msgs[n].index = 0, msgs[n].len = len, msgs[n++].data = d;
    for (i = 0; i < n; i++) {
        if ((st = lumo_session_message_need(msgs[i].type, msgs[i].data, msgs[i].len, &b)))
            return st;
        need += b;
        cap += 12 + ((msgs[i].len + 3u) & ~3u);
    }
    if (prt) {
        k->need_prt = (uint32_t)need;
        if (!(k->welcome_prt = (uint8_t *)malloc(cap)))
            return LUMO_ERR_NOMEM;
        return lumo_net_welcome_encode(k->id, k->need_prt, msgs, n, k->welcome_prt, cap, &k->welcome_prt_len);
    }
    k->need = (uint32_t)need;
    if (!(k->welcome = (uint8_t *)malloc(cap)))
        return LUMO_ERR_NOMEM;
    return lumo_net_welcome_encode(k->id, k->need, msgs, n, k->welcome, cap, &k->welcome_len);
}

/* Take ownership of data[0..size) (malloc'ed) and index it. */
static inline lumo_status fake_pkg_open(fake_pkg *k, uint8_t *data, size_t size)
{
    lumo_pkg_info info;
    uint32_t m, b;
    lumo_status st;

    memset(k, 0, sizeof *k);
    k->data = data, k->size = size;
    if ((st = lumo_package_open(&k->pkg, data, size)) || (st = lumo_package_info(&k->pkg, &info)))
        return st;
    if (info.mesh_count > LUMO_MAX_MESHES)
        return LUMO_ERR_LIMIT;
    k->id = lumo_wire_le32(data + 20);
    k->meshes = info.mesh_count;
    for (m = 0; m < k->meshes; m++) {
        fake_mesh *fm = &k->mesh[m];
        size_t at, n;
        const uint8_t *r;
        if ((st = lumo_package_find(&k->pkg, LUMO_PKG_PMSH, m, &fm->stream, &fm->len)) ||
            (st = lumo_pmesh_read_header(fm->stream, fm->len, &fm->h)))
            return st;
        at = fm->h.header_bytes;
        if (!(fm->rec = (uint32_t *)malloc(((size_t)fm->h.batch_count + 1) * sizeof *fm->rec)))
            return LUMO_ERR_NOMEM;
        for (b = 0; b < fm->h.batch_count; b++) {
            fm->rec[b] = (uint32_t)at;
            if ((st = lumo_pmesh_next_record(fm->stream, fm->len, &at, &r, &n)))
                return st;
        }
        fm->rec[b] = (uint32_t)at;
        if (at != fm->len)
            return LUMO_ERR_CORRUPT;
        if (lumo_package_find(&k->pkg, LUMO_MSG_PRTV, m, &k->prt[m], &k->prt_len[m]) == LUMO_OK)
            k->has_prt = 1;
        else
            k->prt[m] = NULL;
    }
    if (lumo_package_ivg_order(&k->pkg, &k->order) == LUMO_OK) {
        k->has_ivg = 1;
        if ((st = lumo_package_find(&k->pkg, LUMO_PKG_IVGF, 0, &k->bundle[LUMO_IVG_FORM_FLOAT],
                                    &k->bundle_len[LUMO_IVG_FORM_FLOAT])) ||
            (st = lumo_package_find(&k->pkg, LUMO_PKG_IVGQ, 0, &k->bundle[LUMO_IVG_FORM_QUANTIZED],
                                    &k->bundle_len[LUMO_IVG_FORM_QUANTIZED])))
            return st;
    }
    if (k->has_prt && (st = fake_welcome(k, 1)))
        return st;
    return fake_welcome(k, 0);
}

static inline lumo_status fake_pkg_load(fake_pkg *k, const char *path)
{
    FILE *f = fopen(path, "rb");
    uint8_t *data;
    long size;

    memset(k, 0, sizeof *k);
    if (!f)
        return LUMO_ERR_IO;
    if (fseek(f, 0, SEEK_END) || (size = ftell(f)) <= 0 || fseek(f, 0, SEEK_SET) ||
        !(data = (uint8_t *)malloc((size_t)size)) || fread(data, 1, (size_t)size, f) != (size_t)size) {
        fclose(f);
        return LUMO_ERR_IO;
    }
    fclose(f);
    return fake_pkg_open(k, data, (size_t)size);
}

/* Vertices batch b of a stream adds (the base mesh for b = 0; the last
 * batch holds what is left). */
static inline uint32_t fake_batch_vertices(const lumo_pmesh_header *h, uint32_t b)
{
    uint64_t before;

    if (b == 0)
        return h->base_vertices;
    before = (uint64_t)h->base_vertices + (uint64_t)(b - 1) * h->batch_vertices;
    if (before >= h->vertices)
        return 0;
    return h->vertices - before < h->batch_vertices ? (uint32_t)(h->vertices - before) : h->batch_vertices;
}

/* Brute force: the batches [cursor, end) answering `amount` vertices. */
static inline uint32_t fake_geometry_end(const lumo_pmesh_header *h, uint32_t cursor, uint32_t amount)
{
    uint64_t sum = 0;
    uint32_t e = cursor;

    while (e < h->batch_count && sum + fake_batch_vertices(h, e) <= amount)
        sum += fake_batch_vertices(h, e++);
    return e == cursor && e < h->batch_count ? e + 1 : e;
}

/* PRT (§10), from the protocol's words: the chunk's fixed part F, one
 * vertex record's bytes, and the end of an answer to (cursor, amount). */
static inline uint32_t fake_prt_end(const fake_pkg *k, uint32_t m, uint32_t cursor, uint32_t amount)
{
    const uint8_t *h = k->prt[m];
    uint64_t N = h[1], P = h[2], K = lumo_wire_le32(h + 4), F = 12 + K * (2 * N * N * (P + 1) + 2), vb = 2 + 2 * P;
    uint64_t held = cursor > F ? (cursor - F) / vb : 0, end = F + (held + amount) * vb;
    return end > k->prt_len[m] ? k->prt_len[m] : (uint32_t)end;
}

static inline uint32_t fake_rounds_end(const fake_pkg *k, uint32_t cursor, uint32_t amount)
{
    return amount >= k->order.rounds - cursor ? k->order.rounds : cursor + amount;
}

/* The server's side of one connection. */
typedef struct fake_server {
    const fake_pkg  *k;
    int              prt;         /* the client asked for PRT in HELLO */
    uint8_t          form;
    uint32_t         max_payload;
    lumo_net_request q[FAKE_QUEUE];
    uint32_t         qh, qn;
    int              answering;
    lumo_net_request cur;
    uint32_t         next, end;   /* batches / rounds left of the answer */
    uint32_t         rec, pos;    /* lighting: next record, its byte offset */
    uint64_t         frames, bytes;
} fake_server;

static inline void fake_server_init(fake_server *s, const fake_pkg *k, uint8_t form, uint32_t max_payload)
{
    memset(s, 0, sizeof *s);
    s->k = k, s->form = form, s->max_payload = max_payload;
}

/* Queue a REQUEST (RANGE for what lumo-server refuses; LIMIT when full). */
static inline lumo_status fake_server_request(fake_server *s, const lumo_net_request *r)
{
    if (s->qn == FAKE_QUEUE)
        return LUMO_ERR_LIMIT;
    if (r->channel == LUMO_NET_PRT) {
        if (!s->prt || r->amount == 0 || r->mesh >= s->k->meshes || !s->k->prt[r->mesh] || r->cursor < 12 ||
            r->cursor > s->k->prt_len[r->mesh])
            return LUMO_ERR_RANGE;
        s->q[(s->qh + s->qn++) % FAKE_QUEUE] = *r;
        return LUMO_OK;
    }
    if (r->amount == 0 || r->channel > LUMO_NET_LIGHTING ||
        (r->channel == LUMO_NET_GEOMETRY &&
         (r->mesh >= s->k->meshes || r->cursor > s->k->mesh[r->mesh].h.batch_count)) ||
        (r->channel == LUMO_NET_LIGHTING && (!s->k->has_ivg || r->cursor > s->k->order.rounds)))
        return LUMO_ERR_RANGE;
    s->q[(s->qh + s->qn++) % FAKE_QUEUE] = *r;
    return LUMO_OK;
}

static inline uint32_t fake_record_bytes(const uint8_t *p, uint8_t form)
{
    if (lumo_wire_le32(p) & LUMO_IVG_SOLID_BIT)
        return 4;
    return form == LUMO_IVG_FORM_QUANTIZED ? LUMO_IVG_QUANT_RECORD : LUMO_IVG_FLOAT_RECORD;
}

static inline void fake_geometry_frame(fake_server *s, lumo_net_data *d)
{
    const fake_mesh *m = &s->k->mesh[s->cur.mesh];
    uint32_t max = s->max_payload - LUMO_NET_DATA_HEAD, e = s->next + 1;

    while (e < s->end && m->rec[e + 1] - m->rec[s->next] <= max)
        e++;
    d->channel = LUMO_NET_GEOMETRY, d->mesh = s->cur.mesh;
    d->first = s->next, d->count = d->records = e - s->next;
    d->bytes = m->stream + m->rec[s->next];
    d->len = m->rec[e] - m->rec[s->next];
    s->next = e;
}

static inline void fake_lighting_frame(fake_server *s, lumo_net_data *d)
{
    const lumo_ivg_order *o = &s->k->order;
    const uint8_t *area = s->k->bundle[s->form];
    uint32_t max = s->max_payload - LUMO_NET_DATA_HEAD, r = s->next, start = s->pos;
    uint32_t round_end = lumo_ivg_order_offset(o, (lumo_ivg_form)s->form, r + 1);

    d->channel = LUMO_NET_LIGHTING, d->form = s->form, d->first = r, d->bytes = area + start;
    if (s->rec == lumo_ivg_order_first(o, r) && round_end - start <= max) {
        uint32_t e = r + 1;   /* whole rounds */
        while (e < s->end && lumo_ivg_order_offset(o, (lumo_ivg_form)s->form, e + 1) - start <= max)
            e++;
        d->count = e - r;
        d->records = lumo_ivg_order_first(o, e) - s->rec;
        s->pos = lumo_ivg_order_offset(o, (lumo_ivg_form)s->form, e);
        s->rec = lumo_ivg_order_first(o, e);
        s->next = e;
    } else {   /* a round too large for a frame: whole records */
        uint32_t k = s->rec, pos = s->pos, last = lumo_ivg_order_first(o, r + 1);
        while (k < last) {
            uint32_t b = fake_record_bytes(area + pos, s->form);
            if (pos + b - start > max && k > s->rec)
                break;
            pos += b, k++;
        }
        d->records = k - s->rec;
        d->count = k == last ? 1 : 0;
        s->rec = k, s->pos = pos;
        if (k == last)
            s->next = r + 1;
    }
    d->len = s->pos - start;
}

static inline void fake_prt_frame(fake_server *s, lumo_net_data *d)
{
    uint32_t max = s->max_payload - LUMO_NET_DATA_HEAD, n = s->end - s->next < max ? s->end - s->next : max;

    d->channel = LUMO_NET_PRT, d->mesh = s->cur.mesh, d->form = 0;
    d->first = d->records = s->next, d->count = d->len = n;
    d->bytes = s->k->prt[s->cur.mesh] + s->next;
    s->next += n;
}

/* The next frame the server sends, encoded into out (cap bytes): 1, or 0
 * when nothing is asked. */
static inline int fake_server_frame(fake_server *s, uint8_t *out, size_t cap, size_t *written)
{
    lumo_net_data d;

    while (!s->answering) {
        const fake_pkg *k = s->k;
        if (!s->qn)
            return 0;
        s->cur = s->q[s->qh];
        s->qh = (s->qh + 1) % FAKE_QUEUE, s->qn--;
        if (s->cur.channel == LUMO_NET_PRT) {
            if (s->cur.cursor == k->prt_len[s->cur.mesh]) {
                lumo_net_end e;
                e.channel = LUMO_NET_PRT, e.mesh = s->cur.mesh;
                return lumo_net_end_encode(&e, out, cap, written) == LUMO_OK;
            }
            s->next = s->cur.cursor;
            s->end = fake_prt_end(k, s->cur.mesh, s->cur.cursor, s->cur.amount);
        } else if (s->cur.channel == LUMO_NET_GEOMETRY) {
            const lumo_pmesh_header *h = &k->mesh[s->cur.mesh].h;
            if (s->cur.cursor == h->batch_count) {
                lumo_net_end e;
                e.channel = LUMO_NET_GEOMETRY, e.mesh = s->cur.mesh;
                return lumo_net_end_encode(&e, out, cap, written) == LUMO_OK;
            }
            s->next = s->cur.cursor;
            s->end = fake_geometry_end(h, s->cur.cursor, s->cur.amount);
        } else {
            if (s->cur.cursor == k->order.rounds) {
                lumo_net_end e;
                e.channel = LUMO_NET_LIGHTING, e.mesh = 0;
                return lumo_net_end_encode(&e, out, cap, written) == LUMO_OK;
            }
            s->next = s->cur.cursor;
            s->end = fake_rounds_end(k, s->cur.cursor, s->cur.amount);
            s->rec = lumo_ivg_order_first(&k->order, s->next);
            s->pos = lumo_ivg_order_offset(&k->order, (lumo_ivg_form)s->form, s->next);
        }
        s->answering = 1;
    }
    memset(&d, 0, sizeof d);
    if (s->cur.channel == LUMO_NET_PRT)
        fake_prt_frame(s, &d);
    else if (s->cur.channel == LUMO_NET_GEOMETRY)
        fake_geometry_frame(s, &d);
    else
        fake_lighting_frame(s, &d);
    if (s->next >= s->end)
        s->answering = 0;
    if (lumo_net_data_encode(&d, out, cap, written))
        return 0;
    s->frames++;
    s->bytes += *written;
    return 1;
}

#endif
