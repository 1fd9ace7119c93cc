/* stl_check.c — lumo's check of an STL file before assimp (model_check.h).
 *
 * A binary STL is an 80-byte header, a u32 triangle count n and n records
 * of 50 bytes (normal, three corners, an attribute word): its size must be
 * exactly 84 + 50·n, which is also how assimp tells binary from ASCII. A
 * count the bytes cannot hold (10^9 triangles over a few bytes) is refused
 * here, so assimp's allocation (about 100 bytes per triangle) stays within
 * twice the file. An ASCII STL is "solid", then facets of exactly three
 * "vertex x y z" lines; assimp reserves room from the file's size, so only
 * the text and the numbers need checking. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "scene/model_check.h"
#include "scene/model_check_internal.h"

#define STL_HEADER 80u
#define STL_RECORD 50u

static float le_float(const uint8_t *p)
{
    uint32_t w = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &w, 4);
    return f;
}

/* Each corner of each record finite and within the coordinate bound (the
 * normal is recomputed by lumo, its value is not used). */
static lumo_status stl_binary_body(srv_mc *c, uint32_t n)
{
    for (uint32_t t = 0; t < n; t++) {
        const uint8_t *r = c->base + STL_HEADER + 4 + (size_t)t * STL_RECORD;
        for (int k = 0; k < 9; k++) {
            float v = le_float(r + 12 + 4 * k);
            const char *why = srv_mc_coord_problem(v);
            if (why)
                return srv_mc_fail(c, srv_mc_coord_status(v), "triangle %u, corner %d: %c = %.9g %s", t, k / 3,
                                   "xyz"[k % 3], v, why);
        }
    }
    return LUMO_OK;
}

/* The next word of the text at c->p (its line counted) into [*s, *e); 0 at
 * the end. */
static int next_word(srv_mc *c, const char **s, const char **e)
{
    while (c->p < c->end && isspace(*c->p))
        c->line += *c->p++ == '\n';
    if (c->p >= c->end)
        return 0;
    *s = (const char *)c->p;
    while (c->p < c->end && !isspace(*c->p))
        c->p++;
    *e = (const char *)c->p;
    return 1;
}

static int word_is(const char *s, const char *e, const char *w)
{
    return (size_t)(e - s) == strlen(w) && !memcmp(s, w, (size_t)(e - s));
}

/* "vertex x y z" of corner k of facet f. */
static lumo_status stl_vertex(srv_mc *c, unsigned long f, int k)
{
    for (int a = 0; a < 3; a++) {
        const char *s, *e, *why;
        char buf[64], *stop;
        double v;
        if (!next_word(c, &s, &e) || (size_t)(e - s) >= sizeof buf)
            return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: facet %lu, vertex %d: %c is missing", c->line + 1, f,
                               k, "xyz"[a]);
        memcpy(buf, s, (size_t)(e - s));
        buf[e - s] = 0;
        v = strtod(buf, &stop);
        if (*stop)
            return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: facet %lu, vertex %d: %c '%s' is not a number",
                               c->line + 1, f, k, "xyz"[a], buf);
        if ((why = srv_mc_coord_problem(v)))
            return srv_mc_fail(c, srv_mc_coord_status(v), "line %u: facet %lu, vertex %d: %c = %.9g %s",
                               c->line + 1, f, k, "xyz"[a], v, why);
    }
    return LUMO_OK;
}

/* After "solid name": facets, each with exactly three vertices, up to
 * "endsolid" or the end. Other words (normal, loop, their numbers) are
 * assimp's business. */
static lumo_status stl_ascii(srv_mc *c)
{
    const char *s, *e;
    unsigned long facets = 0;
    int corners = -1;   /* inside a facet: its vertices so far */
    lumo_status st = LUMO_OK;
    while (!st && next_word(c, &s, &e) && !word_is(s, e, "endsolid")) {
        if (word_is(s, e, "facet")) {
            if (corners >= 0)
                return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: facet %lu has no endfacet", c->line + 1, facets);
            corners = 0;
        } else if (word_is(s, e, "vertex")) {
            if (corners < 0 || corners == 3)
                return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: %s", c->line + 1,
                                   corners < 0 ? "a vertex outside a facet" : "a facet with more than 3 vertices");
            st = stl_vertex(c, facets, corners++);
        } else if (word_is(s, e, "endfacet")) {
            if (corners != 3)
                return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: facet %lu has %d vertices, a facet has 3",
                                   c->line + 1, facets, corners < 0 ? 0 : corners);
            corners = -1;
            facets++;
        }
    }
    if (!st && corners >= 0)
        return srv_mc_fail(c, LUMO_ERR_TRUNCATED, "the file ends inside facet %lu", facets);
    if (!st && facets == 0)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "an ASCII STL without a facet");
    return st;
}

/* Whether the file opens with the word "solid" and is text throughout. */
static int ascii_stl(const srv_mc *c)
{
    srv_mc probe = *c;
    const char *s, *e;
    return next_word(&probe, &s, &e) && word_is(s, e, "solid") && !srv_mc_check_text(&probe, c->base, c->end);
}

lumo_status srv_mc_check_stl(srv_mc *c)
{
    size_t size = (size_t)(c->end - c->base);
    const uint8_t *nl;
    if (size >= STL_HEADER + 4) {
        const uint8_t *q = c->base + STL_HEADER;
        uint32_t n = (uint32_t)q[0] | (uint32_t)q[1] << 8 | (uint32_t)q[2] << 16 | (uint32_t)q[3] << 24;
        unsigned long long need = STL_HEADER + 4 + (unsigned long long)STL_RECORD * n;
        if (need == size)
            return n ? stl_binary_body(c, n) : srv_mc_fail(c, LUMO_ERR_CORRUPT, "a binary STL of 0 triangles");
        if (!ascii_stl(c))
            return srv_mc_fail(c, need > size ? LUMO_ERR_TRUNCATED : LUMO_ERR_CORRUPT,
                               "the binary STL header declares %u triangles: 84 + 50 x %u = %llu bytes, the file "
                               "holds %zu", n, n, need, size);
    } else if (!ascii_stl(c)) {
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "%zu bytes: too short for a binary STL (84-byte header) and not "
                           "an ASCII one ('solid' and text)", size);
    }
    /* "solid NAME": the name is the rest of the line, whatever its words. */
    nl = memchr(c->base, '\n', size);
    c->p = nl ? nl + 1 : c->end;
    c->line = 1;
    return stl_ascii(c);
}
