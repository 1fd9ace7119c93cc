/*
 * raster_draw.c — triangles to pixels, in integers only.
 *
 * Pipeline (docs/rasterizer.md): vertex -> camera space -> clip space
 * (x, y scaled by cot(fovy/2), w = depth along the view axis) -> homogeneous
 * clipping against the near plane and a guard band -> screen coordinates
 * with 4 sub-pixel bits -> edge functions with the top-left fill rule (exact
 * 64-bit integers: shared edges are watertight) -> per pixel: depth near/w,
 * perspective-correct barycentrics, varyings, shading, tone map.
 *
 * Every pixel's value is a function of the triangle and the pixel alone, so
 * drawing a frame in bands of any height gives the same bytes.
 */
#include "lumo/arena.h"
#include "raster_internal.h"

/* Guard band: vertices are clipped to 4096 pixels around the frame centre,
 * so screen coordinates stay under 2^17 sub-pixels and edge functions under
 * 2^37 (int64 with room to spare). */
#define GUARD_PX 4096
#define CLIP_PLANES 5
#define MAX_POLY (3 + CLIP_PLANES)
typedef lumo_raster_sv screen_vertex;
typedef lumo_raster_ctx draw_ctx;

/* ---- vertices ------------------------------------------------------------ */

static unsigned outcode(const lumo_raster_view *view, const lumo_raster_vertex *v);
static int faces_away(const lumo_raster_view *v, const lumo_q16_16 p[3], const lumo_q1_14 n[3]);
static void light_side(const lumo_raster_scene *s, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                       int back, const lumo_q1_14 rho[3], lumo_uq16_16 out[3]);
LUMO_RASTER_HOT void project(const lumo_raster_view *view, const lumo_raster_vertex *v, screen_vertex *s);

/* Camera axis i of p: the rotation's row i times p - eye, rounded from
 * Q14 (the difference made per axis: fewer live registers on the
 * Cortex-M3, where the shadow lookups call it per pixel). */
LUMO_RASTER_HOT int64_t camera_axis(const lumo_raster_view *v, const lumo_q16_16 p[3], int i)
{
    return lumo_round_shift(((int64_t)p[0] - v->eye[0]) * v->rot[i][0] + ((int64_t)p[1] - v->eye[1]) * v->rot[i][1]
                                + ((int64_t)p[2] - v->eye[2]) * v->rot[i][2],
                            LUMO_Q14_SHIFT);
}

/* lumo_raster_to_camera, inlined into the per-vertex transform (a call a
 * vertex was 0.4 M instructions a frame of the 48k dragon, round five);
 * the three axes written out: GCC -O2 kept a loop (and c in memory), 0.5 M
 * a frame (round five part two). */
LUMO_RASTER_HOT void to_camera(const lumo_raster_view *v, const lumo_q16_16 p[3], int64_t c[3])
{
#if defined(__OPTIMIZE_SIZE__)
    /* -Os: a loop, one use of lumo_round_shift, which -Os then inlines
     * (written out, three calls to it: +27 instructions a pixel of the
     * board's shadowed per-pixel frame, whose lookups call this) */
    int i;

    for (i = 0; i < 3; i++)
        c[i] = camera_axis(v, p, i);
#else
    c[0] = camera_axis(v, p, 0);
    c[1] = camera_axis(v, p, 1);
    c[2] = camera_axis(v, p, 2);
#endif
}

void lumo_raster_to_camera(const lumo_raster_view *v, const lumo_q16_16 p[3], int64_t c[3])
{
    to_camera(v, p, c);
}

/* The exposed radiance of a vertex capped at 2^30 (64 x white, far past
 * code 255): every value a Gouraud run interpolates then lies in [0, 2^30]
 * (raster_span.c). Called three times, not from a loop (which GCC -O2
 * kept: 3 instructions a channel and vertex, round five part two). */
LUMO_RASTER_HOT int32_t exposed_capped(lumo_uq16_16 radiance, lumo_uq16_16 exposure)
{
    uint64_t e = lumo_raster_exposed64(radiance, exposure);   /* lumo_raster_exposed's cap is above 2^30 */

    return e > ((uint64_t)1 << 30) ? (1 << 30) : (int32_t)e;
}

void lumo_raster_transform_vertex(const lumo_raster_view *v, const lumo_raster_scene *s,
                                  const lumo_raster_mesh *m, uint32_t index,
                                  lumo_raster_vertex *out)
{
    const lumo_q16_16 *p = &m->pos[3 * (size_t)index];
    const lumo_q1_14 *n = &m->normal[3 * (size_t)index];
    const lumo_q1_14 *rho = m->albedo ? &m->albedo[3 * (size_t)index] : m->mesh_albedo;
    int64_t c[3];
    int i;

    to_camera(v, p, c);
    out->clip[0] = lumo_sat_i32(lumo_round_shift(c[0] * v->cot_half, 16));
    out->clip[1] = lumo_sat_i32(lumo_round_shift(c[1] * v->cot_half, 16));
    out->clip[2] = lumo_sat_i32(c[2]);
    for (i = 0; i < LUMO_RASTER_MAX_VARYINGS; i++)
        out->var[i] = 0;
    if (s->flags & LUMO_RASTER_PER_PIXEL) {
        for (i = 0; i < 3; i++) {
            out->var[i] = p[i];
            out->var[3 + i] = n[i];
            out->var[6 + i] = rho[i];
        }
        if (m->indirect) {
            const lumo_uq16_16 *ind = &m->indirect[6 * (size_t)index + (faces_away(v, p, n) ? 3 : 0)];
            for (i = 0; i < 3; i++)
                out->var[9 + i] = ind[i] > (uint32_t)INT32_MAX ? INT32_MAX : (int32_t)ind[i];
        }
    } else {
        lumo_uq16_16 l[3];
        const lumo_uq16_16 ex = s->exposure;   /* once: out's stores could alias *s */
        const lumo_uq16_16 *lit = l;
        if (m->lit)
            lit = &m->lit[6 * (size_t)index + (faces_away(v, p, n) ? 3 : 0)];
        else
            light_side(s, p, n, faces_away(v, p, n), rho, l);
        out->var[0] = exposed_capped(lit[0], ex);
        out->var[1] = exposed_capped(lit[1], ex);
        out->var[2] = exposed_capped(lit[2], ex);
    }
    out->outcode = outcode(v, out);
    out->screen[0] = out->screen[1] = 0;
    out->q = 0;
    if (out->outcode == 0) {
        screen_vertex sv;
        project(v, out, &sv);
        out->screen[0] = sv.x;
        out->screen[1] = sv.y;
        out->q = sv.q;
    }
}

/* 1 when the eye sees the side of p opposite to n. */
static int faces_away(const lumo_raster_view *v, const lumo_q16_16 p[3], const lumo_q1_14 n[3])
{
    /* the three terms written out: GCC -O2 kept a loop (3 instructions a
     * term and vertex, round five part two) */
    int64_t d = ((int64_t)v->eye[0] - p[0]) * n[0] + ((int64_t)v->eye[1] - p[1]) * n[1]
              + ((int64_t)v->eye[2] - p[2]) * n[2];

    return d < 0;
}

/* Surfaces are two-sided (docs/scene-format.md): the shading normal is
 * turned towards the viewer. out may alias n. */
void lumo_raster_face_viewer(const lumo_raster_view *v, const lumo_q16_16 p[3],
                             const lumo_q1_14 n[3], lumo_q1_14 out[3])
{
    int away = faces_away(v, p, n), i;

    for (i = 0; i < 3; i++)
        out[i] = (lumo_q1_14)(away ? -n[i] : n[i]);
}

/* Radiance of the side of p facing n (back: -n): the one lighting of a
 * vertex, per frame or once into a mesh's `lit`. */
static void light_side(const lumo_raster_scene *s, const lumo_q16_16 p[3], const lumo_q1_14 n[3],
                       int back, const lumo_q1_14 rho[3], lumo_uq16_16 out[3])
{
    lumo_uq16_16 e[3];
    lumo_q1_14 nf[3];
    int i;

    for (i = 0; i < 3; i++)
        nf[i] = (lumo_q1_14)(back ? -n[i] : n[i]);
    lumo_raster_irradiance(s, p, nf, e);
    lumo_raster_radiance(e, rho, out);
}

size_t lumo_raster_lit_bytes(uint32_t vertex_count)
{
    return lumo_size_mul(lumo_size_mul(vertex_count, 6), sizeof(lumo_uq16_16));
}

/* At most LUMO_MAX_LIGHTS lights, and every axis within +-1 (a unit
 * vector's components are): the shading's 32-bit dot products of an axis
 * with a light vector of 15-bit components rely on it (a spot axis of
 * 1.9 overflowed one; fuzz_raster). */
static int lights_ok(const lumo_raster_scene *s)
{
    uint32_t i;
    int k;

    if (s->light_count > LUMO_MAX_LIGHTS || (s->light_count && !s->lights))
        return 0;
    for (i = 0; i < s->light_count; i++)
        for (k = 0; k < 3; k++)
            if (s->lights[i].dir[k] > LUMO_Q14_ONE || s->lights[i].dir[k] < -LUMO_Q14_ONE)
                return 0;
    return 1;
}

lumo_status lumo_raster_light_vertices(const lumo_raster_scene *s, const lumo_raster_mesh *m,
                                       lumo_uq16_16 *lit)
{
    uint32_t i;

    if (!s || !m || (m->vertex_count && (!lit || !m->pos || !m->normal)))
        return LUMO_ERR_ARG;
    if (!lights_ok(s))
        return LUMO_ERR_RANGE;
    for (i = 0; i < m->vertex_count; i++) {
        const lumo_q16_16 *p = &m->pos[3 * (size_t)i];
        const lumo_q1_14 *n = &m->normal[3 * (size_t)i];
        const lumo_q1_14 *rho = m->albedo ? &m->albedo[3 * (size_t)i] : m->mesh_albedo;
        light_side(s, p, n, 0, rho, &lit[6 * (size_t)i]);
        light_side(s, p, n, 1, rho, &lit[6 * (size_t)i + 3]);
    }
    return LUMO_OK;
}

lumo_status lumo_raster_indirect_vertices(const lumo_raster_scene *s, const lumo_raster_mesh *m,
                                          lumo_uq16_16 *ind)
{
    uint32_t i;
    int k;

    if (!s || !m || !s->indirect || (m->vertex_count && (!ind || !m->pos || !m->normal)))
        return LUMO_ERR_ARG;
    for (i = 0; i < m->vertex_count; i++) {
        const lumo_q16_16 *p = &m->pos[3 * (size_t)i];
        lumo_q1_14 n[3], back[3];
        for (k = 0; k < 3; k++) {
            n[k] = m->normal[3 * (size_t)i + (size_t)k];
            back[k] = (lumo_q1_14)-n[k];
        }
        s->indirect(s->indirect_ctx, p, n, &ind[6 * (size_t)i]);
        s->indirect(s->indirect_ctx, p, back, &ind[6 * (size_t)i + 3]);
    }
    return LUMO_OK;
}

size_t lumo_raster_cache_bytes(uint32_t vertex_count)
{
    return lumo_size_mul(vertex_count, sizeof(lumo_raster_vertex));
}

static lumo_status check_inputs(const lumo_raster_view *v, const lumo_raster_scene *s,
                                const lumo_raster_mesh *m)
{
    if (!v || !s || !m)
        return LUMO_ERR_ARG;
    if ((m->vertex_count && (!m->pos || !m->normal)) || (m->tri_count && !m->tris))
        return LUMO_ERR_ARG;
    if (!lights_ok(s))
        return LUMO_ERR_RANGE;
    if (v->znear <= 0 || v->width == 0 || v->height == 0)
        return LUMO_ERR_RANGE;
    return LUMO_OK;
}

lumo_status lumo_raster_prepare(const lumo_raster_view *v, const lumo_raster_scene *s,
                                const lumo_raster_mesh *m, lumo_raster_vertex *cache)
{
    lumo_status st = check_inputs(v, s, m);
    uint32_t i;

    if (st)
        return st;
    if (!cache && m->vertex_count)
        return LUMO_ERR_ARG;
    for (i = 0; i < m->vertex_count; i++)
        lumo_raster_transform_vertex(v, s, m, i, &cache[i]);
    return LUMO_OK;
}

/* ---- clipping ------------------------------------------------------------ */

/* Signed distance of a clip-space vertex to plane k (inside when >= 0):
 * the near plane w >= znear, then |x| and |y| within the guard band,
 * |x_c * H * 8 / w| <= GUARD_PX * 16  <=>  2 * GUARD_PX * w -+ x_c * H >= 0.
 * Inlined: outcode's loop over the planes then folds the switch away (a
 * call per plane and vertex was 3 % of a frame of small triangles). */
LUMO_RASTER_HOT int64_t plane_dist(const lumo_raster_view *view, int k, const lumo_raster_vertex *v)
{
    int64_t g = (int64_t)2 * GUARD_PX * v->clip[2];
    int64_t h = view->height;

    switch (k) {
    case 0:  return (int64_t)v->clip[2] - view->znear;
    case 1:  return g - (int64_t)v->clip[0] * h;
    case 2:  return g + (int64_t)v->clip[0] * h;
    case 3:  return g - (int64_t)v->clip[1] * h;
    default: return g + (int64_t)v->clip[1] * h;
    }
}

/* The five planes written out: GCC -O2 kept the loop over them (0.09 M
 * instructions a frame of the 48k dragon, round five part two). */
static unsigned outcode(const lumo_raster_view *view, const lumo_raster_vertex *v)
{
    return (unsigned)(plane_dist(view, 0, v) < 0) | (unsigned)(plane_dist(view, 1, v) < 0) << 1
         | (unsigned)(plane_dist(view, 2, v) < 0) << 2 | (unsigned)(plane_dist(view, 3, v) < 0) << 3
         | (unsigned)(plane_dist(view, 4, v) < 0) << 4;
}

/* The point where the segment from the inside vertex a (da >= 0) to the
 * outside vertex b (db < 0) meets the plane. Always computed from the inside
 * end, so the two triangles sharing an edge get the very same point. */
static void intersect(const lumo_raster_vertex *a, int64_t da, const lumo_raster_vertex *b,
                      int64_t db, unsigned nvar, lumo_raster_vertex *out)
{
    uint64_t num = (uint64_t)da, den = (uint64_t)da + (uint64_t)(-db);
    int64_t t;
    unsigned i;

    while (den >= ((uint64_t)1 << 32)) {   /* keep t * (b - a) within 64 bits */
        num >>= 1;
        den >>= 1;
    }
    t = (int64_t)((num << 30) / den);      /* Q0.30 in [0, 1] */
    for (i = 0; i < 3; i++)
        out->clip[i] = lumo_sat_i32(a->clip[i] + lumo_round_shift(((int64_t)b->clip[i] - a->clip[i]) * t, 30));
    for (i = 0; i < nvar; i++)
        out->var[i] = lumo_sat_i32(a->var[i] + lumo_round_shift(((int64_t)b->var[i] - a->var[i]) * t, 30));
}

/* Sutherland-Hodgman against one plane; returns the new vertex count. */
static int clip_plane(const draw_ctx *c, int k, const lumo_raster_vertex *in, int n,
                      lumo_raster_vertex *out)
{
    int i, m = 0;

    for (i = 0; i < n; i++) {
        const lumo_raster_vertex *a = &in[i], *b = &in[(i + 1) % n];
        int64_t da = plane_dist(c->view, k, a), db = plane_dist(c->view, k, b);
        if (da >= 0)
            out[m++] = *a;
        if (da >= 0 && db < 0)
            intersect(a, da, b, db, c->nvar, &out[m++]);
        else if (da < 0 && db >= 0)
            intersect(b, db, a, da, c->nvar, &out[m++]);
    }
    return m;
}

/* ---- triangle setup and scan ---------------------------------------------- */

static int32_t clamp_sub(int64_t v)
{
    const int64_t lim = (int64_t)1 << 18;
    return (int32_t)(v > lim ? lim : v < -lim ? -lim : v);
}

static int64_t div_round(int64_t n, int64_t d)   /* d > 0 */
{
    return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

/* Inlined (LUMO_RASTER_HOT) into the per-vertex transform and the clipped
 * path: 74.1 -> 73.7 M instructions a frame of the 48k dragon (round five). */
LUMO_RASTER_HOT void project(const lumo_raster_view *view, const lumo_raster_vertex *v, screen_vertex *s)
{
    int64_t w = v->clip[2] < view->znear ? view->znear : v->clip[2];
    int64_t h8 = (int64_t)view->height * 8;
    int64_t q = (((int64_t)view->znear << 30) + w / 2) / w;

    s->x = clamp_sub((int64_t)view->width * 8 + div_round((int64_t)v->clip[0] * h8, w));
    s->y = clamp_sub(h8 - div_round((int64_t)v->clip[1] * h8, w));
    s->q = (uint32_t)(q > ((int64_t)1 << 30) ? ((int64_t)1 << 30) : q);
    s->var = v->var;
}

/* One screen triangle: dropped when degenerate or a culled back face,
 * else put in the order the edge functions want (positive area) and drawn;
 * tri is reordered in place. Inlined into its two callers (raster_peers:
 * 71.57 -> 71.34 M a frame, round five). */
LUMO_RASTER_HOT void draw_tri(const draw_ctx *c, screen_vertex tri[3])
{
    int64_t area = ((int64_t)tri[1].x - tri[0].x) * ((int64_t)tri[2].y - tri[0].y)
                 - ((int64_t)tri[1].y - tri[0].y) * ((int64_t)tri[2].x - tri[0].x);

    if (area == 0)
        return;
    /* Front faces are counter-clockwise with y up, so negative here. */
    if (area > 0 && (c->scene->flags & LUMO_RASTER_CULL_BACK)) {
        if (c->stats)
            c->stats->tris_culled++;
        return;
    }
    if (area < 0) {              /* the edge functions want positive area */
        screen_vertex tmp = tri[1];
        tri[1] = tri[2];
        tri[2] = tmp;
        area = -area;
    }
    lumo_raster_triangle(c, tri, area);
}

/* Draw a convex screen polygon (a clipped triangle) as a fan. */
static void draw_fan(const draw_ctx *c, const screen_vertex *s, int n)
{
    int i;

    for (i = 1; i + 1 < n; i++) {
        screen_vertex tri[3];
        tri[0] = s[0];
        tri[1] = s[i];
        tri[2] = s[i + 1];
        draw_tri(c, tri);
    }
}

static void screen_of(const lumo_raster_vertex *v, screen_vertex *s)
{
    s->x = v->screen[0];
    s->y = v->screen[1];
    s->q = v->q;
    s->var = v->var;
}

/* A triangle whose vertices need no clipping: already projected, and
 * dropped at once when its rows miss the band (the common case of band
 * rendering: each band costs little more than this test per triangle). */
static int misses_band(const lumo_raster_target *t, const lumo_raster_vertex *a, const lumo_raster_vertex *b,
                       const lumo_raster_vertex *d)
{
    int32_t lo = a->screen[1], hi = a->screen[1];

    if (b->screen[1] < lo) lo = b->screen[1];
    if (d->screen[1] < lo) lo = d->screen[1];
    if (b->screen[1] > hi) hi = b->screen[1];
    if (d->screen[1] > hi) hi = d->screen[1];
    /* rows whose centres 16 y + 8 lie in [lo, hi] */
    return hi < 16 * (int32_t)t->band_y + 8 || lo > 16 * ((int32_t)t->band_y + t->band_rows - 1) + 8;
}

/* The test is skipped for a target holding the whole frame (the span code
 * drops a triangle above or below it): 1 M instructions a frame of 48k
 * small triangles (round five). */
static void draw_unclipped(const draw_ctx *c, const lumo_raster_vertex *a,
                           const lumo_raster_vertex *b, const lumo_raster_vertex *d)
{
    const lumo_raster_target *t = c->target;
    screen_vertex s[3];

    if (t->band_rows != t->height && misses_band(t, a, b, d))
        return;
    screen_of(a, &s[0]);
    screen_of(b, &s[1]);
    screen_of(d, &s[2]);
    draw_tri(c, s);
}

/* A triangle that crosses a clip plane: clipped, projected, drawn as a fan.
 * Its own function: the unclipped triangles (nearly all) then do not set up
 * its 1.2 KB of polygon buffers (0.9 M instructions a frame of the 48k
 * dragon, round five). */
LUMO_RASTER_APART void draw_clipped(const draw_ctx *c, const lumo_raster_vertex *a, const lumo_raster_vertex *b,
                         const lumo_raster_vertex *d)
{
    lumo_raster_vertex buf[2][MAX_POLY];
    screen_vertex s[MAX_POLY];
    unsigned out = a->outcode | b->outcode | d->outcode;
    int n = 3, cur = 0, k;

    buf[0][0] = *a;
    buf[0][1] = *b;
    buf[0][2] = *d;
    if (c->stats)
        c->stats->tris_clipped++;
    for (k = 0; k < CLIP_PLANES && n >= 3; k++) {
        if (!(out & (1u << k)))
            continue;
        n = clip_plane(c, k, buf[cur], n, buf[cur ^ 1]);
        cur ^= 1;
    }
    if (n < 3)
        return;
    for (k = 0; k < n; k++)
        project(c->view, &buf[cur][k], &s[k]);
    draw_fan(c, s, n);
}

static void draw_triangle(const draw_ctx *c, const lumo_raster_vertex *a,
                          const lumo_raster_vertex *b, const lumo_raster_vertex *d)
{
    unsigned oa = a->outcode, ob = b->outcode, od = d->outcode;

    if (oa & ob & od)
        return;                              /* all outside one plane */
    if ((oa | ob | od) == 0)
        draw_unclipped(c, a, b, d);
    else
        draw_clipped(c, a, b, d);
}

/* A triangle's three indices tested together, one branch (raster_peers:
 * 72.10 -> 71.95 M instructions a frame of 48k triangles, round five). */
static lumo_status check_indices(const lumo_raster_mesh *m)
{
    const uint32_t n = m->vertex_count, *ix = m->tris;
    uint32_t i;

    for (i = 0; i < m->tri_count; i++, ix += 3)
        if ((ix[0] >= n) | (ix[1] >= n) | (ix[2] >= n))
            return LUMO_ERR_RANGE;
    return LUMO_OK;
}

/* Without a cache: each triangle transforms its three vertices (the same
 * bytes: lumo_raster_transform_vertex is a pure function). */
static void draw_mesh_uncached(const draw_ctx *c, const lumo_raster_mesh *m)
{
    uint32_t i;
    int k;

    for (i = 0; i < m->tri_count; i++) {
        const uint32_t *tri = &m->tris[3 * (size_t)i];
        lumo_raster_vertex tv[3];
        for (k = 0; k < 3; k++)
            lumo_raster_transform_vertex(c->view, c->scene, m, tri[k], &tv[k]);
        draw_triangle(c, &tv[0], &tv[1], &tv[2]);
    }
}

/* The cached loop apart from the uncached one: no test per triangle and
 * no 228-byte frame of transformed vertices. */
static void draw_mesh(const draw_ctx *c, const lumo_raster_mesh *m, const lumo_raster_vertex *cache)
{
    const uint32_t *tri = m->tris, *end = tri + 3 * (size_t)m->tri_count;

    if (!cache) {
        draw_mesh_uncached(c, m);
        return;
    }
    for (; tri != end; tri += 3)
        draw_triangle(c, &cache[tri[0]], &cache[tri[1]], &cache[tri[2]]);
}

/* 1 when no depth entry of the band is set (nothing drawn since the clear). */
static int depth_clear(const lumo_raster_target *t)
{
    size_t i, n = (size_t)t->width * t->band_rows;

    if (t->depth_bits == 16) {
        const uint16_t *d = (const uint16_t *)t->depth;
        for (i = 0; i < n; i++)
            if (d[i])
                return 0;
    } else {
        const uint32_t *d = (const uint32_t *)t->depth;
        for (i = 0; i < n; i++)
            if (d[i])
                return 0;
    }
    return 1;
}

/* Every set depth one step nearer the far plane (0 stays "clear"): after
 * the depth-only pass each pixel holds its nearest fragment's depth D, and
 * the colour pass's test (depth > stored) now passes at D - 1 for exactly
 * that fragment, the first one to reach D, as drawing without the pass
 * would keep; it stores D again, so later fragments at D fail as before. */
static void depth_step_back(const lumo_raster_target *t)
{
    size_t i, n = (size_t)t->width * t->band_rows;

    if (t->depth_bits == 16) {
        uint16_t *d = (uint16_t *)t->depth;
        for (i = 0; i < n; i++)
            d[i] = (uint16_t)(d[i] - (d[i] != 0));
    } else {
        uint32_t *d = (uint32_t *)t->depth;
        for (i = 0; i < n; i++)
            d[i] -= (d[i] != 0);
    }
}

/* LUMO_RASTER_DEPTH_FIRST: the mesh's depth alone first (exact per-pixel
 * depth: the colour pass computes the very same values), so that the
 * colour pass shades each pixel once. Only into a clear band: there the
 * picture is byte for byte the one drawn without it. */
static void depth_first(draw_ctx *c, const lumo_raster_mesh *m, const lumo_raster_vertex *cache)
{
    lumo_raster_stats *stats = c->stats;

    if (!(c->scene->flags & LUMO_RASTER_DEPTH_FIRST) || !(c->scene->flags & LUMO_RASTER_PER_PIXEL)
        || !depth_clear(c->target))
        return;
    /* the caller's context switched to laying depth and back (no copy: the
     * board's stack peak is in this call chain) */
    c->stats = NULL;
    c->laying = 1;
    draw_mesh(c, m, cache);
    c->stats = stats;
    c->laying = 0;
    depth_step_back(c->target);
}

lumo_status lumo_raster_draw_stats(const lumo_raster_view *v, const lumo_raster_scene *s,
                                   const lumo_raster_mesh *m, const lumo_raster_vertex *cache,
                                   lumo_raster_target *t, lumo_raster_stats *stats)
{
    draw_ctx c;
    lumo_status st = check_inputs(v, s, m);

    if (st)
        return st;
    st = lumo_raster_target_check(t);
    if (st)
        return st;
    if (t->width != v->width || t->height != v->height)
        return LUMO_ERR_RANGE;
    st = check_indices(m);
    if (st)
        return st;
    c.view = v;
    c.scene = s;
    c.target = t;
    c.stats = stats;
    c.nvar = lumo_raster_varyings(s, m);
    c.depth_only = 0;
    c.laying = 0;
    if (stats) {
        lumo_raster_stats zero = {0, 0, 0, 0, 0, 0};
        *stats = zero;
        stats->tris_in = m->tri_count;
    }
    depth_first(&c, m, cache);
    draw_mesh(&c, m, cache);
    return LUMO_OK;
}

/* Depth only, both sides, no varyings: a shadow map face (raster_shadow.c).
 * The per-pixel flag keeps transform_vertex from lighting the vertices. */
lumo_status lumo_raster_draw_depth(const lumo_raster_view *v, const lumo_raster_mesh *m,
                                   lumo_raster_target *t)
{
    static const lumo_raster_scene depth_scene = {NULL, 0, NULL, NULL, 0, LUMO_RASTER_PER_PIXEL};
    draw_ctx c;
    lumo_status st = check_inputs(v, &depth_scene, m);

    if (st)
        return st;
    if (t->width != v->width || t->height != v->height || t->depth_bits != 16 || !t->depth)
        return LUMO_ERR_RANGE;
    st = check_indices(m);
    if (st)
        return st;
    c.view = v;
    c.scene = &depth_scene;
    c.target = t;
    c.stats = NULL;
    c.nvar = 0;
    c.depth_only = 1;
    c.laying = 0;
    draw_mesh(&c, m, NULL);
    return LUMO_OK;
}

lumo_status lumo_raster_draw(const lumo_raster_view *v, const lumo_raster_scene *s,
                             const lumo_raster_mesh *m, const lumo_raster_vertex *cache,
                             lumo_raster_target *t)
{
    return lumo_raster_draw_stats(v, s, m, cache, t, NULL);
}
