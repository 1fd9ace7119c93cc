/*
 * plan.c — requests to byte ranges of the mapping (serve/plan.h).
 */
#include "serve/plan.h"

#include <stdio.h>
#include <string.h>
#include "lumo/ivg.h"
#include "lumo/prt.h"
#include "common/status_msg.h"
#include "lumo/wire.h"

/* PRT (§10): cursor = bytes of the mesh's PRTV chunk the client holds
 * (at least its header, from WELCOME); the answer is the rest of the
 * clusters and pass table, then `amount` more vertex records than the
 * client holds whole. */
static lumo_status plan_prt(const srv_pkg *p, const lumo_net_request *r, srv_answer *a, int *end_of_channel,
                            char *err, size_t errlen)
{
    const srv_mesh_index *m;
    uint64_t held, end;

    if (r->mesh >= p->mesh_count || !p->mesh[r->mesh].prt)
        return srv_fail(err, errlen, LUMO_ERR_RANGE, "PRT request: mesh %u has no PRTV", r->mesh);
    m = &p->mesh[r->mesh];
    if (r->cursor < LUMO_PRT_HEADER_SIZE || r->cursor > m->prt_len)
        return srv_fail(err, errlen, LUMO_ERR_RANGE, "mesh %u: PRT cursor %u outside [%u, %u]", r->mesh, r->cursor,
                        LUMO_PRT_HEADER_SIZE, m->prt_len);
    a->mesh = r->mesh;
    if (r->cursor == m->prt_len)
        return *end_of_channel = 1, LUMO_OK;
    held = r->cursor > m->prt_fixed ? (r->cursor - m->prt_fixed) / m->prt_vbytes : 0;
    end = m->prt_fixed + (held + r->amount) * m->prt_vbytes;
    a->next = r->cursor;
    a->end = end > m->prt_len ? m->prt_len : (uint32_t)end;
    return LUMO_OK;
}

lumo_status srv_plan_start(const srv_pkg *p, const lumo_net_request *r, uint8_t form, uint32_t max_payload,
                           srv_answer *a, int *end_of_channel, char *err, size_t errlen)
{
    memset(a, 0, sizeof *a);
    *end_of_channel = 0;
    if (max_payload <= LUMO_NET_DATA_HEAD)
        return srv_fail(err, errlen, LUMO_ERR_LIMIT, "max payload %u holds no record", max_payload);
    a->channel = r->channel;
    a->max_data = max_payload - LUMO_NET_DATA_HEAD;
    if (r->amount == 0)
        return srv_fail(err, errlen, LUMO_ERR_RANGE, "request for 0 %s", r->channel ? "rounds" : "vertices");
    if (r->channel == LUMO_NET_GEOMETRY) {
        const srv_mesh_index *m;
        uint32_t b;
        if (r->mesh >= p->mesh_count)
            return srv_fail(err, errlen, LUMO_ERR_RANGE, "mesh %u past the mesh count %u", r->mesh, p->mesh_count);
        m = &p->mesh[r->mesh];
        if (r->cursor > m->h.batch_count)
            return srv_fail(err, errlen, LUMO_ERR_RANGE, "mesh %u: cursor %u past its %u batches", r->mesh,
                        r->cursor, m->h.batch_count);
        a->mesh = r->mesh;
        if (r->cursor == m->h.batch_count)
            return *end_of_channel = 1, LUMO_OK;
        a->next = r->cursor;
        a->end = lumo_net_geometry_end(&m->h, r->cursor, r->amount);
        if (m->max_record > a->max_data)   /* only then can a record of the range be too large */
            for (b = a->next; b < a->end; b++)
                if (m->rec[b + 1] - m->rec[b] > a->max_data)
                    return srv_fail(err, errlen, LUMO_ERR_LIMIT,
                                "mesh %u: batch record %u is %u bytes, more than max payload %u allows",
                                r->mesh, b, m->rec[b + 1] - m->rec[b], max_payload);
        return LUMO_OK;
    }
    if (r->channel == LUMO_NET_LIGHTING) {
        const srv_ivg_index *g = &p->ivg;
        if (!g->present)
            return srv_fail(err, errlen, LUMO_ERR_RANGE, "lighting request: the package has no IVG");
        if (form != LUMO_IVG_FORM_FLOAT && form != LUMO_IVG_FORM_QUANTIZED)
            return srv_fail(err, errlen, LUMO_ERR_RANGE, "lighting request: no IVG form chosen in HELLO");
        if (r->cursor > g->rounds)
            return srv_fail(err, errlen, LUMO_ERR_RANGE, "lighting cursor %u past the %u rounds", r->cursor,
                        g->rounds);
        if (r->cursor == g->rounds)
            return *end_of_channel = 1, LUMO_OK;
        a->form = form;
        a->next = r->cursor;
        a->end = r->amount > g->rounds - r->cursor ? g->rounds : r->cursor + r->amount;
        a->rec = g->first[a->next];
        a->pos = g->off[form][a->next];
        return LUMO_OK;
    }
    if (r->channel == LUMO_NET_PRT)
        return plan_prt(p, r, a, end_of_channel, err, errlen);
    return srv_fail(err, errlen, LUMO_ERR_RANGE, "unknown channel %u", r->channel);
}

static int next_geometry(const srv_pkg *p, srv_answer *a, lumo_net_data *d)
{
    const srv_mesh_index *m = &p->mesh[a->mesh];
    uint32_t e = a->next + 1;   /* a record fits: checked by srv_plan_start */

    while (e < a->end && m->rec[e + 1] - m->rec[a->next] <= a->max_data)
        e++;
    d->channel = LUMO_NET_GEOMETRY;
    d->mesh = a->mesh;
    d->first = a->next;
    d->count = d->records = e - a->next;
    d->form = 0;
    d->bytes = m->stream + m->rec[a->next];
    d->len = m->rec[e] - m->rec[a->next];
    a->next = e;
    return 1;
}

/* Bytes of the record at area[pos] (docs/ivg-format.md §2.2). */
static uint32_t record_bytes(const uint8_t *area, uint32_t pos, uint8_t form)
{
    if (lumo_wire_le32(area + pos) & 0x80000000u)
        return 4;
    return 4 + 6 * (form == LUMO_IVG_FORM_QUANTIZED ? 7u : 24u);
}

static int next_lighting(const srv_pkg *p, srv_answer *a, lumo_net_data *d)
{
    const srv_ivg_index *g = &p->ivg;
    const uint32_t *off = g->off[a->form];
    const uint8_t *area = g->bundle[a->form];
    uint32_t r = a->next, start = a->pos;

    d->channel = LUMO_NET_LIGHTING;
    d->mesh = 0;
    d->form = a->form;
    d->first = r;
    d->bytes = area + start;
    if (a->rec == g->first[r] && off[r + 1] - off[r] <= a->max_data) {
        uint32_t e = r + 1;   /* whole rounds */
        while (e < a->end && off[e + 1] - off[r] <= a->max_data)
            e++;
        d->count = e - r;
        d->records = g->first[e] - g->first[r];
        d->len = off[e] - off[r];
        a->next = e;
        a->rec = g->first[e];
        a->pos = off[e];
    } else {
        /* A round larger than a frame, split at record boundaries (at least
         * one record per frame: a record is at most 148 bytes, a frame at
         * least LUMO_NET_MIN_PAYLOAD). */
        uint32_t k = a->rec, pos = a->pos, end = g->first[r + 1];
        while (k < end) {
            uint32_t b = record_bytes(area, pos, a->form);
            if ((pos + b - start > a->max_data && k > a->rec) || pos + b > off[r + 1])
                break;
            pos += b, k++;
        }
        if (k == a->rec) {   /* cannot happen in an indexed package (its rounds
                                are checked at open); never loop on it */
            a->next = a->end;
            return 0;
        }
        d->records = k - a->rec;
        d->len = pos - start;
        if (k == end || pos >= off[r + 1]) {   /* this frame ends the round */
            d->count = 1;
            a->next = r + 1;
            a->rec = end;
            a->pos = off[r + 1];
        } else {
            d->count = 0;
            a->rec = k;
            a->pos = pos;
        }
    }
    return 1;
}

/* A frame's end in a PRTV chunk: where max_data bytes from `from` reach,
 * moved back to the last whole cluster or vertex record when that leaves
 * some (the session takes any split: this keeps each frame's records
 * whole for a client that relights as frames come). */
static uint32_t prt_cut(const srv_mesh_index *m, uint32_t from, uint32_t end, uint32_t max_data)
{
    uint32_t cut = end - from > max_data ? from + max_data : end, c;

    if (cut == end)
        return cut;
    if (cut > m->prt_fixed)
        c = m->prt_fixed + (cut - m->prt_fixed) / m->prt_vbytes * m->prt_vbytes;
    else
        c = LUMO_PRT_HEADER_SIZE + (cut - LUMO_PRT_HEADER_SIZE) / m->prt_cbytes * m->prt_cbytes;
    return c > from ? c : cut;
}

/* PRT DATA (§10): first = records = the span's offset, count = its bytes. */
static int next_prt(const srv_pkg *p, srv_answer *a, lumo_net_data *d)
{
    const srv_mesh_index *m = &p->mesh[a->mesh];
    uint32_t e = prt_cut(m, a->next, a->end, a->max_data);

    d->channel = LUMO_NET_PRT;
    d->mesh = a->mesh;
    d->first = d->records = a->next;
    d->count = d->len = e - a->next;
    d->bytes = m->prt + a->next;
    a->next = e;
    return 1;
}

int srv_plan_next(const srv_pkg *p, srv_answer *a, lumo_net_data *d)
{
    if (a->next >= a->end)
        return 0;
    memset(d, 0, sizeof *d);
    if (a->channel == LUMO_NET_PRT)
        return next_prt(p, a, d);
    return a->channel == LUMO_NET_GEOMETRY ? next_geometry(p, a, d) : next_lighting(p, a, d);
}
