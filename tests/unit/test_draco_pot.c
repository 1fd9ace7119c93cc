/*
 * test_draco_pot.c — the lean Draco decoder's packed opposite table
 * (ld_pot, sdk/src/draco_cornertable.c) on synthetic corner tables: every
 * kind of word (near, based, escape, border) at the narrowest fields the
 * decoder accepts, read back exactly, and the face words stripped back to
 * their vertex ids. The dragons exercise the same code through the
 * conformance suite; these tables reach the corners of the format that
 * real meshes seldom do (full escape blocks, bases out of int16 range,
 * 3-byte escape entries).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "test_common.h"
#include "../../sdk/src/draco_internal.h"

static uint32_t g_seed;
static uint32_t rnd(void)
{
    g_seed = g_seed * 1664525u + 1013904223u;
    return g_seed >> 8;
}

/* The kinds of opposite distance a table draws from, in percent. */
typedef struct pot_mix {
    unsigned near, ring, far, border;  /* the rest: the next free corner */
    uint32_t ring_len;                 /* the spiral's ring, in corners */
} pot_mix;

/* An involution on n corners with the mix's distances; LD_INV: border. */
static void make_opposites(uint32_t *opp, uint32_t n, const pot_mix *mix)
{
    uint32_t c;
    for (c = 0; c < n; ++c)
        opp[c] = LD_O24_NONE;  /* unpaired so far */
    for (c = 0; c < n; ++c) {
        uint32_t r = rnd() % 100u, o = n, tries;
        if (opp[c] != LD_O24_NONE)
            continue;
        if (r < mix->border) {
            opp[c] = LD_INV;
            continue;
        }
        r -= mix->border;
        if (r < mix->near)
            o = c + 1u + rnd() % 8u;
        else if (r < mix->near + mix->ring)
            o = c + mix->ring_len - 64u + rnd() % 128u;
        else if (r < mix->near + mix->ring + mix->far)
            o = c + 1u + rnd() % (n - c);
        for (tries = 0; tries < 64u && (o >= n || opp[o] != LD_O24_NONE); ++tries)
            o = o >= n ? c + 1u : o + 1u;  /* the next free corner after c */
        if (o >= n || opp[o] != LD_O24_NONE) {
            opp[c] = LD_INV;
            continue;
        }
        opp[c] = o;
        opp[o] = c;
    }
}

/* Words of each kind in a packed table. */
typedef struct pot_kinds {
    uint32_t near, based, escape, border, rank15;
} pot_kinds;

static void count_kinds(const uint32_t *words, uint32_t n, unsigned vshift, pot_kinds *k)
{
    const uint32_t gmask = (1u << (31u - vshift)) - 1u;
    uint32_t c;
    memset(k, 0, sizeof *k);
    for (c = 0; c < n; ++c) {
        const uint32_t g = (words[c] >> vshift) & gmask;
        if (!(words[c] & LD_POT_FAR))
            k->near++;
        else if (!(g & 1u))
            k->based++;
        else if (g == gmask)
            k->border++;
        else {
            k->escape++;
            k->rank15 += ((g >> 1) & 31u) == 15u;
        }
    }
}

/* Pack a table of n corners with vertex ids below 2^vshift, read every
 * opposite back, strip the words; *k: the kinds of word packed. */
static void check_table(uint32_t n, unsigned vshift, const pot_mix *mix, pot_kinds *k)
{
    uint32_t *opp = malloc(n * sizeof *opp), *vert = malloc(n * sizeof *vert);
    uint32_t *words = malloc(n * sizeof *words);
    uint8_t *o24 = calloc(3u * (size_t)n + 1u, 1);
    uint16_t *fine = malloc(((n + 15u) / 16u) * sizeof *fine);
    uint32_t *coarse = malloc(((n + 1023u) / 1024u) * sizeof *coarse);
    int16_t *base = malloc(2u * ld_pot_bases(n) * sizeof *base);
    const uint32_t vmax = vshift >= 32u ? 0xFFFFFFFFu : (1u << vshift) - 1u;
    uint32_t c, bad = 0;
    size_t esc;
    ld_pot t;
    assert_non_null(opp);
    assert_non_null(vert);
    assert_non_null(words);
    assert_non_null(o24);
    assert_non_null(fine);
    assert_non_null(coarse);
    assert_non_null(base);
    make_opposites(opp, n, mix);
    for (c = 0; c < n; ++c) {
        vert[c] = c % 7u == 0 ? vmax : rnd() % (vmax + 1u);  /* the top id too */
        words[c] = vert[c];
        ld_o24_set(o24, c, opp[c] == LD_INV ? LD_O24_NONE : opp[c]);
    }
    ld_pot_build(&t, words, n, vshift, o24, fine, coarse, base, &esc);
    assert_true(esc <= 3u * (size_t)n);
    count_kinds(words, n, vshift, k);
    assert_int_equal(esc, (size_t)k->escape * t.esc_width);
    for (c = 0; c < n; ++c) {
        const uint32_t got = ld_pot_opp(&t, c);
        if (got != opp[c] && bad++ < 5)
            fprintf(stderr, "corner %u: opposite %u, read %u\n", c, opp[c], got);
        if ((words[c] & vmax) != vert[c] && bad++ < 5)
            fprintf(stderr, "corner %u: vertex %u, read %u\n", c, vert[c], words[c] & vmax);
    }
    assert_int_equal(bad, 0);
    ld_pot_strip(words, n, vshift);
    for (c = 0; c < n; ++c)
        assert_int_equal(words[c], vert[c]);
    free(opp);
    free(vert);
    free(words);
    free(o24);
    free(fine);
    free(coarse);
    free(base);
}

/* The dragons' mix: near, a ring, a few far and borders. */
static void test_spiral(void **state)
{
    const pot_mix mix = {62, 30, 3, 2, 6000};
    pot_kinds k;
    unsigned vshift;
    (void)state;
    g_seed = 1;
    for (vshift = 16; vshift <= LD_POT_MAX_VSHIFT; vshift += 4) {
        check_table(3u * 40000u, vshift, &mix, &k);
        assert_true(k.near > 0 && k.escape > 0 && k.border > 0);
    }
    check_table(3u * 40000u + 3u, 19, &mix, &k);  /* a partial last block */
    /* k = 13, the 871k dragon's: the ring is beyond the near window */
    assert_true(k.based > k.escape && k.near > k.based && k.border > 0);
}

/* Everything far: full blocks of 16 escapes (rank 15), bases refused. */
static void test_all_far(void **state)
{
    const pot_mix mix = {0, 0, 100, 0, 0};
    pot_kinds k;
    (void)state;
    g_seed = 2;
    check_table(3u * 30000u, LD_POT_MAX_VSHIFT, &mix, &k);
    assert_true(k.escape > k.based && k.rank15 > 0);
    check_table(3u * 30000u, 20, &mix, &k);
    assert_true(k.rank15 > 0);
}

/* Rings longer than an int16 base reaches: their first far opposites escape
 * and leave the base unset. */
static void test_long_rings(void **state)
{
    const pot_mix mix = {50, 45, 0, 5, 40000};
    pot_kinds k;
    (void)state;
    g_seed = 3;
    check_table(3u * 50000u, 22, &mix, &k);
    assert_true(k.escape > 0 && k.based == 0);
}

/* Corner ids beyond 2^21 with 8 bits of field: escape entries of 3 bytes. */
static void test_wide_escapes(void **state)
{
    const pot_mix mix = {40, 20, 35, 5, 3000};
    pot_kinds k;
    (void)state;
    g_seed = 4;
    assert_int_equal(ld_pot_escape_width(3u * 1000000u, 24), 3);
    check_table(3u * 1000000u, 24, &mix, &k);
    assert_true(k.escape > 0 && k.based > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spiral),
        cmocka_unit_test(test_all_far),
        cmocka_unit_test(test_long_rings),
        cmocka_unit_test(test_wide_escapes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
