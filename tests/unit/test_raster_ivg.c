/*
 * test_raster_ivg.c — indirect light from a real lumo_ivg through the soft
 * rasterizer: a synthetic grid written by the server's bundle writer
 * (quantized wire form), decoded by the client, drawn per pixel on tilted
 * planes, against a double implementation of seed 000 §3.2 over the
 * dequantized entries; plus golden frame hashes of the IVG path (bit-exact,
 * for the board's host == board test).
 */
#include <stdio.h>
#include <stdlib.h>
#include "test_common.h"
#include "lumo/arena.h"
#include "lumo/ivg.h"
#include "lumo/raster.h"
#include "package/ivg_encode.h"
#include "../../tools/lumo-render/mesh_build.h"
#include "../../tools/lumo-render/scene_convert.h"

#define W 128
#define H 96

static const uint16_t dims[3] = {5, 4, 6};
static const double bmin[3] = {-2, -1, -3}, bmax[3] = {2, 2, 1};
static srv_ivg_fentry deq[5 * 4 * 6][LUMO_IVG_AXES];
static uint32_t color[W * H], depth[W * H];
static uint8_t arena_buf[1 << 20];
static uint8_t bundle[1 << 16];

static void make_entry(int i, int j, int k, int a, srv_ivg_fentry *e)
{
    double d[3] = {0.3 * sin(i + a), 0.3 * cos(j * 1.7 + a), 0.3 * sin(k * 0.9 - a)}, l;
    int m;
    d[a / 2] += (a & 1) ? -1 : 1;
    l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (m = 0; m < 3; m++)
        e->d[m] = (float)(d[m] / l);
    e->c[0] = (float)(0.5 + 0.1 * i + 0.05 * a);
    e->c[1] = (float)(0.3 + 0.05 * j * (a + 1));
    e->c[2] = (float)(0.2 + 0.07 * k + 0.02 * a);
}

static lumo_ivg *build_grid(void)
{
    lumo_ivg_desc desc;
    lumo_arena arena;
    srv_ivg_writer w;
    lumo_ivg *g = NULL;
    uint32_t applied = 0, v = 0;
    size_t len;
    int i, j, k, a;

    memset(&desc, 0, sizeof desc);
    for (a = 0; a < 3; a++) {
        desc.dims[a] = dims[a];
        desc.bmin[a] = host_q16(bmin[a]);
        desc.bmax[a] = host_q16(bmax[a]);
    }
    assert_int_equal(lumo_arena_init(&arena, arena_buf, sizeof arena_buf), LUMO_OK);
    assert_int_equal(lumo_ivg_create(&g, &arena, &desc), LUMO_OK);
    assert_int_equal(srv_ivg_writer_begin(&w, bundle, sizeof bundle, LUMO_IVG_FORM_QUANTIZED, dims), LUMO_OK);
    for (k = 0; k < dims[2]; k++)
        for (j = 0; j < dims[1]; j++)
            for (i = 0; i < dims[0]; i++, v++) {
                srv_ivg_fentry e[LUMO_IVG_AXES];
                for (a = 0; a < LUMO_IVG_AXES; a++) {
                    make_entry(i, j, k, a, &e[a]);
                    srv_ivg_dequantize(&e[a], &deq[v][a]);
                }
                assert_int_equal(srv_ivg_writer_add(&w, v, e), LUMO_OK);
            }
    len = srv_ivg_writer_finish(&w);
    assert_true(len > 0);
    assert_int_equal(lumo_ivg_apply_bundle(g, bundle, len, &applied), LUMO_OK);
    assert_int_equal(applied, v);
    return g;
}

/* Seed 000 §3.2 in double: hemispheres by the signs of n, trilinear c and d
 * separately, I_n . n = sum n_a^2 (d_a . n) c_a, clamped at 0. */
static void ref_irradiance(const double p[3], const double n[3], double e[3])
{
    double s[3] = {0, 0, 0};
    int cell[3], a, m, corner;
    double t[3];

    for (a = 0; a < 3; a++) {
        double u = (p[a] - bmin[a]) / (bmax[a] - bmin[a]);
        u = (u < 0 ? 0 : u > 1 ? 1 : u) * (dims[a] - 1);
        cell[a] = (int)floor(u);
        if (cell[a] > dims[a] - 2) cell[a] = dims[a] - 2;
        t[a] = u - cell[a];
    }
    for (a = 0; a < 3; a++) {
        int axis = 2 * a + (n[a] < 0);
        double c[3] = {0, 0, 0}, d[3] = {0, 0, 0}, dn;
        for (corner = 0; corner < 8; corner++) {
            int ix = cell[0] + (corner & 1), iy = cell[1] + ((corner >> 1) & 1), iz = cell[2] + (corner >> 2);
            double wgt = ((corner & 1) ? t[0] : 1 - t[0]) * (((corner >> 1) & 1) ? t[1] : 1 - t[1])
                       * ((corner >> 2) ? t[2] : 1 - t[2]);
            const srv_ivg_fentry *f = &deq[ix + dims[0] * (iy + dims[1] * iz)][axis];
            for (m = 0; m < 3; m++) {
                c[m] += wgt * f->c[m];
                d[m] += wgt * f->d[m];
            }
        }
        dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        for (m = 0; m < 3; m++)
            s[m] += n[a] * n[a] * dn * c[m];
    }
    for (m = 0; m < 3; m++)
        e[m] = s[m] > 0 ? s[m] : 0;
}

static double srgb8(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
    return floor(v * 255 + 0.5);
}

static void normalize(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l; v[1] /= l; v[2] /= l;
}

typedef struct plane_case {
    double n[3], point[3], eye_off[3];
} plane_case;

static const plane_case cases[] = {
    {{0.3, 0.8, 0.5}, {0, 0.5, -1}, {0.4, 0.3, 0.2}},
    {{-0.6, 0.3, 0.74}, {0.5, 0.2, -0.5}, {-0.2, 0.5, 0.1}},
    {{0.2, -0.5, 0.84}, {-0.3, 1.0, -1.5}, {0.3, -0.2, 0.3}},
};

/* Render plane case `ci` with the IVG only; return the FNV-1a hash of the
 * frame and, when check > 0, check it against the reference: at most
 * `check` codes off on every channel. ivg_vertex: per pixel with the IVG
 * sampled per vertex and interpolated (lumo_raster_indirect_vertices). */
static uint64_t draw_case_mode(const lumo_ivg *g, int ci, uint32_t flags, int check, int ivg_vertex)
{
    const plane_case *pc = &cases[ci];
    const double alb[3] = {0.9, 0.8, 0.7};
    double n[3], u[3], v[3], c[3], eye[3], f[3], r[3], up[3], tn;
    host_mesh m = {0};
    lumo_raster_camera cam;
    lumo_raster_view view;
    lumo_raster_scene s;
    lumo_raster_mesh rm;
    lumo_raster_target t;
    char cs[256];
    uint64_t h = 1469598103934665603ull;
    int k, x, y, compared = 0, worst = 0;
    double sum = 0;
    lumo_uq16_16 *ind = NULL;

    memcpy(n, pc->n, sizeof n);
    normalize(n);
    u[0] = n[1]; u[1] = -n[0]; u[2] = 0;           /* u perpendicular to n */
    normalize(u);
    v[0] = n[1] * u[2] - n[2] * u[1];               /* v = n x u: u x v = n */
    v[1] = n[2] * u[0] - n[0] * u[2];
    v[2] = n[0] * u[1] - n[1] * u[0];
    for (k = 0; k < 3; k++) {
        c[k] = pc->point[k] - 20 * u[k] - 20 * v[k];
        u[k] *= 40;
        v[k] *= 40;
        eye[k] = pc->point[k] + 2.5 * n[k] + pc->eye_off[k];
    }
    host_mesh_add_quad(&m, c, u, v, 24, 24, alb);
    rm = host_mesh_raster(&m);
    snprintf(cs, sizeof cs, "%.17g,%.17g,%.17g:%.17g,%.17g,%.17g:0,1,0:60", eye[0], eye[1], eye[2],
             pc->point[0], pc->point[1], pc->point[2]);
    memset(&cam, 0, sizeof cam);
    assert_int_equal(host_camera_from_string(cs, &cam), LUMO_OK);
    cam.znear = host_q16(0.05);
    assert_int_equal(lumo_raster_view_init(&view, &cam, W, H), LUMO_OK);
    memset(&s, 0, sizeof s);
    s.indirect = lumo_raster_ivg_irradiance;
    s.indirect_ctx = g;
    s.exposure = LUMO_Q16_FROM_INT(2);
    s.flags = flags;
    memset(&t, 0, sizeof t);
    t.width = W; t.height = H; t.band_rows = H; t.format = LUMO_PIXEL_XRGB8888;
    t.color = color; t.color_stride = W * 4; t.depth = depth; t.depth_bits = 32;
    lumo_raster_clear(&t, 0);
    if (ivg_vertex) {
        ind = malloc(lumo_raster_lit_bytes(rm.vertex_count));
        assert_non_null(ind);
        assert_int_equal(lumo_raster_indirect_vertices(&s, &rm, ind), LUMO_OK);
        rm.indirect = ind;
    }
    assert_int_equal(lumo_raster_draw(&view, &s, &rm, NULL, &t), LUMO_OK);
    for (k = 0; k < W * H; k++) {
        h ^= color[k];
        h *= 1099511628211ull;
    }
    /* Rays exactly as the camera convention (docs/scene-format.md), from
     * the Q16.16 camera the rasterizer saw. */
    for (k = 0; k < 3; k++) {
        eye[k] = cam.eye[k] / 65536.0;
        f[k] = cam.target[k] / 65536.0 - eye[k];
        up[k] = k == 1;
    }
    normalize(f);
    r[0] = f[1] * up[2] - f[2] * up[1]; r[1] = f[2] * up[0] - f[0] * up[2]; r[2] = f[0] * up[1] - f[1] * up[0];
    normalize(r);
    up[0] = r[1] * f[2] - r[2] * f[1]; up[1] = r[2] * f[0] - r[0] * f[2]; up[2] = r[0] * f[1] - r[1] * f[0];
    tn = tan(60 * M_PI / 360);
    for (y = 0; check && y < H; y++)
        for (x = 0; x < W; x++) {
            double sx = (2 * (x + 0.5) / W - 1) * tn * W / H, sy = (1 - 2 * (y + 0.5) / H) * tn;
            double d[3], den = 0, num = 0, hit, p[3], e[3], nn[3];
            for (k = 0; k < 3; k++) {
                d[k] = f[k] + sx * r[k] + sy * up[k];
                den += d[k] * n[k];
                num += (pc->point[k] - eye[k]) * n[k];
            }
            if (den > -0.05) continue;           /* grazing: sub-pixel detail */
            hit = num / den;
            for (k = 0; k < 3; k++) {
                p[k] = eye[k] + hit * d[k];
                nn[k] = host_q14(n[k]) / 16384.0;  /* the normal the mesh holds */
            }
            if (fabs((p[0] - pc->point[0]) * u[0] + (p[1] - pc->point[1]) * u[1] + (p[2] - pc->point[2]) * u[2]) > 19.5 * 40
                || fabs((p[0] - pc->point[0]) * v[0] + (p[1] - pc->point[1]) * v[1] + (p[2] - pc->point[2]) * v[2]) > 19.5 * 40)
                continue;
            ref_irradiance(p, nn, e);
            for (k = 0; k < 3; k++) {
                int want = (int)srgb8(2 * alb[k] / M_PI * e[k]);
                int got = (int)((color[y * W + x] >> (16 - 8 * k)) & 0xFF);
                int diff = abs(got - want);
                if (diff > worst) worst = diff;
                sum += diff;
            }
            compared++;
        }
    if (check) {
        printf("IVG plane %d%s: %d pixels, worst %d codes, mean %.3f\n", ci, ivg_vertex ? " (IVG per vertex)" : "",
               compared, worst, sum / (3.0 * compared));
        assert_true(compared > W * H / 4);
        assert_true(worst <= check);
    }
    free(ind);
    host_mesh_free(&m);
    return h;
}

static uint64_t draw_case(const lumo_ivg *g, int ci, uint32_t flags, int check)
{
    return draw_case_mode(g, ci, flags, check, 0);
}

static void test_ivg_per_pixel_vs_reference(void **state)
{
    lumo_ivg *g = build_grid();
    int ci;
    (void)state;
    for (ci = 0; ci < 3; ci++)
        draw_case(g, ci, LUMO_RASTER_PER_PIXEL, 1);
}

/* The IVG sampled per vertex and interpolated (per-pixel lighting): on a
 * quad tessellated at 1.7 units through a grid of 1-unit cells, the error
 * against the double reference, and the bytes the same in bands (the
 * interpolated IVG is a varying like any other). */
static void test_ivg_per_vertex(void **state)
{
    lumo_ivg *g = build_grid();
    int ci;
    (void)state;
    for (ci = 0; ci < 3; ci++)
        draw_case_mode(g, ci, LUMO_RASTER_PER_PIXEL, 16, 1);
}

/* Bit-exact frames of the IVG path, per pixel and per vertex. */
static void test_ivg_golden(void **state)
{
    static const uint64_t golden[2][3] = {
        {0x3376944ea66de461ull, 0xec72c096ceadb8c0ull, 0x5baa95239c29452aull},
        {0xa8d79bbb7b22a6fcull, 0x39ebc66f756767c7ull, 0xc8b3d9e4fbb33970ull}};
    lumo_ivg *g = build_grid();
    int ci, mode, bad = 0;
    (void)state;
    for (mode = 0; mode < 2; mode++)
        for (ci = 0; ci < 3; ci++) {
            uint64_t h = draw_case(g, ci, mode ? 0 : LUMO_RASTER_PER_PIXEL, 0);
            if (h != golden[mode][ci]) {
                printf("golden[%d][%d] = 0x%016llxull\n", mode, ci, (unsigned long long)h);
                bad = 1;
            }
        }
    assert_int_equal(bad, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ivg_per_pixel_vs_reference),
        cmocka_unit_test(test_ivg_golden),
        cmocka_unit_test(test_ivg_per_vertex),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
