/*
 * raster_shadow.c — shadow maps drawn by the soft rasterizer itself, and
 * their lookup (docs/rasterizer.md "Shadows").
 *
 * A map is a set of depth-only faces seen from the light, drawn with the
 * very pipeline that draws frames (lumo_raster_draw_depth: same clipping,
 * fill rule and znear/w depth, 16 bits). A point light gets a cube of six
 * 90-degree faces; a spot one face over its cone; a directional light one
 * narrow perspective face from far up-light (the rasterizer has no
 * orthographic projection; 16 radii away the rays are within 3.6 degrees
 * of parallel). Every function is integer-only, so the visibility — and
 * with it every shadowed pixel — is bit-exact on every board.
 */
#include <string.h>
#include "raster_internal.h"

/* Normal offset and depth bias, in texel footprints at the point's
 * distance (Q4: 24/16 = 1.5 and 16/16 = 1). The normal offset moves the
 * point off its surface by more than the surface's depth spread over the
 * 2x2 filter (the footprint times the slope), so lit slopes do not
 * self-shadow (acne); the depth bias covers the 16-bit depth step and the
 * rasterization of the occluder between texel centres. Chosen on the
 * default scene and the test scene (tests/unit/test_raster_shadow.c):
 * smaller values show acne on the box's walls at 64^2, larger ones detach
 * the dragon's shadow from its feet by more than a texel. */
#define NORMAL_OFFSET_Q4 24
#define DEPTH_BIAS_Q4    16
/* A spot wider than this (half angle, degrees) gets a cube map. */
#define SPOT_MAX_HALF_DEG 75
/* Directional lights: the view's eye sits DIR_DISTANCE radii up-light. */
#define DIR_DISTANCE 16

unsigned lumo_raster_shadow_faces(const lumo_raster_light *l)
{
    if (!l)
        return 0;
    switch (l->kind) {
    case LUMO_LIGHT_POINT:
        return 6;
    case LUMO_LIGHT_SPOT:
        /* cos(75 deg) = 0.2588: a wider cone does not fit one face */
        return l->cos_cutoff < (lumo_q1_14)4240 ? 6 : 1;
    case LUMO_LIGHT_DIRECTIONAL:
        return 1;
    default:
        return 0;
    }
}

size_t lumo_raster_shadow_bytes(const lumo_raster_light *l, uint16_t size)
{
    unsigned faces = lumo_raster_shadow_faces(l);

    if (faces == 0 || size < LUMO_RASTER_SHADOW_MIN_SIZE || size > LUMO_MAX_FRAME_DIM)
        return 0;
    return (size_t)faces * size * size * sizeof(uint16_t);
}

/* Smallest whole degree d in [1, 89] whose cosine is <= c (Q1.14): the
 * cone's half angle rounded up, from the sine table (Q2.30). */
static int32_t half_angle_deg(lumo_q1_14 c)
{
    int32_t d;

    for (d = 1; d < 89; d++)
        if (lumo_raster_sin_deg[90 - d] <= (uint32_t)((int64_t)(c < 0 ? 0 : c) << 16))
            break;
    return d;
}

/* Smallest whole degree d whose sine is >= 1 / DIR_DISTANCE. */
static int32_t dir_half_angle_deg(void)
{
    int32_t d;

    for (d = 1; d < 89; d++)
        if (lumo_raster_sin_deg[d] >= ((uint32_t)1 << 30) / DIR_DISTANCE)
            break;
    return d;
}

static lumo_status face_view(lumo_raster_view *v, const lumo_q16_16 eye[3], const int32_t fwd[3],
                             const lumo_q16_16 up[3], int32_t fov_deg, lumo_q16_16 znear,
                             uint16_t size)
{
    lumo_raster_camera cam;
    int i;

    for (i = 0; i < 3; i++) {
        cam.eye[i] = eye[i];
        cam.target[i] = lumo_sat_i32((int64_t)eye[i] + fwd[i]);
        cam.up[i] = up[i];
    }
    cam.fovy_deg = LUMO_Q16_FROM_INT(fov_deg);
    cam.znear = znear;
    return lumo_raster_view_init(v, &cam, size, size);
}

/* Cube faces +x, -x, +y, -y, +z, -z: one metre along the axis. */
static lumo_status cube_views(lumo_raster_shadow *sh, const lumo_q16_16 pos[3], lumo_q16_16 znear)
{
    static const lumo_q16_16 up_y[3] = {0, LUMO_Q16_ONE, 0}, up_z[3] = {0, 0, LUMO_Q16_ONE};
    lumo_status st;
    int f;

    for (f = 0; f < 6; f++) {
        int32_t fwd[3] = {0, 0, 0};
        fwd[f / 2] = (f & 1) ? -LUMO_Q16_ONE : LUMO_Q16_ONE;
        st = face_view(&sh->face[f], pos, fwd, f / 2 == 1 ? up_z : up_y, 90, znear, sh->size);
        if (st)
            return st;
    }
    return LUMO_OK;
}

static void up_for(const lumo_q1_14 dir[3], lumo_q16_16 up[3])
{
    /* world y, or world x for a direction within 45 degrees of y */
    int steep = dir[1] > 11585 || dir[1] < -11585;

    up[0] = steep ? LUMO_Q16_ONE : 0;
    up[1] = steep ? 0 : LUMO_Q16_ONE;
    up[2] = 0;
}

static lumo_status spot_view(lumo_raster_shadow *sh, const lumo_raster_light *l, lumo_q16_16 znear)
{
    int32_t fwd[3];
    lumo_q16_16 up[3];
    int i;

    for (i = 0; i < 3; i++)
        fwd[i] = (int32_t)l->dir[i] * 4;                /* Q1.14 -> Q16.16 */
    up_for(l->dir, up);
    return face_view(&sh->face[0], l->pos, fwd, up, 2 * half_angle_deg(l->cos_cutoff) + 2, znear,
                     sh->size);
}

static lumo_status directional_view(lumo_raster_shadow *sh, const lumo_raster_light *l,
                                    const lumo_q16_16 centre[3], lumo_q16_16 radius)
{
    lumo_q16_16 eye[3], up[3];
    int32_t fwd[3];
    int64_t dist = (int64_t)radius * DIR_DISTANCE;
    int i;

    if (!centre || radius <= 0)
        return LUMO_ERR_ARG;
    if (dist > INT32_MAX)
        return LUMO_ERR_RANGE;                          /* the eye must stay in Q16.16 */
    for (i = 0; i < 3; i++) {
        int64_t e = centre[i] - lumo_round_shift(dist * l->dir[i], LUMO_Q14_SHIFT);
        if (e > INT32_MAX || e < INT32_MIN)
            return LUMO_ERR_RANGE;
        eye[i] = (lumo_q16_16)e;
        fwd[i] = (int32_t)l->dir[i] * 4;
    }
    up_for(l->dir, up);
    /* the bounding sphere starts DIR_DISTANCE - 1 radii away; one more
     * radius of margin for the normal offset */
    return face_view(&sh->face[0], eye, fwd, up, 2 * dir_half_angle_deg() + 2,
                     (lumo_q16_16)(dist / DIR_DISTANCE * (DIR_DISTANCE - 2)), sh->size);
}

lumo_status lumo_raster_shadow_views(lumo_raster_shadow *sh, const lumo_raster_light *l, uint16_t size,
                                     const lumo_q16_16 centre[3], lumo_q16_16 radius, lumo_q16_16 znear)
{
    lumo_status st;

    if (!sh || !l)
        return LUMO_ERR_ARG;
    if (lumo_raster_shadow_bytes(l, size) == 0 || znear < 0)
        return LUMO_ERR_RANGE;
    memset(sh, 0, sizeof *sh);
    sh->size = size;
    sh->faces = (uint8_t)lumo_raster_shadow_faces(l);
    if (znear == 0)
        znear = LUMO_RASTER_SHADOW_ZNEAR;
    if (l->kind == LUMO_LIGHT_DIRECTIONAL)
        st = directional_view(sh, l, centre, radius);
    else if (sh->faces == 6)
        st = cube_views(sh, l->pos, znear);
    else
        st = spot_view(sh, l, znear);
    if (st)
        sh->faces = 0;
    return st;
}

lumo_status lumo_raster_shadow_init(lumo_raster_shadow *sh, const lumo_raster_light *l,
                                    uint16_t size, uint16_t *depth, size_t bytes,
                                    const lumo_q16_16 centre[3], lumo_q16_16 radius,
                                    lumo_q16_16 znear)
{
    size_t need = lumo_raster_shadow_bytes(l, size);
    lumo_status st;

    if (!sh || !l || !depth)
        return LUMO_ERR_ARG;
    if (need == 0 || bytes < need || znear < 0)
        return LUMO_ERR_RANGE;
    st = lumo_raster_shadow_views(sh, l, size, centre, radius, znear);
    if (st)
        return st;
    sh->depth = depth;
    memset(depth, 0, need);
    return LUMO_OK;
}

lumo_status lumo_raster_shadow_draw(lumo_raster_shadow *sh, const lumo_raster_mesh *m)
{
    lumo_raster_target t;
    unsigned f;
    lumo_status st;

    if (!sh || !m || !sh->depth || sh->faces == 0)
        return LUMO_ERR_ARG;
    memset(&t, 0, sizeof t);
    t.width = t.height = t.band_rows = sh->size;
    t.format = LUMO_PIXEL_XRGB8888;
    t.depth_bits = 16;
    for (f = 0; f < sh->faces; f++) {
        t.depth = sh->depth + (size_t)f * sh->size * sh->size;
        t.color = t.depth;                      /* never written in depth-only drawing */
        t.color_stride = (uint32_t)sh->size * 4u;
        st = lumo_raster_draw_depth(&sh->face[f], m, &t);
        if (st)
            return st;
    }
    return LUMO_OK;
}

/* ---- lookup ---------------------------------------------------------------- */

/* The cube face whose 90-degree frustum holds direction d: its major axis. */
static unsigned cube_face(const int64_t d[3])
{
    int64_t a[3];
    unsigned k = 0;
    int i;

    for (i = 0; i < 3; i++)
        a[i] = d[i] < 0 ? -d[i] : d[i];
    if (a[1] > a[k]) k = 1;
    if (a[2] > a[k]) k = 2;
    return 2 * k + (d[k] < 0);
}

/* floor(v / 16) and the remainder in [0, 15], without shifting negatives. */
static int64_t floor_div16(int64_t v, unsigned *frac)
{
    int64_t q = v >= 0 ? v / 16 : -((-v + 15) / 16);

    *frac = (unsigned)(v - 16 * q);
    return q;
}

static int64_t div_round_pos(int64_t n, int64_t d)   /* d > 0 */
{
    return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

/* 1 when the stored texel s does not hide a point at distance wb (Q16.16)
 * along the face's axis: wb <= znear / q with q the centre of s's 16-bit
 * step (Q0.30), tested as wb * q <= znear * 2^30 (no division). */
static unsigned texel_lit(uint16_t s, int64_t wb, lumo_q16_16 znear)
{
    uint64_t q = ((uint64_t)s << 14) + ((uint64_t)1 << 13);

    return s == 0 || (uint64_t)wb * q <= (uint64_t)znear << 30;
}

static unsigned texel_at(const lumo_raster_shadow *sh, const uint16_t *map, int64_t i, int64_t j,
                         int64_t wb, lumo_q16_16 znear)
{
    int64_t n = sh->size - 1;

    if (i < 0) i = 0;
    if (i > n) i = n;
    if (j < 0) j = 0;
    if (j > n) j = n;
    return texel_lit(map[(size_t)j * sh->size + (size_t)i], wb, znear);
}

uint32_t lumo_raster_shadow_visibility(const lumo_raster_shadow *sh, const lumo_q16_16 p[3],
                                       const lumo_q1_14 n[3])
{
    const lumo_raster_view *v;
    const uint16_t *map;
    lumo_q16_16 po[3];
    int64_t d[3], c[3], foot, x, y, s16 = (int64_t)sh->size * 16, wb;
    unsigned f = 0, fu, fv;
    int i;

    if (!sh || sh->faces == 0 || !sh->depth)
        return 256;                                       /* no map (or views only): lit */
    if (sh->faces == 6) {
        for (i = 0; i < 3; i++)
            d[i] = (int64_t)p[i] - sh->face[0].eye[i];
        f = cube_face(d);
    }
    v = &sh->face[f];
    map = sh->depth + (size_t)f * sh->size * sh->size;
    lumo_raster_to_camera(v, p, c);
    if (c[2] < v->znear)
        return 256;                                       /* before the near plane: no caster */
    /* one texel's footprint at this distance: 2 w / (size cot(fov/2)) */
    foot = ((c[2] * 2) << 16) / ((int64_t)sh->size * v->cot_half);
    if (foot > ((int64_t)1 << 30))
        foot = (int64_t)1 << 30;                          /* 16384 units: keeps the products in 64 bits */
    for (i = 0; i < 3; i++)
        po[i] = lumo_sat_i32((int64_t)p[i] + lumo_round_shift(n[i] * foot * NORMAL_OFFSET_Q4,
                                                              LUMO_Q14_SHIFT + 4));
    lumo_raster_to_camera(v, po, c);
    if (c[2] < v->znear)
        return 256;
    /* the face's screen position in 1/16 texel, as project() in raster_draw.c */
    x = s16 / 2 + div_round_pos(lumo_round_shift(c[0] * v->cot_half, 16) * (s16 / 2), c[2]) - 8;
    y = s16 / 2 - div_round_pos(lumo_round_shift(c[1] * v->cot_half, 16) * (s16 / 2), c[2]) - 8;
    if (sh->faces == 1 && (x < -8 || y < -8 || x > s16 - 8 || y > s16 - 8))
        return 256;                                       /* outside the one face: not mapped */
    wb = c[2] - ((foot * DEPTH_BIAS_Q4) >> 4);
    if (wb <= 0)
        return 256;
    x = floor_div16(x, &fu);                              /* texel left of / above, and */
    y = floor_div16(y, &fv);                              /* the 1/16 weights */
    return (16 - fu) * (16 - fv) * texel_at(sh, map, x, y, wb, v->znear)
         + fu * (16 - fv) * texel_at(sh, map, x + 1, y, wb, v->znear)
         + (16 - fu) * fv * texel_at(sh, map, x, y + 1, wb, v->znear)
         + fu * fv * texel_at(sh, map, x + 1, y + 1, wb, v->znear);
}
