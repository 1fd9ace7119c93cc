/*
 * tests/serve/test_serve_plan.c — lumo-server's request mapping
 * (server/serve/plan.h) on synthetic streams and round tables, against
 * brute-force references: the batches of a geometry answer (every cursor,
 * every amount), frames that cover the answer exactly with whole records
 * under the max payload and as full as they can be, rounds split at record
 * boundaries only when they do not fit, and the requests refused.
 */
#include <stdlib.h>
#include "test_common.h"
#include "lumo/ivg.h"
#include "lumo/wire.h"
#include "serve/plan.h"

/* Vertices of batches [0, b): the protocol's count, one batch at a time. */
static uint32_t ref_vertices(const lumo_pmesh_header *h, uint32_t b)
{
    uint32_t v = 0, k;
    for (k = 0; k < b; k++)
        v += k == 0 ? h->base_vertices : (h->vertices - v < h->batch_vertices ? h->vertices - v : h->batch_vertices);
    return v;
}

/* docs/protocol.md §2 DATA, geometry, as the client computes it. */
static uint32_t ref_end(const lumo_pmesh_header *h, uint32_t c, uint32_t amount)
{
    uint32_t e = c + 1;
    while (e < h->batch_count && ref_vertices(h, e + 1) - ref_vertices(h, c) <= amount)
        e++;
    return e;
}

static void test_geometry_end_exhaustive(void **state)
{
    srv_mesh_index m;
    uint32_t n, base, bv, c, amount, cases = 0;

    (void)state;
    memset(&m, 0, sizeof m);
    for (n = 1; n <= 40; n++)
        for (base = 1; base <= n; base++)
            for (bv = 1; bv <= 7; bv++) {
                m.h.vertices = n;
                m.h.base_vertices = base;
                m.h.batch_vertices = bv;
                m.h.batch_count = 1 + (n - base + bv - 1) / bv;
                for (c = 0; c < m.h.batch_count; c++) {
                    for (amount = 1; amount <= n + 3; amount++, cases++)
                        assert_int_equal(lumo_net_geometry_end(&m.h, c, amount), ref_end(&m.h, c, amount));
                    assert_int_equal(lumo_net_geometry_end(&m.h, c, 0xffffffffu), m.h.batch_count);
                    assert_int_equal(lumo_net_vertices_before(&m.h, c), ref_vertices(&m.h, c));
                }
            }
    print_message("%u cursor/amount cases\n", cases);
}

/* A package of one synthetic mesh (records of random sizes) and an IVG of
 * random rounds, both in one buffer. */
typedef struct synth {
    srv_pkg  p;
    srv_mesh_index mesh;
    uint8_t *stream, *bundle[2];
    uint32_t rec[401];
} synth;

static void synth_mesh(synth *s, test_rng *r, uint32_t batches)
{
    uint32_t b, at = LUMO_PMESH_HEADER_MIN;  /* any header length */

    memset(&s->mesh, 0, sizeof s->mesh);
    for (b = 0; b < batches; b++) {
        s->rec[b] = at;
        at += 7 + (uint32_t)(test_rng_next(r) % (b % 7 == 3 ? 9000 : 1500));
        if (at - s->rec[b] > s->mesh.max_record)
            s->mesh.max_record = at - s->rec[b];
    }
    s->rec[batches] = at;
    s->stream = calloc(1, at);
    for (b = 0; b < at; b++)
        s->stream[b] = (uint8_t)(b * 31 + 7);
    s->mesh.stream = s->stream;
    s->mesh.len = at;
    s->mesh.rec = s->rec;
    s->mesh.h.vertices = 10 + (batches - 1) * 50 - 20;
    s->mesh.h.base_vertices = 10;
    s->mesh.h.batch_vertices = 50;
    s->mesh.h.batch_count = batches;
    s->p.mesh = &s->mesh;
    s->p.mesh_count = 1;
}

/* Rounds of 1..slices records (round 0: 8), a quarter of them solid; the
 * same records in both forms. */
static void synth_ivg(synth *s, test_rng *r, uint32_t rounds, uint32_t slices)
{
    srv_ivg_index *g = &s->p.ivg;
    uint32_t k, f, rec = 0, nrec;
    uint8_t *solid;

    memset(g, 0, sizeof *g);
    g->present = 1;
    g->rounds = rounds;
    g->first = calloc(rounds + 1, sizeof *g->first);
    for (k = 0; k < rounds; k++) {
        g->first[k] = rec;
        rec += k == 0 ? 8 : 1 + (uint32_t)(test_rng_next(r) % slices);
    }
    g->first[rounds] = nrec = rec;
    g->records = nrec;
    solid = calloc(nrec, 1);
    for (k = 0; k < nrec; k++)
        solid[k] = test_rng_next(r) % 4 == 0;
    for (f = 0; f < 2; f++) {
        uint32_t entry = f == LUMO_IVG_FORM_QUANTIZED ? 46 : 148, pos = SRV_IVG_BUNDLE_HEAD, q = 0;
        s->bundle[f] = calloc(1, SRV_IVG_BUNDLE_HEAD + (size_t)nrec * 148);
        g->off[f] = calloc(rounds + 1, sizeof *g->off[f]);
        for (k = 0; k <= rounds; k++) {
            g->off[f][k] = pos;
            for (; k < rounds && q < g->first[k + 1]; q++) {
                lumo_wire_put_le32(s->bundle[f] + pos, q | (solid[q] ? 0x80000000u : 0));
                pos += solid[q] ? 4 : entry;
            }
        }
        g->bundle[f] = s->bundle[f];
        g->bundle_len[f] = pos;
    }
    free(solid);
}

static void synth_free(synth *s)
{
    free(s->stream);
    free(s->bundle[0]);
    free(s->bundle[1]);
    free(s->p.ivg.first);
    free(s->p.ivg.off[0]);
    free(s->p.ivg.off[1]);
}

static void test_geometry_frames(void **state)
{
    static const uint32_t payloads[] = {4096, 5000, 9100, 16384, 65536};
    test_rng r = {0x5eed};
    synth s;
    uint32_t t;

    (void)state;
    memset(&s, 0, sizeof s);
    synth_mesh(&s, &r, 400);
    for (t = 0; t < 3000; t++) {
        lumo_net_request q = {LUMO_NET_GEOMETRY, 0, 0, 0};
        uint32_t maxp = payloads[t % 5], at, e, frames = 0;
        srv_answer a;
        lumo_net_data d;
        char err[160];
        int end;
        lumo_status st;

        q.cursor = (uint32_t)(test_rng_next(&r) % 401);
        q.amount = 1 + (uint32_t)(test_rng_next(&r) % (t % 2 ? 400 : 20000));
        st = srv_plan_start(&s.p, &q, LUMO_NET_FORM_NONE, maxp, &a, &end, err, sizeof err);
        if (q.cursor == 400) {
            assert_int_equal(st, LUMO_OK);
            assert_true(end);
            continue;
        }
        e = ref_end(&s.mesh.h, q.cursor, q.amount);
        for (at = q.cursor; at < e; at++)
            if (s.rec[at + 1] - s.rec[at] > maxp - LUMO_NET_DATA_HEAD)
                break;
        if (at < e) {   /* a record of the range is larger than a frame */
            assert_int_equal(st, LUMO_ERR_LIMIT);
            continue;
        }
        assert_int_equal(st, LUMO_OK);
        assert_false(end);
        at = q.cursor;
        while (srv_plan_next(&s.p, &a, &d)) {
            assert_int_equal(d.channel, LUMO_NET_GEOMETRY);
            assert_int_equal(d.first, at);
            assert_true(d.count >= 1);
            assert_int_equal(d.records, d.count);
            assert_true(d.first + d.count <= e);
            assert_ptr_equal(d.bytes, s.stream + s.rec[at]);
            assert_int_equal(d.len, s.rec[at + d.count] - s.rec[at]);
            assert_true(d.len <= maxp - LUMO_NET_DATA_HEAD);
            /* as full as it can be: the next record would not fit */
            if (d.first + d.count < e)
                assert_true(s.rec[at + d.count + 1] - s.rec[at] > maxp - LUMO_NET_DATA_HEAD);
            at += d.count;
            frames++;
        }
        assert_int_equal(at, e);
        assert_true(frames >= 1);
    }
    synth_free(&s);
}

static uint32_t rec_bytes(const uint8_t *p, int form)
{
    return lumo_wire_le32(p) & 0x80000000u ? 4 : form == LUMO_IVG_FORM_QUANTIZED ? 46u : 148u;
}

static void test_lighting_frames(void **state)
{
    static const uint32_t payloads[] = {4096, 4200, 8192, 65536};
    test_rng r = {0xfeed};
    synth s;
    uint32_t t, splits = 0;

    (void)state;
    memset(&s, 0, sizeof s);
    synth_ivg(&s, &r, 300, 60);   /* rounds up to 60 x 148 bytes: some larger than a frame */
    for (t = 0; t < 4000; t++) {
        const srv_ivg_index *g = &s.p.ivg;
        lumo_net_request q = {LUMO_NET_LIGHTING, 0, 0, 0};
        uint8_t form = (uint8_t)(t % 2);
        uint32_t maxp = payloads[t % 4], maxd = maxp - LUMO_NET_DATA_HEAD, round, pos, e;
        const uint32_t *off = g->off[form];
        srv_answer a;
        lumo_net_data d;
        char err[160];
        int end;

        q.cursor = (uint32_t)(test_rng_next(&r) % 301);
        q.amount = 1 + (uint32_t)(test_rng_next(&r) % (t % 3 ? 5 : 400));
        assert_int_equal(srv_plan_start(&s.p, &q, form, maxp, &a, &end, err, sizeof err), LUMO_OK);
        if (q.cursor == 300) {
            assert_true(end);
            continue;
        }
        e = q.cursor + q.amount > 300 ? 300 : q.cursor + q.amount;
        round = q.cursor;
        pos = off[round];
        while (srv_plan_next(&s.p, &a, &d)) {
            uint32_t q2 = pos, n = 0;
            assert_int_equal(d.channel, LUMO_NET_LIGHTING);
            assert_int_equal(d.form, form);
            assert_int_equal(d.first, round);
            assert_ptr_equal(d.bytes, s.bundle[form] + pos);
            assert_true(d.len >= 1 && d.len <= maxd);
            while (q2 < pos + d.len)
                q2 += rec_bytes(s.bundle[form] + q2, form), n++;
            assert_int_equal(q2, pos + d.len);   /* whole records */
            assert_int_equal(d.records, n);
            pos += d.len;
            if (d.count == 0) {   /* a split round: only when it does not fit */
                assert_true(off[round + 1] - off[round] > maxd);
                assert_true(pos < off[round + 1]);
                splits++;
            } else {
                assert_true(round + d.count <= e);
                assert_int_equal(pos, off[round + d.count]);
                if (pos - d.len == off[round])   /* whole rounds: all their records */
                    assert_int_equal(d.records, g->first[round + d.count] - g->first[round]);
                /* whole rounds fill the frame: the next round would not fit */
                if (pos - d.len == off[round] && round + d.count < e)
                    assert_true(off[round + d.count + 1] - off[round] > maxd);
                round += d.count;
            }
        }
        assert_int_equal(round, e);
        assert_int_equal(pos, off[e]);
    }
    assert_true(splits > 0);
    print_message("%u frames continued a split round\n", splits);
    synth_free(&s);
}

static void test_refused(void **state)
{
    test_rng r = {7};
    synth s;
    srv_answer a;
    char err[160];
    int end;
    lumo_net_request q;

    (void)state;
    memset(&s, 0, sizeof s);
    synth_mesh(&s, &r, 10);
    q = (lumo_net_request){LUMO_NET_GEOMETRY, 1, 0, 10};
    assert_int_equal(srv_plan_start(&s.p, &q, 0, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);
    q = (lumo_net_request){LUMO_NET_GEOMETRY, 0, 11, 10};
    assert_int_equal(srv_plan_start(&s.p, &q, 0, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);
    q = (lumo_net_request){LUMO_NET_GEOMETRY, 0, 0, 0};
    assert_int_equal(srv_plan_start(&s.p, &q, 0, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);
    q = (lumo_net_request){2, 0, 0, 1};
    assert_int_equal(srv_plan_start(&s.p, &q, 0, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);
    q = (lumo_net_request){LUMO_NET_LIGHTING, 0, 0, 1};   /* no IVG */
    assert_int_equal(srv_plan_start(&s.p, &q, 1, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);
    synth_ivg(&s, &r, 20, 8);
    assert_int_equal(srv_plan_start(&s.p, &q, LUMO_NET_FORM_NONE, 65536, &a, &end, err, sizeof err),
                     LUMO_ERR_RANGE);
    q.cursor = 21;
    assert_int_equal(srv_plan_start(&s.p, &q, 1, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);
    q.cursor = 20;
    assert_int_equal(srv_plan_start(&s.p, &q, 1, 65536, &a, &end, err, sizeof err), LUMO_OK);
    assert_true(end);
    q = (lumo_net_request){LUMO_NET_GEOMETRY, 0, 10, 1};
    assert_int_equal(srv_plan_start(&s.p, &q, 1, 65536, &a, &end, err, sizeof err), LUMO_OK);
    assert_true(end);
    synth_free(&s);
}

/* The ends of whole cluster records (up to the fixed part) and of whole
 * vertex records (from it): where the server prefers to cut. */
static int prt_boundary(const srv_mesh_index *m, uint32_t x)
{
    if (x >= m->prt_fixed)
        return (x - m->prt_fixed) % m->prt_vbytes == 0;
    return (x - 12) % m->prt_cbytes == 0;
}

/* PRT (docs/protocol.md §10) on the committed PRT package: for cursors
 * across the whole chunk, amounts and payloads, the frames cover exactly
 * [C, min(S, F + (H + n) * vb)) as spans (first = records = offset, count
 * = len), each under the payload, cut at a whole cluster or vertex record
 * whenever one lies in the frame; and the requests refused. */
static void test_prt_frames(void **state)
{
    static const uint32_t payloads[] = {4096, 4100, 9000, 65536};
    srv_pkg p;
    char err[200];
    test_rng r = {0x9d7};
    const srv_mesh_index *m;
    uint32_t t, C;
    (void)state;
    assert_int_equal(srv_pkg_open(&p, "tests/fuzz/seeds/fuzz_package/prt.lumo", err, sizeof err), LUMO_OK);
    assert_true(p.has_prt && p.welcome_prt && p.arena_need_prt > p.arena_need);
    m = &p.mesh[6];
    assert_non_null(m->prt);
    for (t = 0; t < 2000; t++) {
        lumo_net_request q = {LUMO_NET_PRT, 6, 0, 0};
        uint32_t maxp = payloads[t % 4], at, held, n = 1 + (uint32_t)(test_rng_next(&r) % 150);
        uint64_t e;
        srv_answer a;
        lumo_net_data d;
        int end;
        C = 12 + (uint32_t)(test_rng_next(&r) % (m->prt_len - 11));
        q.cursor = C, q.amount = n;
        assert_int_equal(srv_plan_start(&p, &q, LUMO_NET_FORM_NONE, maxp, &a, &end, err, sizeof err), LUMO_OK);
        if (C == m->prt_len) {
            assert_true(end);
            continue;
        }
        held = C > m->prt_fixed ? (C - m->prt_fixed) / m->prt_vbytes : 0;
        e = m->prt_fixed + (uint64_t)(held + n) * m->prt_vbytes;
        if (e > m->prt_len)
            e = m->prt_len;
        for (at = C; srv_plan_next(&p, &a, &d);) {
            uint32_t stop = at + d.len;
            assert_int_equal(d.channel, LUMO_NET_PRT);
            assert_int_equal(d.mesh, 6);
            assert_int_equal(d.first, at);
            assert_int_equal(d.records, at);
            assert_int_equal(d.count, d.len);
            assert_true(d.len >= 1 && d.len <= maxp - LUMO_NET_DATA_HEAD);
            assert_ptr_equal(d.bytes, m->prt + at);
            if (stop < e && !prt_boundary(m, stop)) {   /* a cut inside a record: none ends in the frame */
                assert_int_equal(d.len, maxp - LUMO_NET_DATA_HEAD);
                for (uint32_t x = at + 1; x <= stop; x++)
                    assert_false(prt_boundary(m, x));
            }
            at = stop;
        }
        assert_int_equal(at, e);
    }
    lumo_net_request q = {LUMO_NET_PRT, 6, 11, 1};
    srv_answer a;
    int end;
    assert_int_equal(srv_plan_start(&p, &q, 0, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);   /* below the header */
    q.cursor = m->prt_len + 1;
    assert_int_equal(srv_plan_start(&p, &q, 0, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);
    q = (lumo_net_request){LUMO_NET_PRT, 7, 12, 1};   /* no mesh 7 */
    assert_int_equal(srv_plan_start(&p, &q, 0, 65536, &a, &end, err, sizeof err), LUMO_ERR_RANGE);
    srv_pkg_close(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_geometry_end_exhaustive),
        cmocka_unit_test(test_geometry_frames),
        cmocka_unit_test(test_lighting_frames),
        cmocka_unit_test(test_refused),
        cmocka_unit_test(test_prt_frames),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
