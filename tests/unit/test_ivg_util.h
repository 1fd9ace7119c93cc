/*
 * test_ivg_util.h — helpers shared by the IVG unit tests (test_ivg*.c):
 * grids on a heap buffer, random irradiance fields in float, bundles built
 * with the server's writer (server/package/ivg_encode.c) as the server would.
 */
#ifndef LUMO_TEST_IVG_UTIL_H
#define LUMO_TEST_IVG_UTIL_H

#include <stdlib.h>
#include "test_common.h"
#include "lumo/ivg.h"
#include "package/ivg_encode.h"

#define Q16 65536.0
#define Q14 16384.0

typedef struct tgrid {
    uint8_t      *mem;
    size_t        size;
    lumo_arena    arena;
    lumo_ivg     *g;
    lumo_ivg_desc desc;
} tgrid;

/* A grid of nx x ny x nz over [0, ext]^3 (ext in scene units). */
static inline lumo_ivg *tgrid_make(tgrid *t, unsigned nx, unsigned ny, unsigned nz, int32_t ext)
{
    lumo_ivg_desc d = {{(uint16_t)nx, (uint16_t)ny, (uint16_t)nz}, {0, 0, 0},
                       {LUMO_Q16_FROM_INT(ext), LUMO_Q16_FROM_INT(ext), LUMO_Q16_FROM_INT(ext)}};
    t->desc = d;
    t->size = lumo_ivg_memory_size(&d);
    assert_true(t->size > 0);
    t->mem = malloc(t->size);
    assert_non_null(t->mem);
    memset(t->mem, 0x5A, t->size);   /* the arena must zero what it hands out */
    assert_int_equal(lumo_arena_init(&t->arena, t->mem, t->size), LUMO_OK);
    assert_int_equal(lumo_ivg_create(&t->g, &t->arena, &d), LUMO_OK);
    return t->g;
}

static inline void tgrid_free(tgrid *t)
{
    free(t->mem);
    t->mem = NULL;
}

/* A random unit vector, uniform over the sphere (rejection sampling). */
static inline void random_unit3(test_rng *r, double v[3])
{
    double len;
    int k;
    do {
        len = 0;
        for (k = 0; k < 3; k++) {
            v[k] = test_rng_uniform(r, -1, 1);
            len += v[k] * v[k];
        }
    } while (len < 0.01 || len > 1);
    len = sqrt(len);
    for (k = 0; k < 3; k++)
        v[k] /= len;
}

/* A random entry: unit d, colour in [0, cmax) per channel. */
static inline void random_fentry(test_rng *r, srv_ivg_fentry *e, double cmax)
{
    double v[3];
    int k;
    random_unit3(r, v);
    for (k = 0; k < 3; k++) {
        e->d[k] = (float)v[k];
        e->c[k] = (float)test_rng_uniform(r, 0, cmax);
    }
}

/* A whole field: count vertices x 6 entries. */
static inline srv_ivg_fentry (*random_field(test_rng *r, uint32_t count, double cmax))[LUMO_IVG_AXES]
{
    srv_ivg_fentry (*f)[LUMO_IVG_AXES] = malloc(sizeof *f * count);
    uint32_t v;
    int a;
    assert_non_null(f);
    for (v = 0; v < count; v++)
        for (a = 0; a < LUMO_IVG_AXES; a++)
            random_fentry(r, &f[v][a], cmax);
    return f;
}

/* Bundle of the listed vertices of `field` (malloc'd; *len its size). */
static inline uint8_t *make_bundle(const lumo_ivg_desc *d, lumo_ivg_form form, const uint32_t *verts,
                                   uint32_t n, const srv_ivg_fentry (*field)[LUMO_IVG_AXES], size_t *len)
{
    size_t cap = srv_ivg_bundle_bytes(form, n, 0);
    uint8_t *buf = malloc(cap + 1);
    srv_ivg_writer w;
    uint32_t i;
    assert_non_null(buf);
    assert_int_equal(srv_ivg_writer_begin(&w, buf, cap, form, d->dims), LUMO_OK);
    for (i = 0; i < n; i++)
        assert_int_equal(srv_ivg_writer_add(&w, verts[i], field[verts[i]]), LUMO_OK);
    *len = srv_ivg_writer_finish(&w);
    assert_int_equal(*len, cap);
    return buf;
}

/* Apply the listed vertices of `field` to g; asserts success. */
static inline void send(lumo_ivg *g, lumo_ivg_form form, const uint32_t *verts, uint32_t n,
                        const srv_ivg_fentry (*field)[LUMO_IVG_AXES])
{
    size_t len;
    uint32_t applied = 0;
    uint8_t *b = make_bundle(lumo_ivg_get_desc(g), form, verts, n, field, &len);
    assert_int_equal(lumo_ivg_apply_bundle(g, b, len, &applied), LUMO_OK);
    assert_int_equal(applied, n);
    free(b);
}

/* A random subset of about `percent` % of 0..count-1 (at least one);
 * returns the number chosen, in increasing order. */
static inline uint32_t random_subset(test_rng *r, uint32_t count, unsigned percent, uint32_t *out)
{
    uint32_t v, n = 0;
    for (v = 0; v < count; v++)
        if (test_rng_next(r) % 100u < percent)
            out[n++] = v;
    if (n == 0)
        out[n++] = (uint32_t)(test_rng_next(r) % count);
    return n;
}

#endif
