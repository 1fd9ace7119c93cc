/*
 * scene_payload.c — the scene payloads of docs/package-format.md (INFO with
 * its lights, MESH, IVGD), decoded from their bytes wherever they came from:
 * a package chunk or a network message. Validates everything it reads;
 * integer code only; no allocation.
 */
#include <string.h>
#include "lumo/scene.h"
#include "lumo/wire.h"

#define INFO_FIXED   80u
#define LIGHT_SIZE   72u
#define MESH_HEAD    16u
#define MESH_VERTEX  36u
#define MESH_TRI     12u
#define IVGD_SIZE    48u
#define ORDR_HEAD    8u
#define ORDR_STEP    12u

/* ---- binary32 fields to fixed point --------------------------------------- */

static lumo_status rd_fixed(const uint8_t *p, unsigned frac, int32_t *out)
{
    return lumo_f32bits_to_fixed(lumo_wire_le32(p), frac, out);
}

static lumo_status rd_q16_3(const uint8_t *p, lumo_q16_16 out[3])
{
    int32_t v[3];
    unsigned i;
    for (i = 0; i < 3; i++) {
        lumo_status st = rd_fixed(p + 4 * i, LUMO_Q16_SHIFT, &v[i]);
        if (st)
            return st;
    }
    for (i = 0; i < 3; i++)
        out[i] = v[i];
    return LUMO_OK;
}

/* A Q1.14 value in [lo, 1] (unit vector components, albedo, cosines). */
static lumo_status rd_q14(const uint8_t *p, int32_t lo, lumo_q1_14 *out)
{
    int32_t v;
    lumo_status st = rd_fixed(p, LUMO_Q14_SHIFT, &v);
    if (st)
        return st;
    if (v < lo || v > LUMO_Q14_ONE)
        return LUMO_ERR_RANGE;
    *out = (lumo_q1_14)v;
    return LUMO_OK;
}

static lumo_status rd_q14_3(const uint8_t *p, int32_t lo, lumo_q1_14 out[3])
{
    lumo_q1_14 v[3];
    unsigned i;
    for (i = 0; i < 3; i++) {
        lumo_status st = rd_q14(p + 4 * i, lo, &v[i]);
        if (st)
            return st;
    }
    for (i = 0; i < 3; i++)
        out[i] = v[i];
    return LUMO_OK;
}

static lumo_status check_info(const uint8_t *p, size_t len)
{
    if (!p)
        return LUMO_ERR_ARG;
    if (len < INFO_FIXED)
        return LUMO_ERR_TRUNCATED;
    if (lumo_wire_le32(p + 4) > LUMO_MAX_LIGHTS)
        return LUMO_ERR_LIMIT;
    if (len != INFO_FIXED + lumo_wire_le32(p + 4) * LIGHT_SIZE)
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

/* v scaled down by a power of two until every component is below 2^14
 * in magnitude: squares of cross products (< 3 * 2^58) and products of
 * squared lengths (< 9 * 2^56) then fit in int64. */
static void small_vec(const int64_t v[3], int64_t out[3])
{
    int64_t m = 0;
    unsigned i, shift = 0;
    for (i = 0; i < 3; i++)
        m |= v[i] < 0 ? -v[i] : v[i];
    while ((m >> shift) >= ((int64_t)1 << 14))
        shift++;
    for (i = 0; i < 3; i++)
        out[i] = v[i] / ((int64_t)1 << shift);
}

/* A camera that cannot be placed: eye on the target, up zero or along the
 * view (no frame to draw; the rasterizer would divide by zero). Along the
 * view means sin(angle)^2 <= 2^-20 (0.06 degrees): |d x u|^2 <= |d|^2 |u|^2 / 2^20. */
static int camera_degenerate(const lumo_pkg_info *r)
{
    int64_t d[3], u[3], a[3], b[3], c[3], cc, dd, uu;
    unsigned i;
    for (i = 0; i < 3; i++) {
        d[i] = (int64_t)r->target[i] - r->eye[i];
        u[i] = r->up[i];
    }
    small_vec(d, a);
    small_vec(u, b);
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
    cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    dd = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    uu = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
    return cc <= (dd * uu) >> 20;
}

lumo_status lumo_scene_info_decode(const uint8_t *p, size_t len, lumo_pkg_info *out)
{
    lumo_pkg_info r;
    int32_t fovy;
    lumo_status st;
    if (!out)
        return LUMO_ERR_ARG;
    st = check_info(p, len);
    if (st)
        return st;
    r.mesh_count = lumo_wire_le32(p);
    r.light_count = lumo_wire_le32(p + 4);
    r.triangle_count = lumo_wire_le32(p + 8);
    st = rd_q16_3(p + 16, r.bmin);
    if (!st) st = rd_q16_3(p + 28, r.bmax);
    if (!st) st = rd_q16_3(p + 40, r.eye);
    if (!st) st = rd_q16_3(p + 52, r.target);
    if (!st) st = rd_q16_3(p + 64, r.up);
    if (!st) st = rd_fixed(p + 76, LUMO_Q16_SHIFT, &fovy);
    if (st)
        return st;
    if (fovy <= 0 || fovy >= LUMO_Q16_FROM_INT(180))
        return LUMO_ERR_RANGE;
    r.fovy_deg = fovy;
    if (camera_degenerate(&r))
        return LUMO_ERR_RANGE;
    *out = r;
    return LUMO_OK;
}

lumo_status lumo_scene_light_decode(const uint8_t *p, size_t len, uint32_t index, lumo_pkg_light *out)
{
    uint32_t kind;
    lumo_pkg_light l;
    int32_t w[3];
    lumo_status st;
    unsigned i;
    if (!out)
        return LUMO_ERR_ARG;
    st = check_info(p, len);
    if (st)
        return st;
    if (index >= lumo_wire_le32(p + 4))
        return LUMO_ERR_RANGE;
    p += INFO_FIXED + (size_t)index * LIGHT_SIZE;
    kind = lumo_wire_le32(p);
    if (kind > LUMO_LIGHT_AREA)
        return LUMO_ERR_UNSUPPORTED;
    l.kind = (lumo_light_kind)kind;
    st = rd_q16_3(p + 4, l.pos);
    if (!st) st = rd_q14_3(p + 16, -LUMO_Q14_ONE, l.dir);
    if (!st) st = rd_q16_3(p + 28, l.u);
    if (!st) st = rd_q16_3(p + 40, l.v);
    if (!st) st = rd_fixed(p + 52, LUMO_Q16_SHIFT, &l.half_angle_deg);
    if (!st) st = rd_q14(p + 56, -LUMO_Q14_ONE, &l.cos_half);
    for (i = 0; !st && i < 3; i++) {
        st = rd_fixed(p + 60 + 4 * i, LUMO_Q16_SHIFT, &w[i]);
        if (!st && w[i] < 0)
            st = LUMO_ERR_RANGE;
    }
    if (st)
        return st;
    for (i = 0; i < 3; i++)
        l.power[i] = (lumo_uq16_16)w[i];
    *out = l;
    return LUMO_OK;
}

/* ---- meshes ------------------------------------------------------------- */

static lumo_status check_mesh(const uint8_t *p, size_t len, lumo_pkg_mesh_info *mi)
{
    if (!p)
        return LUMO_ERR_ARG;
    if (len < MESH_HEAD)
        return LUMO_ERR_TRUNCATED;
    mi->flags = lumo_wire_le32(p);
    mi->nverts = lumo_wire_le32(p + 4);
    mi->ntris = lumo_wire_le32(p + 8);
    if (mi->flags & ~LUMO_PKG_MESH_EMITTER)
        return LUMO_ERR_UNSUPPORTED;
    if ((uint64_t)len != MESH_HEAD + (uint64_t)mi->nverts * MESH_VERTEX + (uint64_t)mi->ntris * MESH_TRI)
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

lumo_status lumo_scene_mesh_info_decode(const uint8_t *p, size_t len, lumo_pkg_mesh_info *out)
{
    lumo_pkg_mesh_info mi;
    lumo_status st;
    if (!out)
        return LUMO_ERR_ARG;
    st = check_mesh(p, len, &mi);
    if (st)
        return st;
    *out = mi;
    return LUMO_OK;
}

/* One vertex record: position, normal, albedo; NULL outputs only validate. */
static lumo_status mesh_vertex(const uint8_t *p, lumo_q16_16 *pos, lumo_q1_14 *nrm, lumo_q1_14 *alb)
{
    lumo_q16_16 tp[3];
    lumo_q1_14 tn[3], ta[3];
    lumo_status st = rd_q16_3(p, tp);
    if (!st) st = rd_q14_3(p + 12, -LUMO_Q14_ONE, tn);
    if (!st) st = rd_q14_3(p + 24, 0, ta);
    if (st)
        return st;
    if (pos)
        memcpy(pos, tp, sizeof tp);
    if (nrm)
        memcpy(nrm, tn, sizeof tn);
    if (alb)
        memcpy(alb, ta, sizeof ta);
    return LUMO_OK;
}

lumo_status lumo_scene_mesh_decode(const uint8_t *p, size_t len, lumo_q16_16 *pos, lumo_q1_14 *nrm,
                                   lumo_q1_14 *albedo, uint32_t *tris)
{
    const uint8_t *t;
    lumo_pkg_mesh_info mi;
    uint32_t i;
    lumo_status st;
    if (!pos)
        return LUMO_ERR_ARG;
    st = check_mesh(p, len, &mi);
    if (st)
        return st;
    p += MESH_HEAD;
    t = p + (size_t)mi.nverts * MESH_VERTEX;
    /* Pass 1 validates everything, pass 2 writes: outputs stay untouched on error. */
    for (i = 0; i < mi.nverts; i++)
        if ((st = mesh_vertex(p + (size_t)i * MESH_VERTEX, NULL, NULL, NULL)) != LUMO_OK)
            return st;
    for (i = 0; i < 3u * mi.ntris; i++)
        if (lumo_wire_le32(t + 4 * (size_t)i) >= mi.nverts)
            return LUMO_ERR_RANGE;
    for (i = 0; i < mi.nverts; i++)
        mesh_vertex(p + (size_t)i * MESH_VERTEX, pos + 3 * (size_t)i, nrm ? nrm + 3 * (size_t)i : NULL,
                    albedo ? albedo + 3 * (size_t)i : NULL);
    for (i = 0; tris && i < 3u * mi.ntris; i++)
        tris[i] = lumo_wire_le32(t + 4 * (size_t)i);
    return LUMO_OK;
}

/* ---- IVG ---------------------------------------------------------------- */

lumo_status lumo_scene_ivg_desc_decode(const uint8_t *p, size_t len, lumo_ivg_desc *out)
{
    uint32_t i;
    lumo_ivg_desc d;
    lumo_status st;
    if (!out || !p)
        return LUMO_ERR_ARG;
    if (len != IVGD_SIZE)
        return len < IVGD_SIZE ? LUMO_ERR_TRUNCATED : LUMO_ERR_CORRUPT;
    st = rd_q16_3(p + 8, d.bmin);
    if (!st)
        st = rd_q16_3(p + 20, d.bmax);
    if (st)
        return st;
    for (i = 0; i < 3; i++) {
        d.dims[i] = (uint16_t)lumo_wire_le16(p + 2 * i);
        if (d.dims[i] < LUMO_IVG_MIN_DIM || d.dims[i] > LUMO_IVG_MAX_DIM || d.bmax[i] <= d.bmin[i])
            return LUMO_ERR_RANGE;
    }
    *out = d;
    return LUMO_OK;
}


/* ---- ORDR ---------------------------------------------------------------------- */

lumo_status lumo_scene_order_decode(const uint8_t *p, size_t len, uint32_t mesh_count, lumo_scene_order *out)
{
    lumo_scene_order o;
    uint64_t need;
    uint32_t i;
    if (!out || !p)
        return LUMO_ERR_ARG;
    if (len < ORDR_HEAD)
        return LUMO_ERR_TRUNCATED;
    o.prefix = lumo_wire_le32(p);
    o.cycle = lumo_wire_le32(p + 4);
    o.steps = p + ORDR_HEAD;
    need = ORDR_HEAD + ORDR_STEP * ((uint64_t)o.prefix + o.cycle);
    if ((uint64_t)len != need)
        return (uint64_t)len < need ? LUMO_ERR_TRUNCATED : LUMO_ERR_CORRUPT;
    for (i = 0; i < o.prefix + o.cycle; i++) {
        const uint8_t *s = o.steps + (size_t)i * ORDR_STEP;
        uint32_t mesh = lumo_wire_le32(s + 4);
        if (s[0] > LUMO_CHANNEL_LIGHTING)
            return LUMO_ERR_UNSUPPORTED;
        if (lumo_wire_le32(s + 8) == 0 || (s[0] == LUMO_CHANNEL_LIGHTING && mesh != 0))
            return LUMO_ERR_CORRUPT;
        if (s[0] == LUMO_CHANNEL_GEOMETRY && mesh >= mesh_count)
            return LUMO_ERR_RANGE;
    }
    *out = o;
    return LUMO_OK;
}

lumo_status lumo_scene_order_step(const lumo_scene_order *o, uint32_t i, lumo_scene_step *out)
{
    const uint8_t *s;
    if (!o || !out)
        return LUMO_ERR_ARG;
    if (i >= o->prefix + o->cycle)
        return LUMO_ERR_RANGE;
    s = o->steps + (size_t)i * ORDR_STEP;
    out->channel = s[0];
    out->mesh = lumo_wire_le32(s + 4);
    out->amount = lumo_wire_le32(s + 8);
    return LUMO_OK;
}
