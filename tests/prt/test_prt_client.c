/* test_prt_client.c — the fixed-point PRT client (lumo/prt.h) against
 * double references from the server (seed 003 §3.2, Eq. 7; docs/prt.md):
 * its constant tables equal the server's formulas, SH evaluation, rotation
 * (against the quadrature rotation, and round trips), the PRTV chunk
 * (writer to reader, hostile headers), and shading of a real transfer
 * against the same sum in double within the bound docs/prt.md states. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "common/rng.h"
#include "lumo/prt.h"
#include "lumo/wire.h"
#include "../../sdk/src/prt_internal.h"
#include "prt/cpca.h"
#include "prt/prt_pack.h"
#include "prt/sh.h"
#include "prt/transfer.h"
#include "scene/shapes.h"

static double frand(srv_rng *r) { return srv_rng_u32(r) / 4294967296.0; }

static void rand_dir(srv_rng *r, double d[3], lumo_q1_14 q[3])
{
    double z = 1 - 2 * frand(r), ph = 2 * M_PI * frand(r), s = sqrt(1 - z * z);
    int32_t v[3] = {(int32_t)lrint(s * cos(ph) * 1e6), (int32_t)lrint(s * sin(ph) * 1e6), (int32_t)lrint(z * 1e6)};
    assert_int_equal(lumo_normalize3_q14(v, q), LUMO_OK);
    for (int a = 0; a < 3; a++)
        d[a] = q[a] / 16384.0;   /* the reference sees the very direction the client does */
}

static void test_tables(void **state)
{
    (void)state;
    double rot[9] = {1, 0, 0, 0, 0, -1, 0, 1, 0}, M[36 * 36];
    srv_sh_rotation(6, rot, M);
    size_t off = 0;
    for (int l = 0; l < 6; l++) {
        int n = 2 * l + 1;
        for (int a = 0; a < n; a++)
            for (int b = 0; b < n; b++) {
                double want = M[(l * l + a) * 36 + l * l + b] * 1073741824.0;
                assert_true(fabs(lumo_prt_rx90[off + (size_t)(a * n + b)] - want) <= 1.0);
            }
        off += (size_t)(n * n);
    }
    assert_int_equal(off, 286);
    for (int l = 0; l < 6; l++)   /* K from y at the pole and on the equator */
        for (int m = 0; m <= l; m++) {
            double k = sqrt((2 * l + 1) / (4 * M_PI) * tgamma(l - m + 1) / tgamma(l + m + 1)) * (m ? M_SQRT2 : 1);
            assert_true(fabs(lumo_prt_sh_k[l * (l + 1) / 2 + m] - k * 1073741824.0) <= 1.0);
        }
}

/* lumo_prt_sh_eval vs srv_sh_eval: the bound lumo/prt.h states. */
static void test_sh_eval(void **state)
{
    (void)state;
    srv_rng r;
    srv_rng_seed(&r, 5, 0);
    double worst = 0;
    for (int t = 0; t < 20000; t++) {
        double d[3], y[36];
        lumo_q1_14 q[3];
        int32_t yq[36];
        rand_dir(&r, d, q);
        srv_sh_eval(6, d, y);
        lumo_prt_sh_eval(6, q, yq);
        for (int i = 0; i < 36; i++)
            worst = fmax(worst, fabs(yq[i] / 1073741824.0 - y[i]));
    }
    print_message("SH eval: worst error %.2e\n", worst);
    assert_true(worst < 1e-3);
}

static void euler(double a, double b, double g, double R[9])
{
    double rz1[9] = {cos(a), -sin(a), 0, sin(a), cos(a), 0, 0, 0, 1};
    double ry[9] = {cos(b), 0, sin(b), 0, 1, 0, -sin(b), 0, cos(b)};
    double rz2[9] = {cos(g), -sin(g), 0, sin(g), cos(g), 0, 0, 0, 1}, t[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            t[3 * i + j] = 0;
            for (int k = 0; k < 3; k++)
                t[3 * i + j] += ry[3 * i + k] * rz1[3 * k + j];
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            R[3 * i + j] = 0;
            for (int k = 0; k < 3; k++)
                R[3 * i + j] += rz2[3 * i + k] * t[3 * k + j];
        }
}

static void cs(double a, lumo_q1_14 out[2])
{
    out[0] = (lumo_q1_14)lrint(cos(a) * 16384), out[1] = (lumo_q1_14)lrint(sin(a) * 16384);
}

/* Random lighting, random turns: fixed point vs the quadrature rotation of
 * the angles the Q1.14 pairs stand for; then the way back. */
static void test_rotate(void **state)
{
    (void)state;
    srv_rng r;
    srv_rng_seed(&r, 9, 0);
    double worst = 0, worst_trip = 0;
    for (int t = 0; t < 200; t++) {
        lumo_prt_light in, out, back;
        lumo_prt_light_clear(&in, 6);
        for (int c = 0; c < 3; c++)
            for (int i = 0; i < 36; i++)
                in.c[c][i] = (lumo_q16_16)lrint((frand(&r) * 2 - 1) * 4 * 65536);
        lumo_q1_14 qa[2], qb[2], qg[2], na[2], nb[2], ng[2];
        cs(2 * M_PI * frand(&r), qa), cs(M_PI * frand(&r), qb), cs(2 * M_PI * frand(&r), qg);
        double a = atan2(qa[1], qa[0]), b = atan2(qb[1], qb[0]), g = atan2(qg[1], qg[0]), R[9], M[36 * 36];
        euler(a, b, g, R);
        srv_sh_rotation(6, R, M);
        assert_int_equal(lumo_prt_light_rotate(&in, qa, qb, qg, &out), LUMO_OK);
        for (int c = 0; c < 3; c++)
            for (int i = 0; i < 36; i++) {
                double s = 0;
                for (int j = 0; j < 36; j++)
                    s += M[36 * i + j] * in.c[c][j] / 65536.0;
                worst = fmax(worst, fabs(out.c[c][i] / 65536.0 - s));
            }
        na[0] = qg[0], na[1] = (lumo_q1_14)-qg[1], nb[0] = qb[0], nb[1] = (lumo_q1_14)-qb[1];
        ng[0] = qa[0], ng[1] = (lumo_q1_14)-qa[1];
        assert_int_equal(lumo_prt_light_rotate(&out, na, nb, ng, &back), LUMO_OK);
        for (int c = 0; c < 3; c++)
            for (int i = 0; i < 36; i++)
                worst_trip = fmax(worst_trip, fabs((double)back.c[c][i] - in.c[c][i]) / 65536.0);
    }
    print_message("rotation: worst error %.2e, round trip %.2e (coefficients up to 4)\n", worst, worst_trip);
    assert_true(worst < 5e-5 && worst_trip < 1e-4);   /* docs/prt.md */
    lumo_prt_light in, out;
    lumo_prt_light_clear(&in, 3);
    lumo_q1_14 bad[2] = {8000, 0}, one[2] = {16384, 0};
    assert_int_equal(lumo_prt_light_rotate(&in, bad, one, one, &out), LUMO_ERR_RANGE);
    assert_int_equal(lumo_prt_light_rotate(&in, one, one, one, &in), LUMO_ERR_ARG);
}

/* The scene's lights as distant lights: a point light against the double
 * formula E = power / (4 pi r^2) from its direction; a spot that misses the
 * centre adds nothing; a light at the centre is refused. */
static void test_light_pkg(void **state)
{
    (void)state;
    srv_rng r;
    srv_rng_seed(&r, 3, 0);
    double worst = 0;
    for (int t = 0; t < 300; t++) {
        lumo_prt_light l, ref;
        lumo_pkg_light pl;
        lumo_q16_16 c[3];
        double d[3], r2 = 0, p = 5 + 200 * frand(&r), scale = t % 3 == 0 ? 1000 : t % 3 == 1 ? 10 : 0.5;
        memset(&pl, 0, sizeof pl);
        pl.kind = LUMO_LIGHT_POINT;
        for (int a = 0; a < 3; a++) {
            c[a] = (lumo_q16_16)lrint((frand(&r) - 0.5) * 4 * 65536);
            pl.pos[a] = c[a] + (lumo_q16_16)lrint((frand(&r) - 0.5) * 2 * scale * 65536);
            d[a] = (pl.pos[a] - c[a]) / 65536.0;
            r2 += d[a] * d[a];
            pl.power[a] = (lumo_uq16_16)lrint(p * 65536);
        }
        lumo_prt_light_clear(&l, 4);
        assert_int_equal(lumo_prt_light_add_pkg(&l, &pl, c), LUMO_OK);
        /* reference: the client's own directional path at the exact irradiance */
        int32_t v[3] = {pl.pos[0] - c[0], pl.pos[1] - c[1], pl.pos[2] - c[2]};
        lumo_q1_14 q[3];
        double e = fmin(p / (4 * M_PI * r2), 65535.0);
        lumo_uq16_16 ef[3] = {(lumo_uq16_16)lrint(e * 65536), (lumo_uq16_16)lrint(e * 65536), (lumo_uq16_16)lrint(e * 65536)};
        lumo_normalize3_q14(v, q);
        lumo_prt_light_clear(&ref, 4);
        lumo_prt_light_add_directional(&ref, q, ef);
        for (int i = 0; i < 16; i++)
            worst = fmax(worst, fabs((double)l.c[0][i] - ref.c[0][i]) / 65536.0 / (e + 1.0 / 65536));
    }
    print_message("point light as a distant light: worst error %.2e of (E + 1 ulp)\n", worst);
    assert_true(worst < 1e-3);   /* E's own Q16.16 rounding and 4 pi's */
    lumo_prt_light l;
    lumo_pkg_light spot = {.kind = LUMO_LIGHT_SPOT, .pos = {0, 10 * 65536, 0}, .dir = {0, 16384, 0},
                           .cos_half = 14189, .power = {65536, 65536, 65536}};
    lumo_q16_16 c[3] = {0, 0, 0};
    lumo_prt_light_clear(&l, 3);
    assert_int_equal(lumo_prt_light_add_pkg(&l, &spot, c), LUMO_OK);   /* points away from the centre */
    assert_true(l.c[0][0] == 0);
    spot.dir[1] = -16384;
    assert_int_equal(lumo_prt_light_add_pkg(&l, &spot, c), LUMO_OK);
    assert_true(l.c[0][0] > 0);
    spot.pos[1] = 0;
    assert_int_equal(lumo_prt_light_add_pkg(&l, &spot, c), LUMO_ERR_RANGE);
}

/* A sphere's shadowed transfer, clustered and written as PRTV. */
typedef struct {
    srv_scene s;
    srv_prt_mesh m;
    double *t;
    srv_cpca c;
    uint8_t *chunk;
    size_t len;
} fixture;

static void make_fixture(fixture *f, int order, int k, int npc)
{
    srv_scene_init(&f->s);
    assert_int_equal(srv_add_sphere(&f->s, "ball", v3(0, 0, 0), 1.0f, 32, v3(0.5f, 0.5f, 0.5f), 0), LUMO_OK);
    assert_int_equal(srv_add_box(&f->s, "block", v3(-0.3f, -0.3f, 0.9f), v3(0.3f, 0.3f, 1.5f), v3(0.5f, 0.5f, 0.5f), 0),
                     LUMO_OK);
    /* one mesh of both, so the block shadows the ball */
    srv_mesh *a = &f->s.meshes[0], *b = &f->s.meshes[1];
    uint32_t nv = a->nverts + b->nverts, nt = a->ntris + b->ntris;
    float *xyz = malloc(3u * nv * sizeof *xyz);
    uint32_t *tris = malloc(3u * nt * sizeof *tris);
    memcpy(xyz, a->pos, 3u * a->nverts * sizeof *xyz);
    memcpy(xyz + 3 * a->nverts, b->pos, 3u * b->nverts * sizeof *xyz);
    memcpy(tris, a->tris, 3u * a->ntris * sizeof *tris);
    for (uint32_t i = 0; i < 3 * b->ntris; i++)
        tris[3 * a->ntris + i] = b->tris[i] + a->nverts;
    f->m = (srv_prt_mesh){.nverts = nv, .ntris = nt, .xyz = xyz, .tris = tris};
    srv_prt_transfer_opts o;
    srv_prt_transfer_default_opts(&o);
    o.order = order, o.strata = 24, o.bounces = 1, o.threads = 2;
    int nc = order * order;
    char err[128];
    f->t = malloc((size_t)nv * (size_t)nc * sizeof *f->t);
    assert_int_equal(srv_prt_transfer(&f->m, &o, f->t, err, sizeof err), LUMO_OK);
    srv_cpca_opts co;
    srv_cpca_default_opts(&co);
    co.clusters = k, co.components = npc, co.alpha = 0.05;
    assert_int_equal(srv_cpca_build(f->t, nv, nc, xyz, &co, &f->c), LUMO_OK);
    assert_int_equal(srv_prt_encode(&f->c, order, NULL, &f->chunk, &f->len), LUMO_OK);
}

static void free_fixture(fixture *f)
{
    free((void *)f->m.xyz);
    free((void *)f->m.tris);
    free(f->t);
    free(f->chunk);
    srv_cpca_free(&f->c);
    srv_scene_free(&f->s);
}

static void test_chunk(void **state)
{
    (void)state;
    fixture f;
    lumo_prt p;
    make_fixture(&f, 4, 12, 4);
    assert_int_equal(lumo_prt_parse(&p, f.chunk, f.len), LUMO_OK);
    assert_int_equal(p.order, 4);
    assert_int_equal(p.components, 4);
    assert_int_equal(p.clusters, 12);
    assert_int_equal(p.vertices_held, f.m.nverts);
    uint32_t pass[12], np = srv_cpca_superclusters(&f.c, f.m.tris, f.m.ntris, 3, pass);
    uint8_t *sc;
    size_t sl;
    assert_int_equal(srv_prt_encode(&f.c, 4, pass, &sc, &sl), LUMO_OK);
    assert_int_equal(lumo_prt_parse(&p, sc, sl), LUMO_OK);
    for (uint32_t k = 0; k < 12; k++)
        assert_true(lumo_prt_pass(&p, k) == pass[k] && pass[k] < np);
    free(sc);
    assert_int_equal(lumo_prt_parse(&p, f.chunk, f.len), LUMO_OK);
    double qe = srv_prt_quant_sq_error(&f.c, f.chunk, f.len), se = srv_cpca_sq_error(&f.c, f.t);
    print_message("PRTV %zu bytes; squared error CPCA %.3e, Q1.14 quantization %.3e\n", f.len, se, qe);
    assert_true(qe < 1e-7);
    /* a prefix holds fewer vertices; a cut inside the clusters is truncated */
    size_t head = LUMO_PRT_HEADER_SIZE + 12 * (lumo_prt_cluster_bytes(4, 4) + 2);
    assert_int_equal(lumo_prt_parse(&p, f.chunk, head + 10 * lumo_prt_vertex_bytes(4) + 3), LUMO_OK);
    assert_int_equal(p.vertices_held, 10);
    assert_int_equal(lumo_prt_parse(&p, f.chunk, head - 1), LUMO_ERR_TRUNCATED);
    assert_int_equal(lumo_prt_parse(&p, f.chunk, 5), LUMO_ERR_TRUNCATED);
    uint8_t *b = malloc(f.len + 8);
    memcpy(b, f.chunk, f.len);
    assert_int_equal(lumo_prt_parse(&p, b, f.len + 1), LUMO_ERR_CORRUPT);   /* trailing byte */
    b[0] = 2;
    assert_int_equal(lumo_prt_parse(&p, b, f.len), LUMO_ERR_VERSION);
    b[0] = 1, b[1] = 7;
    assert_int_equal(lumo_prt_parse(&p, b, f.len), LUMO_ERR_RANGE);
    b[1] = 4, b[2] = LUMO_PRT_MAX_COMPONENTS + 1;
    assert_int_equal(lumo_prt_parse(&p, b, f.len), LUMO_ERR_LIMIT);
    b[2] = 4;
    lumo_wire_put_le16(b + head - 2, 12);   /* the last cluster's pass: 12 of 12 */
    assert_int_equal(lumo_prt_parse(&p, b, f.len), LUMO_ERR_RANGE);
    lumo_wire_put_le16(b + head - 2, 11);
    assert_int_equal(lumo_prt_parse(&p, b, f.len), LUMO_OK);
    assert_int_equal(lumo_prt_pass(&p, 11), 11);
    assert_int_equal(lumo_prt_pass(&p, 3), 3);   /* no selection: one pass per cluster */
    lumo_wire_put_le16(b + head + 5 * lumo_prt_vertex_bytes(4), 12);   /* cluster 12 of 12 */
    p.order = 99;
    assert_int_equal(lumo_prt_parse(&p, b, f.len), LUMO_ERR_RANGE);
    assert_int_equal(p.order, 99);   /* all-or-nothing */
    free(b);
    free_fixture(&f);
}

/* Shading: the client's fixed point against the same Eq. 7 in double
 * (the Q1.14 chunk's own rounding included: the reference uses the
 * unquantized CPCA). */
static void test_shade(void **state)
{
    (void)state;
    fixture f;
    lumo_prt p;
    make_fixture(&f, 6, 16, 8);
    assert_int_equal(lumo_prt_parse(&p, f.chunk, f.len), LUMO_OK);
    lumo_prt_light L;
    lumo_prt_light_clear(&L, 6);
    double dl[3][2][3] = {{{0.3, -0.5, 0.81}, {3.0, 2.5, 2.0}}, {{-0.8, 0.1, -0.2}, {0.5, 0.7, 1.2}}, {{0, 1, 0}, {1, 1, 1}}};
    double Ld[3][36] = {{0}};
    for (int i = 0; i < 3; i++) {
        double n = sqrt(dl[i][0][0] * dl[i][0][0] + dl[i][0][1] * dl[i][0][1] + dl[i][0][2] * dl[i][0][2]), d[3], y[36];
        int32_t v[3];
        lumo_q1_14 q[3];
        lumo_uq16_16 e[3];
        for (int a = 0; a < 3; a++)
            v[a] = (int32_t)lrint(dl[i][0][a] / n * 1e6), e[a] = (lumo_uq16_16)lrint(dl[i][1][a] * 65536);
        lumo_normalize3_q14(v, q);
        for (int a = 0; a < 3; a++)
            d[a] = q[a] / 16384.0;
        srv_sh_eval(6, d, y);
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 36; k++)
                Ld[c][k] += dl[i][1][c] * y[k];
        assert_int_equal(lumo_prt_light_add_directional(&L, q, e), LUMO_OK);
    }
    lumo_q16_16 *frame = malloc(lumo_prt_frame_entries(&p) * sizeof *frame);
    lumo_uq16_16 *lit = malloc(6u * p.vertices_held * sizeof *lit);
    assert_int_equal(lumo_prt_frame(&p, &L, frame), LUMO_OK);
    assert_int_equal(lumo_prt_shade(&p, frame, NULL, 0, p.vertices_held, lit), LUMO_OK);
    double worst = 0, peak = 0, r[36];
    for (uint32_t v = 0; v < p.vertices_held; v++) {
        srv_cpca_reconstruct(&f.c, v, r);
        for (int c = 0; c < 3; c++) {
            double s = 0;
            for (int k = 0; k < 36; k++)
                s += r[k] * Ld[c][k];
            s = fmax(s, 0.0);
            peak = fmax(peak, s);
            worst = fmax(worst, fabs(lit[6 * v + (uint32_t)c] / 65536.0 - s));
            assert_true(lit[6 * v + 3 + (uint32_t)c] == 0);
        }
    }
    print_message("shading: worst |fixed - double| %.2e W/m^2/sr (peak %.3f)\n", worst, peak);
    assert_true(worst < 1e-3);   /* docs/prt.md: Q16.16 light and frame, 36 terms */
    lumo_prt_light L4;
    lumo_prt_light_clear(&L4, 4);
    assert_int_equal(lumo_prt_frame(&p, &L4, frame), LUMO_ERR_RANGE);
    assert_int_equal(lumo_prt_shade(&p, frame, NULL, 1, p.vertices_held, lit), LUMO_ERR_RANGE);
    free(frame);
    free(lit);
    free_fixture(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tables), cmocka_unit_test(test_sh_eval), cmocka_unit_test(test_rotate),
        cmocka_unit_test(test_chunk),  cmocka_unit_test(test_shade),  cmocka_unit_test(test_light_pkg),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
