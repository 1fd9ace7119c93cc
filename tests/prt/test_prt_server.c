/* test_prt_server.c — PRT on the server against known answers (seed 003
 * §3.1, §4.2-4.3; docs/prt.md): SH projection of a constant and a clamped
 * cosine, orthonormality, rotation (a turned function's projection, round
 * trips), an unoccluded convex object's transfer equals the clamped cosine's
 * projection about its normal, CPCA with alpha = 0 equals plain LBG, null
 * clusters, PCA, super-clusters and overdraw (Eq. 8). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "common/rng.h"
#include "prt/cpca.h"
#include "prt/prt_pack.h"
#include "prt/sh.h"
#include "prt/transfer.h"
#include "scene/shapes.h"

static double fn_const(void *ctx, const double d[3]) { (void)ctx, (void)d; return 1.0; }
static double fn_cos(void *ctx, const double d[3]) { (void)ctx; return d[2] > 0 ? d[2] : 0.0; }
static double fn_basis(void *ctx, const double d[3])
{
    double y[SRV_SH_MAX_COEFFS];
    srv_sh_eval(6, d, y);
    return y[*(int *)ctx];
}

static void test_project_constant(void **state)
{
    (void)state;
    double c[36];
    srv_sh_project(6, fn_const, NULL, 16, 32, c);
    assert_true(fabs(c[0] - 2.0 * sqrt(M_PI)) < 1e-12);   /* 4 pi y_0, y_0 = 1 / (2 sqrt(pi)) */
    for (int i = 1; i < 36; i++)
        assert_true(fabs(c[i]) < 1e-12);
}

/* Closed forms of the clamped cosine's zonal coefficients. */
static const double k_cos_zonal[6] = {0.886226925452758 /* sqrt(pi)/2 */, 1.023326707946489 /* sqrt(pi/3) */,
                                      0.495415912200751 /* sqrt(5 pi)/8 */, 0.0,
                                      -0.110778365681595 /* -sqrt(pi)/16 */, 0.0};

static void test_project_clamped_cosine(void **state)
{
    (void)state;
    double c[36];
    for (int l = 0; l < 6; l++)
        assert_true(fabs(srv_sh_clamped_cosine_zonal(l) - k_cos_zonal[l]) < 1e-12);
    srv_sh_project(6, fn_cos, NULL, 64, 64, c);   /* the kink at z = 0 limits the rule */
    for (int l = 0; l < 6; l++)
        for (int m = -l; m <= l; m++)
            assert_true(fabs(c[l * (l + 1) + m] - (m == 0 ? k_cos_zonal[l] : 0.0)) < 2e-3);
}

static void test_orthonormal(void **state)
{
    (void)state;
    double c[36];
    for (int i = 0; i < 36; i++) {
        srv_sh_project(6, fn_basis, &i, 12, 24, c);
        for (int j = 0; j < 36; j++)
            assert_true(fabs(c[j] - (i == j)) < 1e-12);
    }
}

static void rot_axis_angle(const double ax[3], double a, double r[9])
{
    double c = cos(a), s = sin(a), t = 1 - c, x = ax[0], y = ax[1], z = ax[2];
    double m[9] = {t * x * x + c, t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
                   t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
    memcpy(r, m, sizeof m);
}

typedef struct { const double *rot; } turned;
/* The clamped cosine turned by rot: f(rot^T d). */
static double fn_cos_turned(void *ctx, const double d[3])
{
    const double *r = ((turned *)ctx)->rot;
    double z = r[2] * d[0] + r[5] * d[1] + r[8] * d[2];
    return z > 0 ? z : 0.0;
}

static void test_rotation(void **state)
{
    (void)state;
    double ax[3] = {0.36, -0.48, 0.8}, rot[9], inv[9], R[36 * 36], Ri[36 * 36];
    double c[36], rc[36], want[36];
    rot_axis_angle(ax, 1.1, rot);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            inv[3 * i + j] = rot[3 * j + i];
    srv_sh_rotation(6, rot, R);
    srv_sh_rotation(6, inv, Ri);
    srv_sh_project(6, fn_cos, NULL, 64, 64, c);
    turned t = {rot};
    srv_sh_project(6, fn_cos_turned, &t, 64, 64, want);
    for (int i = 0; i < 36; i++) {
        rc[i] = 0;
        for (int j = 0; j < 36; j++)
            rc[i] += R[36 * i + j] * c[j];
        assert_true(fabs(rc[i] - want[i]) < 4e-3);
    }
    for (int i = 0; i < 36; i++)   /* round trip: Ri R = I */
        for (int j = 0; j < 36; j++) {
            double s = 0;
            for (int k = 0; k < 36; k++)
                s += Ri[36 * i + k] * R[36 * k + j];
            assert_true(fabs(s - (i == j)) < 1e-10);
        }
}

/* The equirectangular projection (y up): a constant sky gives 2 sqrt(pi)
 * times its radiance in coefficient 0 and nothing else; a sky lit above
 * the horizon only gives sqrt(pi) in coefficient 0 and, on y_1^-1 (the y
 * axis), sqrt(3 pi) / 2, zero on the other band-1 terms. */
static void test_env_project(void **state)
{
    (void)state;
    enum { W = 512, H = 256 };
    float *img = malloc(3u * W * H * sizeof *img);
    double c[3 * 36];
    for (int i = 0; i < 3 * W * H; i++)
        img[i] = 0.5f;
    srv_prt_env_project(img, W, H, 6, c);
    for (int ch = 0; ch < 3; ch++)
        for (int i = 0; i < 36; i++)
            assert_true(fabs(c[ch * 36 + i] - (i == 0 ? 0.5 * 2.0 * sqrt(M_PI) : 0.0)) < 2e-4);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < 3 * W; x++)
            img[3 * W * y + x] = y < H / 2 ? 1.0f : 0.0f;
    srv_prt_env_project(img, W, H, 6, c);
    assert_true(fabs(c[0] - sqrt(M_PI)) < 1e-4);
    assert_true(fabs(c[1] - sqrt(3 * M_PI) / 2) < 1e-3);
    assert_true(fabs(c[2]) < 1e-9 && fabs(c[3]) < 1e-9);
    uint8_t *chunk;
    size_t len;
    assert_int_equal(srv_prt_encode_light(c, 6, &chunk, &len), LUMO_OK);
    assert_int_equal(len, 4 + 12 * 36);
    assert_int_equal(chunk[0], 6);
    free(chunk);
    c[5] = 1e9;
    assert_int_equal(srv_prt_encode_light(c, 6, &chunk, &len), LUMO_ERR_RANGE);
    free(img);
}

/* A UV sphere from the scene builder, as float arrays. */
typedef struct { srv_scene s; srv_prt_mesh m; } sphere;

static void make_sphere(sphere *sp, int segments)
{
    srv_scene_init(&sp->s);
    assert_int_equal(srv_add_sphere(&sp->s, "ball", v3(0.5f, 1.0f, -0.25f), 0.7f, segments, v3(0.5f, 0.5f, 0.5f), 0),
                     LUMO_OK);
    srv_mesh *m = &sp->s.meshes[0];
    sp->m = (srv_prt_mesh){.nverts = m->nverts, .ntris = m->ntris, .xyz = &m->pos[0].x, .tris = m->tris};
}

static void test_convex_transfer(void **state)
{
    (void)state;
    sphere sp;
    make_sphere(&sp, 32);
    srv_prt_transfer_opts o;
    srv_prt_transfer_default_opts(&o);
    o.strata = 64, o.bounces = 1, o.threads = 2;
    double *t = malloc((size_t)sp.m.nverts * 36 * sizeof *t), err = 0;
    float *n = malloc(3u * sp.m.nverts * sizeof *n);
    char msg[128];
    assert_int_equal(srv_prt_transfer(&sp.m, &o, t, msg, sizeof msg), LUMO_OK);
    srv_prt_vertex_normals(&sp.m, n);
    for (uint32_t v = 0; v < sp.m.nverts; v++) {
        double y[36], nd[3] = {n[3 * v], n[3 * v + 1], n[3 * v + 2]};
        srv_sh_eval(6, nd, y);
        for (int l = 0; l < 6; l++)
            for (int m = -l; m <= l; m++) {   /* (1/pi) sqrt(4 pi / (2l+1)) z_l y_lm(n) */
                int i = l * (l + 1) + m;
                double want = sqrt(4.0 * M_PI / (2 * l + 1)) * k_cos_zonal[l] * y[i] / M_PI;
                err = fmax(err, fabs(t[(size_t)v * 36 + (size_t)i] - want));
            }
    }
    print_message("convex sphere: worst transfer coefficient error %.2e (c0 = %.3f)\n", err, k_cos_zonal[0] / sqrt(M_PI));
    assert_true(err < 6e-3);
    free(t);
    free(n);
    srv_scene_free(&sp.s);
}

/* Inside a closed sphere every direction is blocked: the shadowed transfer is
 * zero and one bounce brings some light back. */
static void test_enclosed_transfer(void **state)
{
    (void)state;
    srv_scene s;
    srv_scene_init(&s);
    assert_int_equal(srv_add_sphere(&s, "room", v3(0, 0, 0), 1.0f, 24, v3(0.5f, 0.5f, 0.5f), 1), LUMO_OK);
    srv_mesh *m = &s.meshes[0];
    srv_prt_mesh pm = {.nverts = m->nverts, .ntris = m->ntris, .xyz = &m->pos[0].x, .tris = m->tris};
    srv_prt_transfer_opts o;
    srv_prt_transfer_default_opts(&o);
    o.order = 4, o.strata = 16;
    double *t = malloc((size_t)pm.nverts * 16 * sizeof *t);
    char msg[128];
    assert_int_equal(srv_prt_transfer(&pm, &o, t, msg, sizeof msg), LUMO_OK);
    for (size_t i = 0; i < (size_t)pm.nverts * 16; i++)
        assert_true(t[i] == 0.0);
    o.bounces = 1;
    assert_int_equal(srv_prt_transfer(&pm, &o, t, msg, sizeof msg), LUMO_OK);
    for (size_t i = 0; i < (size_t)pm.nverts * 16; i++)   /* bounce 0 is zero, so bounce 1 is */
        assert_true(t[i] == 0.0);
    o.order = 9;
    assert_int_equal(srv_prt_transfer(&pm, &o, t, msg, sizeof msg), LUMO_ERR_ARG);
    free(t);
    srv_scene_free(&s);
}

/* Blobs in 6-D around random centres. */
static double *blobs(uint32_t n, int dim, int nb, uint64_t seed, float *pos)
{
    double *x = malloc((size_t)n * (size_t)dim * sizeof *x), cent[16][8];
    srv_rng r;
    srv_rng_seed(&r, seed, 7);
    for (int b = 0; b < nb; b++)
        for (int d = 0; d < dim; d++)
            cent[b][d] = srv_rng_u32(&r) / 4294967296.0 * 10.0;
    for (uint32_t i = 0; i < n; i++)
        for (int d = 0; d < dim; d++)
            x[i * (uint32_t)dim + (uint32_t)d] = cent[i % (uint32_t)nb][d] + srv_rng_u32(&r) / 4294967296.0 - 0.5;
    for (uint32_t i = 0; pos && i < 3 * n; i++)
        pos[i] = (float)(srv_rng_u32(&r) / 4294967296.0);
    return x;
}

/* Plain LBG (Fig. 3.2) written out here: same start, nearest mean, mean
 * update, Eq. 5's stop. *empty is set when a cluster went empty. */
static void plain_lbg(const double *x, uint32_t n, int dim, int k, uint64_t seed, uint32_t *lab, int *empty)
{
    double *mean = malloc((size_t)k * (size_t)dim * sizeof *mean), prev = INFINITY;
    srv_cpca_init_means(x, n, dim, k, seed, mean);
    *empty = 0;
    for (int it = 0; it < 100; it++) {
        for (uint32_t i = 0; i < n; i++) {
            double best = INFINITY;
            for (int c = 0; c < k; c++) {
                double s = 0;
                for (int d = 0; d < dim; d++)
                    s += pow(x[i * (uint32_t)dim + (uint32_t)d] - mean[c * dim + d], 2);
                if (s < best)
                    best = s, lab[i] = (uint32_t)c;
            }
        }
        double e = 0, cnt[16] = {0};
        memset(mean, 0, (size_t)k * (size_t)dim * sizeof *mean);
        for (uint32_t i = 0; i < n; i++) {
            cnt[lab[i]]++;
            for (int d = 0; d < dim; d++)
                mean[lab[i] * (uint32_t)dim + (uint32_t)d] += x[i * (uint32_t)dim + (uint32_t)d];
        }
        for (int c = 0; c < k; c++) {
            *empty |= cnt[c] == 0;
            for (int d = 0; d < dim && cnt[c]; d++)
                mean[c * dim + d] /= cnt[c];
        }
        for (uint32_t i = 0; i < n; i++)
            for (int d = 0; d < dim; d++)
                e += pow(x[i * (uint32_t)dim + (uint32_t)d] - mean[lab[i] * (uint32_t)dim + (uint32_t)d], 2);
        if (e == 0.0 || (prev - e) / prev < 1e-4)
            break;
        prev = e;
    }
    free(mean);
}

static void test_alpha0_is_lbg(void **state)
{
    (void)state;
    uint32_t n = 600, lab[600];
    int tried = 0;
    for (uint64_t seed = 1; seed < 200 && tried < 8; seed++) {
        double *x = blobs(n, 6, 5, seed, NULL);
        int empty;
        plain_lbg(x, n, 6, 5, seed, lab, &empty);
        if (empty) {   /* the reference has no null-cluster handling */
            free(x);
            continue;
        }
        srv_cpca_opts o;
        srv_cpca c;
        srv_cpca_default_opts(&o);
        o.clusters = 5, o.components = 2, o.seed = seed, o.threads = 2;
        assert_int_equal(srv_cpca_build(x, n, 6, NULL, &o, &c), LUMO_OK);
        assert_memory_equal(c.cluster, lab, sizeof lab);
        srv_cpca_free(&c);
        free(x);
        tried++;
    }
    assert_true(tried >= 5);
}

static void test_null_clusters_and_pca(void **state)
{
    (void)state;
    uint32_t n = 500;
    double *x = blobs(n, 6, 3, 11, NULL);
    srv_cpca_opts o;
    srv_cpca c;
    srv_cpca_default_opts(&o);
    o.clusters = 40, o.components = 6;   /* far more clusters than blobs: nulls happen */
    assert_int_equal(srv_cpca_build(x, n, 6, NULL, &o, &c), LUMO_OK);
    for (int k = 0; k < 40; k++)
        assert_true(c.count[k] > 0);
    assert_true(srv_cpca_sq_error(&c, x) < 1e-20);   /* all components: exact */
    srv_cpca_free(&c);
    o.components = 0;   /* no component: the error is the clusters' variance */
    assert_int_equal(srv_cpca_build(x, n, 6, NULL, &o, &c), LUMO_OK);
    double e = srv_cpca_sq_error(&c, x);
    assert_true(e > 0.0 && e < 0.5);
    srv_cpca_free(&c);
    o.clusters = 501;
    assert_int_equal(srv_cpca_build(x, n, 6, NULL, &o, &c), LUMO_ERR_ARG);
    o.clusters = 4, o.alpha = 0.1;   /* coherence needs positions */
    assert_int_equal(srv_cpca_build(x, n, 6, NULL, &o, &c), LUMO_ERR_ARG);
    free(x);
}

/* On a sphere whose vectors are drawn at random (no spatial coherence of
 * their own): geometry coherence lowers the overdraw, super-clusters lower
 * it again, one pass for all clusters draws each triangle once. */
static void test_overdraw(void **state)
{
    (void)state;
    sphere sp;
    make_sphere(&sp, 48);
    double *t = blobs(sp.m.nverts, 6, 8, 3, NULL);
    srv_cpca_opts o;
    srv_cpca a, b;
    srv_cpca_default_opts(&o);
    o.clusters = 24, o.components = 4, o.threads = 2;
    assert_int_equal(srv_cpca_build(t, sp.m.nverts, 6, sp.m.xyz, &o, &a), LUMO_OK);
    o.alpha = 10.0;
    assert_int_equal(srv_cpca_build(t, sp.m.nverts, 6, sp.m.xyz, &o, &b), LUMO_OK);
    double oa = srv_cpca_overdraw(&a, sp.m.tris, sp.m.ntris, NULL), ob = srv_cpca_overdraw(&b, sp.m.tris, sp.m.ntris, NULL);
    uint32_t pass[24];
    uint32_t np = srv_cpca_superclusters(&a, sp.m.tris, sp.m.ntris, 3, pass);
    double os = srv_cpca_overdraw(&a, sp.m.tris, sp.m.ntris, pass);
    print_message("sphere overdraw: plain %.4f, coherent %.4f, super-clusters of 3 %.4f (%u passes)\n", oa, ob, os, np);
    assert_true(oa > 1.0 && ob < oa && os < oa);
    assert_int_equal(np, 8);
    assert_int_equal(srv_cpca_superclusters(&a, sp.m.tris, sp.m.ntris, 24, pass), 1);
    assert_true(srv_cpca_overdraw(&a, sp.m.tris, sp.m.ntris, pass) == 1.0);
    assert_int_equal(srv_cpca_per_pass(36, 8, 256), 3);   /* seed 003 §4.3's example */
    srv_cpca_free(&a);
    srv_cpca_free(&b);
    free(t);
    srv_scene_free(&sp.s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_project_constant),     cmocka_unit_test(test_project_clamped_cosine),
        cmocka_unit_test(test_orthonormal),          cmocka_unit_test(test_rotation),
        cmocka_unit_test(test_convex_transfer),      cmocka_unit_test(test_enclosed_transfer),
        cmocka_unit_test(test_alpha0_is_lbg),        cmocka_unit_test(test_null_clusters_and_pca),
        cmocka_unit_test(test_overdraw),             cmocka_unit_test(test_env_project),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
