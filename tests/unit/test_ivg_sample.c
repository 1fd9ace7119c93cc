/* test_ivg_sample.c — IVG shading (seed 000 §3.2, eq. 2) against a
 * double-precision reference over the stored entries, and hand-made cases
 * with known answers (constant and linear fields, n along delta). */
#include "test_ivg_util.h"
#include "test_ivg_entry.h"

/* Reference: trilinear interpolation (in double) of the fixed-point entries
 * the grid holds, then I_n . n = sum_a n_a^2 (d_a . n) c_a, clamped at 0.
 * err[k] gets the error bound for channel k: the client interpolates by
 * three rounded lerps (<= 3/2 ulp on c and on d), d . n then carries
 * <= 3/2 ulp(Q1.14) * |n|_1 and the result one final rounding. */
static void ref_irradiance(const lumo_ivg *g, const lumo_q16_16 p[3], const lumo_q1_14 n[3], double out[3],
                           double err[3])
{
    const lumo_ivg_desc *d = lumo_ivg_get_desc(g);
    double u[3], t[3], nn[3], n1 = 0;
    unsigned cell[3];
    int a, k, c;

    for (a = 0; a < 3; a++) {
        double lo = d->bmin[a] / Q16, hi = d->bmax[a] / Q16, x = p[a] / Q16;
        x = x < lo ? lo : x > hi ? hi : x;
        u[a] = (x - lo) / (hi - lo) * (d->dims[a] - 1);
        cell[a] = (unsigned)floor(u[a]);
        if (cell[a] > d->dims[a] - 2u) cell[a] = d->dims[a] - 2u;
        t[a] = u[a] - cell[a];
        nn[a] = n[a] / Q14;
        n1 += fabs(nn[a]);
    }
    for (k = 0; k < 3; k++) out[k] = err[k] = 0;
    for (a = 0; a < 3; a++) {
        int axis = 2 * a + (n[a] < 0);
        double ci[3] = {0, 0, 0}, di[3] = {0, 0, 0}, dn = 0, cmax = 0, n2 = nn[a] * nn[a];
        for (c = 0; c < 8; c++) {
            unsigned i = cell[0] + (c & 1), j = cell[1] + (c >> 1 & 1), kk = cell[2] + (c >> 2 & 1);
            double w = (c & 1 ? t[0] : 1 - t[0]) * (c & 2 ? t[1] : 1 - t[1]) * (c & 4 ? t[2] : 1 - t[2]);
            const lumo_ivg_entry *e = IVG_ENTRY(g, i + d->dims[0] * (j + d->dims[1] * kk), (lumo_ivg_axis)axis);
            for (k = 0; k < 3; k++) {
                ci[k] += w * e->c[k] / Q16;
                di[k] += w * e->d[k] / Q14;
                if (e->c[k] / Q16 > cmax) cmax = e->c[k] / Q16;
            }
        }
        for (k = 0; k < 3; k++)
            dn += di[k] * nn[k];
        for (k = 0; k < 3; k++) {
            out[k] += n2 * dn * ci[k];
            err[k] += n2 * (cmax * 1.5 / Q14 * n1 + 1.5 / Q16 * fabs(dn));
        }
    }
    for (k = 0; k < 3; k++) {
        /* the position maps to Q16 grid units with <= 1 ulp error, a change
         * of at most cmax / 2^16: inside the cmax * 1.5 / 2^14 term above */
        out[k] = out[k] < 0 ? 0 : out[k];
        err[k] += 0.5 / Q16 + 1e-9 + out[k] * 1e-6;
    }
}

static void random_normal(test_rng *r, lumo_q1_14 n[3])
{
    double v[3], len;
    int k;
    random_unit3(r, v);
    /* sometimes exactly on an axis or in a coordinate plane */
    if (test_rng_next(r) % 8 == 0)
        v[test_rng_next(r) % 3] = 0;
    len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (k = 0; k < 3; k++)
        n[k] = (lumo_q1_14)lround(v[k] / len * Q14);
}

static void compare_random(lumo_ivg *g, test_rng *r, int samples)
{
    const lumo_ivg_desc *d = lumo_ivg_get_desc(g);
    double worst = 0;
    int s, a, k;
    for (s = 0; s < samples; s++) {
        lumo_q16_16 p[3];
        lumo_q1_14 n[3];
        lumo_uq16_16 got[3];
        double want[3], err[3];
        for (a = 0; a < 3; a++) {
            double lo = d->bmin[a] / Q16, hi = d->bmax[a] / Q16, m = 0.1 * (hi - lo);
            p[a] = (lumo_q16_16)lround(test_rng_uniform(r, lo - m, hi + m) * Q16);
        }
        random_normal(r, n);
        lumo_ivg_irradiance(g, p, n, got);
        ref_irradiance(g, p, n, want, err);
        for (k = 0; k < 3; k++) {
            double e = fabs(got[k] / Q16 - want[k]);
            if (e / err[k] > worst) worst = e / err[k];
            assert_close(got[k] / Q16, want[k], err[k]);
        }
    }
    print_message("sampling: worst error %.2f of the bound\n", worst);
}

static void test_random_full(void **state)
{
    test_rng r = {123};
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 9, 7, 5, 6);
    uint32_t count = lumo_ivg_vertex_count(g), *all = malloc(count * 4), v;
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(&r, count, 500.0);
    (void)state;
    for (v = 0; v < count; v++) all[v] = v;
    send(g, LUMO_IVG_FORM_QUANTIZED, all, count, f);
    compare_random(g, &r, 200000);
    free(all);
    free(f);
    tgrid_free(&t);
}

/* Sampling a push-pull-filled grid, with an offset, anisotropic box. */
static void test_random_after_pushpull(void **state)
{
    test_rng r = {321};
    tgrid t;
    lumo_ivg *g;
    uint32_t count, *verts, n;
    srv_ivg_fentry (*f)[LUMO_IVG_AXES];
    lumo_ivg_desc d = {{16, 5, 11}, {LUMO_Q16_FROM_INT(-20), LUMO_Q16_FRAC(1, 3), 7}, {LUMO_Q16_FROM_INT(13), LUMO_Q16_FROM_INT(2), 7 + 1000}};
    (void)state;
    t.desc = d;
    t.size = lumo_ivg_memory_size(&d);
    t.mem = malloc(t.size);
    lumo_arena_init(&t.arena, t.mem, t.size);
    assert_int_equal(lumo_ivg_create(&g, &t.arena, &d), LUMO_OK);
    count = lumo_ivg_vertex_count(g);
    verts = malloc(count * 4);
    f = random_field(&r, count, 60.0);
    n = random_subset(&r, count, 20, verts);
    send(g, LUMO_IVG_FORM_FLOAT, verts, n, f);
    assert_int_equal(lumo_ivg_pushpull(g, LUMO_IVG_SMOOTH), LUMO_OK);
    compare_random(g, &r, 100000);
    free(verts);
    free(f);
    tgrid_free(&t);
}

/* Fill every vertex from a function of (i, j, k, axis). */
typedef void (*field_fn)(unsigned i, unsigned j, unsigned k, int axis, srv_ivg_fentry *e);

static void fill(lumo_ivg *g, lumo_ivg_form form, field_fn fn)
{
    const lumo_ivg_desc *d = lumo_ivg_get_desc(g);
    uint32_t count = lumo_ivg_vertex_count(g), *all = malloc(count * 4), v;
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = malloc(count * sizeof *f);
    int a;
    for (v = 0; v < count; v++) {
        all[v] = v;
        for (a = 0; a < LUMO_IVG_AXES; a++)
            fn(v % d->dims[0], v / d->dims[0] % d->dims[1], v / d->dims[0] / d->dims[1], a, &f[v][a]);
    }
    send(g, form, all, count, f);
    free(all);
    free(f);
}

/* d along the hemisphere's own axis, colour linear in the vertex position
 * (values with few bits, exact in binary32 and in UQ16.16). */
static void linear_fn(unsigned i, unsigned j, unsigned k, int axis, srv_ivg_fentry *e)
{
    memset(e, 0, sizeof *e);
    e->d[axis / 2] = axis & 1 ? -1.0f : 1.0f;
    e->c[0] = 10.0f + 2.0f * i + 0.5f * j + 3.0f * k;
    e->c[1] = 100.0f - 1.5f * i + 4.0f * k;
    e->c[2] = 1.0f + 0.25f * (i + j + k) + axis;
}

/* A linear field comes back from trilinear sampling anywhere, within the
 * rounding of the position (1 ulp of Q16 grid units) and of the lerps. */
static void test_linear_field(void **state)
{
    test_rng r = {17};
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 6, 5, 7, 3);
    int s, k, a;
    (void)state;
    fill(g, LUMO_IVG_FORM_FLOAT, linear_fn);
    for (s = 0; s < 50000; s++) {
        lumo_q16_16 p[3];
        lumo_q1_14 n[3] = {0, 0, 0};
        lumo_uq16_16 got[3];
        double u[3], want[3];
        srv_ivg_fentry e;
        int axis = (int)(test_rng_next(&r) % 6);
        for (a = 0; a < 3; a++) {
            p[a] = (lumo_q16_16)(test_rng_next(&r) % (3u << 16));
            u[a] = p[a] / Q16 / 3.0 * (t.desc.dims[a] - 1);
        }
        n[axis / 2] = axis & 1 ? -LUMO_Q14_ONE : LUMO_Q14_ONE;
        lumo_ivg_irradiance(g, p, n, got);
        /* c is linear in (i, j, k): evaluate at the continuous position */
        linear_fn(0, 0, 0, axis, &e);
        want[0] = e.c[0] + 2.0 * u[0] + 0.5 * u[1] + 3.0 * u[2];
        want[1] = e.c[1] - 1.5 * u[0] + 4.0 * u[2];
        want[2] = e.c[2] + 0.25 * (u[0] + u[1] + u[2]);
        for (k = 0; k < 3; k++)
            assert_close(got[k] / Q16, want[k], 8.0 / Q16 + 6.0 / Q16);
    }
    tgrid_free(&t);
}

static void random_entry_fn(unsigned i, unsigned j, unsigned k, int axis, srv_ivg_fentry *e)
{
    test_rng r = {1 + i * 7919u + j * 104729u + k * 1299709u + (unsigned)axis * 15485863u};
    random_fentry(&r, e, 1000.0);
}

/* At a vertex with n = delta the result is exactly c (d . n), rounded once:
 * the directional interpolation is exact there (§3.2). */
static void test_n_along_delta_exact(void **state)
{
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 5, 3, 2, 4);   /* 4 / (dims-1): exact */
    const lumo_ivg_desc *d = lumo_ivg_get_desc(g);
    unsigned i, j, k;
    int axis, ch;
    (void)state;
    fill(g, LUMO_IVG_FORM_QUANTIZED, random_entry_fn);
    for (k = 0; k < d->dims[2]; k++)
        for (j = 0; j < d->dims[1]; j++)
            for (i = 0; i < d->dims[0]; i++)
                for (axis = 0; axis < 6; axis++) {
                    /* vertex positions are exact: 4 units over 4, 2, 1 cells */
                    lumo_q16_16 p[3] = {(lumo_q16_16)(i * (4u << 16) / (d->dims[0] - 1)),
                                        (lumo_q16_16)(j * (4u << 16) / (d->dims[1] - 1)),
                                        (lumo_q16_16)(k * (4u << 16) / (d->dims[2] - 1))};
                    lumo_q1_14 n[3] = {0, 0, 0};
                    lumo_uq16_16 got[3];
                    uint32_t v = i + d->dims[0] * (j + d->dims[1] * k);
                    const lumo_ivg_entry *e = IVG_ENTRY(g, v, (lumo_ivg_axis)axis);
                    int64_t dn;
                    n[axis / 2] = axis & 1 ? -LUMO_Q14_ONE : LUMO_Q14_ONE;
                    lumo_ivg_irradiance(g, p, n, got);
                    dn = (int64_t)e->d[axis / 2] * n[axis / 2];          /* Q28 */
                    for (ch = 0; ch < 3; ch++) {
                        int64_t want = (int64_t)e->c[ch] * dn;            /* Q44 */
                        want = want <= 0 ? 0 : (want + (1 << 27)) >> 28;
                        assert_int_equal(got[ch], (uint32_t)want);
                    }
                }
    tgrid_free(&t);
}

static void constant_fn(unsigned i, unsigned j, unsigned k, int axis, srv_ivg_fentry *e)
{
    (void)i; (void)j; (void)k;
    memset(e, 0, sizeof *e);
    e->d[0] = 0.6f; e->d[1] = axis & 1 ? -0.8f : 0.8f;
    e->c[0] = 12.5f; e->c[1] = 0.75f; e->c[2] = 300.0f;
}

/* A constant field samples to the same bits everywhere, including outside
 * the box (clamped). */
static void test_constant_field(void **state)
{
    test_rng r = {5};
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 4, 9, 2, 5);
    lumo_q1_14 n[3] = {LUMO_Q14_FRAC(2, 3), -LUMO_Q14_FRAC(1, 3), LUMO_Q14_FRAC(2, 3)};
    lumo_q16_16 p0[3] = {0, 0, 0};
    lumo_uq16_16 ref[3], got[3];
    int s, a;
    (void)state;
    fill(g, LUMO_IVG_FORM_QUANTIZED, constant_fn);
    lumo_ivg_irradiance(g, p0, n, ref);
    assert_true(ref[2] > 0);
    for (s = 0; s < 20000; s++) {
        lumo_q16_16 p[3];
        for (a = 0; a < 3; a++)
            p[a] = (lumo_q16_16)(test_rng_next(&r) >> 32);   /* anywhere at all */
        lumo_ivg_irradiance(g, p, n, got);
        assert_memory_equal(got, ref, sizeof ref);
    }
    tgrid_free(&t);
}

/* Radiance = albedo / pi * irradiance; negative albedo counts as 0; a
 * direction facing away from n gives 0, not a negative or wrapped value. */
static void test_radiance_and_clamps(void **state)
{
    test_rng r = {8};
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 3, 3, 3, 1);
    lumo_q16_16 p[3] = {LUMO_Q16_HALF, LUMO_Q16_FRAC(1, 3), 0};
    lumo_uq16_16 irr[3], rad[3];
    int s, k;
    (void)state;
    fill(g, LUMO_IVG_FORM_QUANTIZED, random_entry_fn);
    for (s = 0; s < 20000; s++) {
        lumo_q1_14 n[3], albedo[3];
        random_normal(&r, n);
        for (k = 0; k < 3; k++)
            albedo[k] = (lumo_q1_14)(test_rng_next(&r) % (LUMO_Q14_ONE + 1));
        albedo[s % 3] = s % 7 == 0 ? -100 : albedo[s % 3];
        lumo_ivg_irradiance(g, p, n, irr);
        lumo_ivg_radiance(g, p, n, albedo, rad);
        for (k = 0; k < 3; k++) {
            double rho = albedo[k] < 0 ? 0 : albedo[k] / Q14;
            assert_close(rad[k] / Q16, rho / M_PI * irr[k] / Q16, 0.5 / Q16 + 1e-5 * irr[k] / Q16);
        }
    }
    {   /* d opposite to n, the brightest colour the grid stores: the dot
         * product is negative, the result 0 */
        srv_ivg_fentry f[LUMO_IVG_AXES];
        uint32_t v0 = 0;
        lumo_q16_16 p0[3] = {0, 0, 0};
        lumo_q1_14 n[3] = {LUMO_Q14_ONE, 0, 0}, huge[3] = {-32768, -32768, -32768};
        memset(f, 0, sizeof f);
        f[LUMO_IVG_PX].d[0] = -1.0f;
        f[LUMO_IVG_PX].c[0] = f[LUMO_IVG_PX].c[1] = f[LUMO_IVG_PX].c[2] = 65408.0f;
        send(g, LUMO_IVG_FORM_QUANTIZED, &v0, 1, (const srv_ivg_fentry(*)[LUMO_IVG_AXES])&f);
        assert_int_equal(IVG_ENTRY(g, 0, LUMO_IVG_PX)->c[0], 65408u << 16);
        lumo_ivg_irradiance(g, p0, n, irr);
        assert_int_equal(irr[0], 0);
        /* a wildly non-unit n stays defined (UBSan watches the arithmetic) */
        lumo_ivg_irradiance(g, p0, huge, irr);
        lumo_ivg_irradiance(g, p0, huge, rad);
        assert_memory_equal(irr, rad, sizeof irr);
    }
    tgrid_free(&t);
}

/* The sampler's memo gives lumo_ivg_irradiance's bits: runs of nearby
 * points with slowly turning normals (a span's pixels: mostly one cell,
 * hemispheres opened one by one), random jumps (a new cell each time), and
 * points outside the box; a sampler made again after the grid changed sees
 * the new values. */
static void sampler_matches(lumo_ivg *g, test_rng *r, int runs)
{
    const lumo_ivg_desc *d = lumo_ivg_get_desc(g);
    lumo_ivg_sampler smp;
    long hits = 0, total = 0;
    int run, s, a, k;

    lumo_ivg_sampler_init(&smp, g);
    for (run = 0; run < runs; run++) {
        lumo_q16_16 p[3], step[3];
        lumo_q1_14 n[3];
        int len = 1 + (int)(test_rng_next(r) % 64);
        for (a = 0; a < 3; a++) {
            double lo = d->bmin[a] / Q16, hi = d->bmax[a] / Q16, m = 0.1 * (hi - lo);
            p[a] = (lumo_q16_16)lround(test_rng_uniform(r, lo - m, hi + m) * Q16);
            step[a] = (lumo_q16_16)lround(test_rng_uniform(r, -0.02, 0.02) * (hi - lo) * Q16);
        }
        random_normal(r, n);
        for (s = 0; s < len; s++) {
            lumo_uq16_16 want[3], got[3];
            uint32_t before = smp.cell;
            lumo_ivg_irradiance(g, p, n, want);
            lumo_ivg_sampler_irradiance(&smp, p, n, got);
            for (k = 0; k < 3; k++)
                assert_int_equal(got[k], want[k]);
            hits += smp.cell == before;
            total++;
            for (a = 0; a < 3; a++)
                p[a] += step[a];
            if (test_rng_next(r) % 4 == 0)
                random_normal(r, n);
        }
    }
    print_message("sampler: %ld of %ld samples in the memo's cell\n", hits, total);
    assert_true(hits > total / 2);   /* runs do reuse the memo */
}

static void test_sampler_same_bits(void **state)
{
    test_rng r = {777};
    tgrid t;
    lumo_ivg *g = tgrid_make(&t, 9, 7, 5, 6);
    const lumo_ivg_desc *d = lumo_ivg_get_desc(g);
    uint32_t count = lumo_ivg_vertex_count(g), *all = malloc(count * 4), v;
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = random_field(&r, count, 500.0);
    lumo_ivg_sampler smp;
    lumo_q16_16 p[3];
    lumo_q1_14 n[3];
    lumo_uq16_16 before[64][3], a[3];
    int i, a_, changed = 0;
    (void)state;
    for (v = 0; v < count; v++) all[v] = v;
    send(g, LUMO_IVG_FORM_QUANTIZED, all, count, f);
    sampler_matches(g, &r, 4000);
    /* the grid changes: a sampler made again follows it (the same walk
     * before and after, seeded alike) */
    for (i = 0; i < 64; i++) {
        test_rng w = {1000u + (uint32_t)i};
        for (a_ = 0; a_ < 3; a_++)
            p[a_] = (lumo_q16_16)lround(test_rng_uniform(&w, d->bmin[a_] / Q16, d->bmax[a_] / Q16) * Q16);
        random_normal(&w, n);
        lumo_ivg_irradiance(g, p, n, before[i]);
    }
    free(f);
    f = random_field(&r, count, 50.0);
    send(g, LUMO_IVG_FORM_QUANTIZED, all, count, f);
    lumo_ivg_sampler_init(&smp, g);
    for (i = 0; i < 64; i++) {
        test_rng w = {1000u + (uint32_t)i};
        lumo_uq16_16 want[3];
        for (a_ = 0; a_ < 3; a_++)
            p[a_] = (lumo_q16_16)lround(test_rng_uniform(&w, d->bmin[a_] / Q16, d->bmax[a_] / Q16) * Q16);
        random_normal(&w, n);
        lumo_ivg_irradiance(g, p, n, want);
        lumo_ivg_sampler_irradiance(&smp, p, n, a);
        assert_memory_equal(a, want, sizeof a);
        changed += memcmp(a, before[i], sizeof a) != 0;
    }
    assert_true(changed > 32);
    sampler_matches(g, &r, 1000);
    /* no grid: zeros, like lumo_ivg_irradiance(NULL, ...) */
    lumo_ivg_sampler_init(&smp, NULL);
    lumo_ivg_sampler_irradiance(&smp, p, n, a);
    assert_true(a[0] == 0 && a[1] == 0 && a[2] == 0);
    free(all);
    free(f);
    tgrid_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_full),
        cmocka_unit_test(test_random_after_pushpull),
        cmocka_unit_test(test_linear_field),
        cmocka_unit_test(test_n_along_delta_exact),
        cmocka_unit_test(test_constant_field),
        cmocka_unit_test(test_radiance_and_clamps),
        cmocka_unit_test(test_sampler_same_bits),
    };
    return cmocka_run_group_tests_name("ivg_sample", tests, NULL, NULL);
}
