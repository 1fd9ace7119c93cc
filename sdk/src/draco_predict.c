/*
 * draco_predict.c — prediction schemes and their transforms (paper §3;
 * libdraco compression/attributes/prediction_schemes). The stream holds
 * corrections; prediction + correction, folded by the transform, gives the
 * portable values. All arithmetic is integer, as in libdraco (int64
 * intermediates, wrapping adds where libdraco adds as unsigned).
 */
#include "draco_internal.h"

#define LD_PRED_DIFFERENCE 0
#define LD_PRED_PARALLELOGRAM 1
#define LD_PRED_CONSTRAINED_MULTI 4
#define LD_PRED_TEX_COORDS_PORTABLE 5
#define LD_PRED_GEOMETRIC_NORMAL 6
#define LD_XFORM_WRAP 1
#define LD_XFORM_OCTAHEDRON 2
#define LD_XFORM_OCTAHEDRON_CANON 3
#define LD_MAX_PARALLELOGRAMS 4

/* The hot schemes are kept out of ld_pred_compute (LD_NOINLINE): inlined
 * there, each loop's registers were allocated together with every other
 * scheme's and a change to one moved spills into another. */

static inline int32_t ld_wrap_add(int32_t a, int32_t b)
{
    return (int32_t)((uint32_t)a + (uint32_t)b);
}

/* libdraco's int64 geometry arithmetic can overflow on crafted positions;
 * lumo wraps (two's complement, what libdraco does in practice on x86) so
 * the result stays defined and identical for every valid stream. */
static inline int64_t ld_abs64(int64_t v) { return (int64_t)(v < 0 ? 0u - (uint64_t)v : (uint64_t)v); }
static inline int64_t ld_mul64(int64_t a, int64_t b) { return (int64_t)((uint64_t)a * (uint64_t)b); }
static inline int64_t ld_add64(int64_t a, int64_t b) { return (int64_t)((uint64_t)a + (uint64_t)b); }
static inline int64_t ld_sub64(int64_t a, int64_t b) { return (int64_t)((uint64_t)a - (uint64_t)b); }
static inline int64_t ld_div64(int64_t a, int64_t b)
{
    if (b == 0)
        return 0;
    if (b == -1)
        return (int64_t)(0u - (uint64_t)a);  /* INT64_MIN / -1 wraps */
    return a / b;
}

/* ---- transforms ------------------------------------------------------------- */

static lumo_status ld_wrap_read(ld_pred *p, ld_buf *b)
{
    uint32_t lo, hi;
    lumo_status st;
    if ((st = ld_u32(b, &lo)) || (st = ld_u32(b, &hi)))
        return st;
    p->min_value = (int32_t)lo;
    p->max_value = (int32_t)hi;
    if (p->min_value > p->max_value ||
        (int64_t)p->max_value - p->min_value >= INT32_MAX)
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

static lumo_status ld_octahedron_read(ld_pred *p, ld_buf *b)
{
    uint32_t maxq, center;
    unsigned bits = 0;
    lumo_status st;
    if ((st = ld_u32(b, &maxq)) || (st = ld_u32(b, &center)))
        return st;
    if ((int32_t)maxq <= 0 || (maxq & 1u) == 0)
        return LUMO_ERR_CORRUPT;
    while (bits < 32 && (maxq >> bits) > 1u)
        ++bits;  /* most significant bit */
    bits += 1;
    if (bits < 2 || bits > 30)
        return LUMO_ERR_CORRUPT;
    p->oct_bits = bits;
    p->oct_max_q = (int32_t)((1u << bits) - 1u);
    p->oct_center = (p->oct_max_q - 1) / 2;
    return LUMO_OK;
}

static lumo_status ld_transform_read(ld_pred *p, ld_buf *b)
{
    if (p->transform == LD_XFORM_WRAP)
        return ld_wrap_read(p, b);
    if (p->transform == LD_XFORM_OCTAHEDRON_CANON)
        return ld_octahedron_read(p, b);
    return LUMO_ERR_UNSUPPORTED;
}

/* Wrap transform of one value: clamp the prediction into [lo, hi], add the
 * correction, fold back by dif = hi - lo + 1, all in wrapping 32-bit
 * arithmetic as libdraco does. The one copy every wrap path calls.
 * Computed on u = v - lo (mod 2^32): lo <= v <= hi exactly when u <= hi -
 * lo, one unsigned test, so a prediction and a result in range (nearly
 * every value) cost a test each and no clamp or fold. */
static inline int32_t ld_wrap_value(int32_t pred, int32_t corr, int32_t lo, int32_t hi,
                                    uint32_t dif)
{
    const uint32_t range = dif - 1u;
    uint32_t u = (uint32_t)pred - (uint32_t)lo;
    int32_t v;
    if (u > range)  /* clamp */
        u = pred > hi ? range : 0u;
    u += (uint32_t)corr;
    v = (int32_t)(u + (uint32_t)lo);
    if (u <= range)
        return v;
    return (int32_t)((uint32_t)v + (v > hi ? 0u - dif : dif));  /* fold */
}

static inline void ld_wrap_original(const ld_pred *p, const int32_t *pred, const int32_t *corr,
                                    int32_t *out)
{
    const uint32_t dif = (uint32_t)p->max_value - (uint32_t)p->min_value + 1u;
    unsigned c;
    for (c = 0; c < p->comps; ++c)
        out[c] = ld_wrap_value(pred[c], corr[c], p->min_value, p->max_value, dif);
}

/* Octahedron diamond folding (OctahedronToolBox::InvertDiamond), in the
 * unsigned arithmetic libdraco uses. */
static void ld_invert_diamond(int32_t center, int32_t *s, int32_t *t)
{
    int32_t ss, st;
    uint32_t cs, ct, us, ut;
    if (*s >= 0 && *t >= 0) {
        ss = 1; st = 1;
    } else if (*s <= 0 && *t <= 0) {
        ss = -1; st = -1;
    } else {
        ss = *s > 0 ? 1 : -1;
        st = *t > 0 ? 1 : -1;
    }
    cs = (uint32_t)(ss * center);
    ct = (uint32_t)(st * center);
    us = (uint32_t)*s;
    ut = (uint32_t)*t;
    us = us + us - cs;
    ut = ut + ut - ct;
    if (ss * st >= 0) {
        uint32_t tmp = us;
        us = 0u - ut;
        ut = 0u - tmp;
    } else {
        uint32_t tmp = us;
        us = ut;
        ut = tmp;
    }
    us += cs;
    ut += ct;
    *s = (int32_t)us / 2;
    *t = (int32_t)ut / 2;
}

static int32_t ld_mod_max(const ld_pred *p, int32_t x)
{
    if (x > p->oct_center)
        return x - p->oct_max_q;
    if (x < -p->oct_center)
        return x + p->oct_max_q;
    return x;
}

static inline int32_t ld_neg(int32_t v) { return (int32_t)(0u - (uint32_t)v); }

static void ld_rotate(int32_t *x, int32_t *y, int count)
{
    int32_t a = *x, b = *y;
    switch (count) {
    case 1: *x = b; *y = ld_neg(a); break;
    case 2: *x = ld_neg(a); *y = ld_neg(b); break;
    case 3: *x = ld_neg(b); *y = a; break;
    default: break;
    }
}

static int ld_rotation_count(int32_t x, int32_t y)
{
    if (x == 0)
        return y == 0 ? 0 : (y > 0 ? 3 : 1);
    if (x > 0)
        return y >= 0 ? 2 : 1;
    return y <= 0 ? 0 : 3;
}

/* PredictionSchemeNormalOctahedronCanonicalizedDecodingTransform */
static void ld_octa_original(const ld_pred *p, const int32_t *pred, const int32_t *corr,
                             int32_t *out)
{
    const int32_t c = p->oct_center;
    int32_t s = ld_wrap_add(pred[0], ld_neg(c)), t = ld_wrap_add(pred[1], ld_neg(c)), os, ot;
    int in_diamond = (s < 0 ? 0u - (uint32_t)s : (uint32_t)s) +
                     (t < 0 ? 0u - (uint32_t)t : (uint32_t)t) <= (uint32_t)c;
    int bottom_left, rot;
    if (!in_diamond)
        ld_invert_diamond(c, &s, &t);
    bottom_left = (s == 0 && t == 0) || (s < 0 && t <= 0);
    rot = ld_rotation_count(s, t);
    if (!bottom_left)
        ld_rotate(&s, &t, rot);
    os = ld_mod_max(p, ld_wrap_add(s, corr[0]));
    ot = ld_mod_max(p, ld_wrap_add(t, corr[1]));
    if (!bottom_left)
        ld_rotate(&os, &ot, (4 - rot) % 4);
    if (!in_diamond)
        ld_invert_diamond(c, &os, &ot);
    out[0] = ld_wrap_add(os, c);
    out[1] = ld_wrap_add(ot, c);
}

static inline void ld_original(const ld_pred *p, const int32_t *pred, const int32_t *corr, int32_t *out)
{
    if (p->transform == LD_XFORM_WRAP)
        ld_wrap_original(p, pred, corr, out);
    else
        ld_octa_original(p, pred, corr, out);
}

/* ---- scheme data ---------------------------------------------------------------- */

static lumo_status ld_read_bits(ld_buf *b, ld_mem *m, ld_need *k, uint32_t n, uint8_t **out)
{
    ld_rabs start, r;
    uint8_t *bits;
    uint32_t i;
    lumo_status st = ld_rabs_start(&start, b);
    if (st)
        return st;
    if (!m) {
        ld_need_tmp(k, n, 1);
        *out = NULL;
        return LUMO_OK;
    }
    bits = ld_tmp(m, n, 1);
    if (!bits)
        return LUMO_ERR_NOMEM;
    r = start;  /* a local copy: byte stores may alias anything reachable */
    for (i = 0; i < n; ++i)
        bits[i] = (uint8_t)ld_rabs_bit(&r);
    *out = bits;
    return LUMO_OK;
}

/* Mesh schemes need the mesh's traversal data; without it (sequential
 * connectivity) libdraco falls back to delta coding, and so does any
 * method number it does not know. */
static int ld_effective_method(const ld_pred *p)
{
    int m = p->method;
    if (m == LD_PRED_PARALLELOGRAM || m == LD_PRED_CONSTRAINED_MULTI ||
        m == LD_PRED_TEX_COORDS_PORTABLE || m == LD_PRED_GEOMETRIC_NORMAL ||
        m == 2 || m == 3)
        return p->seq->ct ? m : LD_PRED_DIFFERENCE;
    return LD_PRED_DIFFERENCE;
}

lumo_status ld_pred_decode_data(ld_pred *p, ld_buf *b, ld_mem *m, ld_need *k)
{
    lumo_status st;
    uint32_t i, n;
    int method = ld_effective_method(p);
    if (p->transform == LD_XFORM_OCTAHEDRON_CANON && p->comps != 2)
        return LUMO_ERR_CORRUPT;
    switch (method) {
    case LD_PRED_DIFFERENCE:
    case LD_PRED_PARALLELOGRAM:
        return ld_transform_read(p, b);
    case LD_PRED_CONSTRAINED_MULTI:
        for (i = 0; i < LD_MAX_PARALLELOGRAMS; ++i) {
            if ((st = ld_varint32(b, &n)))
                return st;
            if (n > p->seq->ct->num_corners)
                return LUMO_ERR_CORRUPT;
            p->num_crease[i] = n;
            if (n && (st = ld_rabs_start(&p->crease[i], b)))
                return st;
        }
        return ld_transform_read(p, b);
    case LD_PRED_TEX_COORDS_PORTABLE:
        if ((st = ld_u32(b, &n)))
            return st;
        if ((int32_t)n < 0 || n > p->seq->num_entries)
            return LUMO_ERR_CORRUPT;
        p->num_orient = n;
        if ((st = ld_read_bits(b, m, k, n, &p->orient)))
            return st;
        /* bit 0 flips the running orientation, starting from "true" */
        for (i = 0; i < n && p->orient; ++i) {
            uint8_t last = i ? p->orient[i - 1] : 1u;
            p->orient[i] = p->orient[i] ? last : (uint8_t)!last;
        }
        return ld_transform_read(p, b);
    case LD_PRED_GEOMETRIC_NORMAL:
        if (p->transform != LD_XFORM_OCTAHEDRON_CANON)
            return LUMO_ERR_UNSUPPORTED;
        if ((st = ld_transform_read(p, b)))
            return st;
        return ld_rabs_start(&p->flip, b);
    default:
        return LUMO_ERR_UNSUPPORTED;  /* pre-2.2 schemes */
    }
}

/* ---- schemes ------------------------------------------------------------------ */

/* Delta coding with the wrap transform, any component count, on locals;
 * three components (positions) keep the entry before in registers. */
static LD_NOINLINE lumo_status ld_delta_wrap(const ld_pred *p, int32_t *v, uint32_t n)
{
    const int32_t lo = p->min_value, hi = p->max_value;
    const uint32_t dif = (uint32_t)hi - (uint32_t)lo + 1u, k = p->comps;
    const size_t total = (size_t)n * k;
    size_t i;
    if (k == 3u) {
        int32_t p0 = 0, p1 = 0, p2 = 0;
        for (i = 0; i < total; i += 3u) {
            v[i] = p0 = ld_wrap_value(p0, v[i], lo, hi, dif);
            v[i + 1u] = p1 = ld_wrap_value(p1, v[i + 1u], lo, hi, dif);
            v[i + 2u] = p2 = ld_wrap_value(p2, v[i + 2u], lo, hi, dif);
        }
        return LUMO_OK;
    }
    for (i = 0; i < k && i < total; ++i)
        v[i] = ld_wrap_value(0, v[i], lo, hi, dif);
    for (; i < total; ++i)
        v[i] = ld_wrap_value(v[i - k], v[i], lo, hi, dif);
    return LUMO_OK;
}

static lumo_status ld_delta(ld_pred *p, int32_t *v, uint32_t n)
{
    static const int32_t zero[LUMO_DRACO_MAX_COMPONENTS];
    const unsigned k = p->comps;
    uint32_t i;
    ld_original(p, zero, v, v);
    for (i = 1; i < n; ++i)
        ld_original(p, v + (size_t)(i - 1) * k, v + (size_t)i * k, v + (size_t)i * k);
    return LUMO_OK;
}

static int32_t ld_value_of_vertex(const ld_pred *p, uint32_t v)
{
    return v == LD_INV ? -1 : p->seq->vertex_to_value[v];
}

/* Constrained multi-parallelogram: average the parallelograms around the
 * vertex that the encoder did not flag as crossing a crease. The fan walk
 * (swing left, then right from the start) is inlined on local copies of
 * the corner table: this is the hottest loop at -cl 9/10. */
typedef struct ld_fan {
    const uint32_t *c2v;
    uint32_t vmask;
    const uint32_t *opp32;    /* NULL: packed (LUMO_DRACO_LEAN) */
    ld_pot_near opp;
    int packed;               /* opp32 == NULL; the hot loops take it as a constant */
    const uint8_t *seam;
    const int32_t *v2v;
} ld_fan;

static LD_FORCE_INLINE uint32_t ld_fan_opp(const ld_fan *f, uint32_t c, int packed)
{
    if (f->seam && ld_seam(f->seam, c))
        return LD_INV;
    return packed ? ld_pot_near_opp(f->opp, c) : f->opp32[c];
}

static LD_FORCE_INLINE uint32_t ld_fan_vert(const ld_fan *f, uint32_t c, int packed)
{
    return packed ? f->c2v[c] & f->vmask : f->c2v[c];
}

/* ComputeParallelogramPrediction: the vertex at `oci` (valid corner)
 * reflected across the edge of corners na, nb: na + nb - oci, when all
 * three vertices are decoded before `entry` (unvisited, -1, entries become
 * huge and fail the test). libdraco sums in int64 and truncates; uint32
 * arithmetic is the same. libdraco takes the edge's corners in the
 * opposite face (next and prev of oci); across an edge that is not a seam
 * the corners of the other side hold the same two vertices, and the sum
 * is all the prediction uses, so a fan walker passes its own corners and
 * needs no % 3. */
static LD_FORCE_INLINE int ld_para(const ld_fan *f, uint32_t entry, uint32_t oci, uint32_t na,
                                   uint32_t nb, const int32_t *data, unsigned k, int32_t *out,
                                   int packed)
{
    const uint32_t eo = (uint32_t)f->v2v[ld_fan_vert(f, oci, packed)];
    const uint32_t en = (uint32_t)f->v2v[ld_fan_vert(f, na, packed)];
    const uint32_t ep = (uint32_t)f->v2v[ld_fan_vert(f, nb, packed)];
    uint32_t c;
    if (eo >= entry || en >= entry || ep >= entry)
        return 0;
    if (k == 3u) {  /* a constant in the fast instances: no loop */
        const int32_t *po = data + 3u * (size_t)eo, *pn = data + 3u * (size_t)en,
                      *pp = data + 3u * (size_t)ep;
        out[0] = (int32_t)((uint32_t)pn[0] + (uint32_t)pp[0] - (uint32_t)po[0]);
        out[1] = (int32_t)((uint32_t)pn[1] + (uint32_t)pp[1] - (uint32_t)po[1]);
        out[2] = (int32_t)((uint32_t)pn[2] + (uint32_t)pp[2] - (uint32_t)po[2]);
        return 1;
    }
    for (c = 0; c < k; ++c)
        out[c] = (int32_t)((uint32_t)data[(size_t)en * k + c] + (uint32_t)data[(size_t)ep * k + c] -
                           (uint32_t)data[(size_t)eo * k + c]);
    return 1;
}

/* Across the edge opposite corner ci (nci, pci: its next and previous). */
static LD_FORCE_INLINE int ld_fan_parallelogram(const ld_fan *f, uint32_t entry, uint32_t ci,
                                                uint32_t nci, uint32_t pci, const int32_t *data,
                                                unsigned k, int32_t *out, int packed)
{
    const uint32_t oci = ld_fan_opp(f, ci, packed);
    return oci != LD_INV && ld_para(f, entry, oci, nci, pci, data, k, out, packed);
}

/* Entry i's parallelogram: across from its traversal corner, or, after
 * ld_eb_release_table, from the opposite corner kept in its place. */
static LD_FORCE_INLINE int ld_entry_parallelogram(const ld_pred *p, const ld_fan *f, uint32_t i,
                                                  const int32_t *data, unsigned k, int32_t *out,
                                                  int packed)
{
    const uint32_t c = p->seq->value_to_corner[i];
    if (p->seq->opposites)  /* the table is gone, the faces plain again */
        return c != LD_INV && ld_para(f, i, c, ld_next_v(c), ld_prev_v(c), data, k, out, 0);
    return ld_fan_parallelogram(f, i, c, ld_next_v(c), ld_prev_v(c), data, k, out, packed);
}

static void ld_fan_init(ld_fan *f, const ld_pred *p, int seams)
{
    const ld_ct *ct = p->seq->ct;
    f->c2v = ct->c2v;
    f->vmask = ct->vmask;
    f->opp32 = ct->opp32;
    f->opp = ld_pot_near_of(&ct->opp);
    f->packed = ld_ct_packed(ct);
    f->seam = seams ? ct->seam : NULL;
    f->v2v = p->seq->vertex_to_value;
}

/* The wrap transform's bounds, copied into a local by the loops: the value
 * stores could alias ld_pred's fields and force a reload per value. */
typedef struct ld_wrap {
    int32_t lo, hi;
    uint32_t dif;
} ld_wrap;

static inline ld_wrap ld_wrap_of(const ld_pred *p)
{
    ld_wrap w;
    w.lo = p->min_value;
    w.hi = p->max_value;
    w.dif = (uint32_t)w.hi - (uint32_t)w.lo + 1u;
    return w;
}

/* Three values through the wrap transform, predicted by p0, p1, p2. */
static inline void ld_wrap3(ld_wrap w, int32_t *dst, int32_t p0, int32_t p1, int32_t p2)
{
    dst[0] = ld_wrap_value(p0, dst[0], w.lo, w.hi, w.dif);
    dst[1] = ld_wrap_value(p1, dst[1], w.lo, w.hi, w.dif);
    dst[2] = ld_wrap_value(p2, dst[2], w.lo, w.hi, w.dif);
}

/* The common case, three components with the wrap transform; `fast`: no
 * seams, a constant after inlining. The first entry is predicted by 0,
 * the others by their parallelogram, else by the entry before. The
 * prediction goes to the transform in scalars: a pointer choosing between
 * two arrays would keep it in memory. */
static LD_FORCE_INLINE void ld_parallelogram3_run(const ld_pred *p, int32_t *v, uint32_t n,
                                                  int fast, int packed)
{
    const ld_wrap w = ld_wrap_of(p);
    ld_fan f;
    uint32_t i;
    ld_fan_init(&f, p, !fast);
    if (n)
        ld_wrap3(w, v, 0, 0, 0);
    for (i = 1; i < n; ++i) {
        int32_t *dst = v + 3u * (size_t)i, pred[3];
        if (ld_entry_parallelogram(p, &f, i, v, 3u, pred, packed))
            ld_wrap3(w, dst, pred[0], pred[1], pred[2]);
        else
            ld_wrap3(w, dst, dst[-3], dst[-2], dst[-1]);
    }
}

static LD_NOINLINE lumo_status ld_parallelogram_wrap3(const ld_pred *p, int32_t *v, uint32_t n)
{
    const int packed = ld_ct_packed(p->seq->ct);
    if (!p->seq->ct->seam && !packed)
        ld_parallelogram3_run(p, v, n, 1, 0);
    else if (!p->seq->ct->seam)
        ld_parallelogram3_run(p, v, n, 1, 1);
    else
        ld_parallelogram3_run(p, v, n, 0, packed);
    return LUMO_OK;
}

static lumo_status ld_parallelogram_all(ld_pred *p, int32_t *v, uint32_t n)
{
    static const int32_t zero[LUMO_DRACO_MAX_COMPONENTS];
    int32_t pred[LUMO_DRACO_MAX_COMPONENTS];
    const unsigned k = p->comps;
    ld_fan f;
    uint32_t i;
    ld_fan_init(&f, p, 1);
    ld_original(p, zero, v, v);
    for (i = 1; i < n; ++i) {
        int32_t *dst = v + (size_t)i * k;
        if (ld_entry_parallelogram(p, &f, i, v, k, pred, f.packed))
            ld_original(p, pred, dst, dst);
        else
            ld_original(p, dst - k, dst, dst);
    }
    return LUMO_OK;
}

/* The parallelograms around entry i's vertex, at most four: swing left
 * from its corner, then right from it when the left walk met a border
 * (libdraco's order). A swing crosses the edge from the vertex to a
 * neighbour, so the next face shares that neighbour: each step reads one
 * new neighbour's entry and carries the other (en, ep: the entries at the
 * corner's next and previous vertices), and the opposite corner of a
 * parallelogram is read only when both edge ends are decoded. */
static LD_FORCE_INLINE void ld_fan_para(const ld_fan *f, uint32_t i, uint32_t corner, uint32_t en,
                                        uint32_t ep, const int32_t *v, unsigned k,
                                        int32_t preds[][LUMO_DRACO_MAX_COMPONENTS], int *count,
                                        int packed)
{
    uint32_t oci, eo, c;
    if (en >= i || ep >= i)
        return;
    oci = ld_fan_opp(f, corner, packed);
    if (oci == LD_INV)
        return;
    eo = (uint32_t)f->v2v[ld_fan_vert(f, oci, packed)];
    if (eo >= i)
        return;
    if (k == 3u) {  /* a constant in the fast instances: no loop */
        const int32_t *po = v + 3u * (size_t)eo, *pn = v + 3u * (size_t)en,
                      *pp = v + 3u * (size_t)ep;
        int32_t *out = preds[*count];
        out[0] = (int32_t)((uint32_t)pn[0] + (uint32_t)pp[0] - (uint32_t)po[0]);
        out[1] = (int32_t)((uint32_t)pn[1] + (uint32_t)pp[1] - (uint32_t)po[1]);
        out[2] = (int32_t)((uint32_t)pn[2] + (uint32_t)pp[2] - (uint32_t)po[2]);
    } else {
        for (c = 0; c < k; ++c)
            preds[*count][c] = (int32_t)((uint32_t)v[(size_t)en * k + c] +
                                         (uint32_t)v[(size_t)ep * k + c] -
                                         (uint32_t)v[(size_t)eo * k + c]);
    }
    ++*count;
}

static LD_FORCE_INLINE uint32_t ld_fan_entry(const ld_fan *f, uint32_t c, int packed)
{
    return (uint32_t)f->v2v[ld_fan_vert(f, c, packed)];
}

/* The walk needs no guard against a cycle: the decoder sets opposites in
 * pairs of corners that had none (a new face's corners, and old corners
 * after ld_has_opp: ld_set_opp, ld_set_opp_new), so the opposite map is
 * injective, seams only cut it, and so is the swing
 * next(opp(next(c))). Iterating an injective map from `start` either stops
 * at a border or comes back to `start` itself (a first repeat elsewhere
 * would have two predecessors), which the loops test: at most one turn
 * of the fan, below num_corners steps, on any stream. */
static LD_FORCE_INLINE void ld_fan_walk(const ld_fan *f, uint32_t i, uint32_t start,
                                        const int32_t *v, unsigned k,
                                        int32_t preds[][LUMO_DRACO_MAX_COMPONENTS], int *count,
                                        int packed)
{
    const uint32_t pc0 = ld_prev_v(start), en0 = ld_fan_entry(f, ld_next_v(start), packed);
    uint32_t nc = ld_next_v(start), en = en0, ep = ld_fan_entry(f, pc0, packed), o;
    *count = 0;
    ld_fan_para(f, i, start, en, ep, v, k, preds, count, packed);
    for (;;) {  /* swing left: next(opp(next(c))); the new face's next vertex is ep's */
        if (*count == LD_MAX_PARALLELOGRAMS)
            return;
        o = ld_fan_opp(f, nc, packed);
        if (LD_UNLIKELY(o == LD_INV))
            break;
        if (o == pc0)  /* next(o) == start: the fan is closed */
            return;
        nc = ld_prev_v(o);
        en = ep;
        ep = ld_fan_entry(f, o, packed);
        /* the face's corner at the vertex, computed where the parallelogram needs it */
        ld_fan_para(f, i, ld_next_v(o), en, ep, v, k, preds, count, packed);
    }
    o = ld_fan_opp(f, pc0, packed);  /* swing right from the start */
    if (o == LD_INV)
        return;
    ep = en0;
    for (;;) {  /* prev(opp(prev(c))); the new face's previous vertex is en's */
        const uint32_t corner = ld_prev_v(o), pc = ld_next_v(o);
        en = ld_fan_entry(f, o, packed);
        ld_fan_para(f, i, corner, en, ep, v, k, preds, count, packed);
        if (*count == LD_MAX_PARALLELOGRAMS)
            return;
        o = ld_fan_opp(f, pc, packed);
        if (o == LD_INV || ld_prev_v(o) == start)
            return;
        ep = en;
    }
}

/* `fast`: three components, the wrap transform and no seams, constants
 * after inlining (positions at -cl 9/10); otherwise any attribute. Entry
 * 0 is predicted by 0; entry i by the mean of its fan's parallelograms
 * the crease flags keep, else by entry i - 1. The flags of one entry all
 * come from the context of its parallelogram count: its coder is held in
 * a local across them and its bound checked once. */
static LD_FORCE_INLINE lumo_status ld_multi_run(ld_pred *p, int32_t *v, uint32_t n, int fast,
                                                int packed)
{
    static const int32_t zero[LUMO_DRACO_MAX_COMPONENTS];
    int32_t preds[LD_MAX_PARALLELOGRAMS][LUMO_DRACO_MAX_COMPONENTS];
    uint32_t left[LD_MAX_PARALLELOGRAMS];   /* crease flags not yet read */
    ld_rabs crease[LD_MAX_PARALLELOGRAMS];  /* local: the value stores cannot alias */
    const uint32_t *v2c = p->seq->value_to_corner;
    const unsigned k = fast ? 3u : p->comps;
    const ld_wrap w = ld_wrap_of(p);
    ld_fan f;
    uint32_t i, c;
    ld_fan_init(&f, p, !fast);
    memcpy(crease, p->crease, sizeof crease);
    memcpy(left, p->num_crease, sizeof left);
    if (n == 0)
        return LUMO_OK;
    if (fast)
        ld_wrap3(w, v, 0, 0, 0);
    else
        ld_original(p, zero, v, v);
    for (i = 1; i < n; ++i) {
        int32_t *dst = v + (size_t)i * k, multi[LUMO_DRACO_MAX_COMPONENTS];
        int count = 0, used = 0, j;
        ld_fan_walk(&f, i, v2c[i], v, k, preds, &count, packed);
        for (c = 0; c < k; ++c)
            multi[c] = 0;
        if (count > 0) {
            const int ctx = count - 1;
            ld_rabs r = crease[ctx];
            if (left[ctx] < (uint32_t)count)
                return LUMO_ERR_CORRUPT;  /* more flags than the stream has */
            left[ctx] -= (uint32_t)count;
            for (j = 0; j < count; ++j) {
                if (ld_rabs_bit(&r))
                    continue;  /* across a crease */
                for (c = 0; c < k; ++c)
                    multi[c] = ld_wrap_add(multi[c], preds[j][c]);
                ++used;
            }
            crease[ctx] = r;
        }
        if (fast && used == 0)
            ld_wrap3(w, dst, dst[-3], dst[-2], dst[-1]);
        else if (fast)
            ld_wrap3(w, dst, multi[0] / used, multi[1] / used, multi[2] / used);
        else if (used == 0)
            ld_original(p, dst - k, dst, dst);
        else {
            for (c = 0; c < k; ++c)
                multi[c] /= used;
            ld_original(p, multi, dst, dst);
        }
    }
    return LUMO_OK;
}

static LD_NOINLINE lumo_status ld_multi_parallelogram(ld_pred *p, int32_t *v, uint32_t n)
{
    const int packed = ld_ct_packed(p->seq->ct);
    if (p->comps == 3 && p->transform == LD_XFORM_WRAP && !p->seq->ct->seam)
        return packed ? ld_multi_run(p, v, n, 1, 1) : ld_multi_run(p, v, n, 1, 0);
    return ld_multi_run(p, v, n, 0, packed);
}

/* The position at a corner: its point's position value. libdraco reads
 * the position of the texture coordinate's entry (its first point); every
 * corner of one vertex holds that vertex's position (positions are per
 * mesh vertex), so the corner's own point gives the same value without
 * the entry -> corner -> point steps. */
static LD_FORCE_INLINE void ld_corner_position(const ld_pred *p, uint32_t corner, int64_t out[3])
{
    const uint32_t point = p->seq->faces[corner] & p->seq->faces_mask;
    unsigned c;
    for (c = 0; c < 3; ++c)
        out[c] = lumo_draco_value(p->pos, point, c);
}

/* Bits of n (0 for 0): six halving steps. */
static unsigned ld_bit_length64(uint64_t n)
{
    unsigned len = 0;
    if (n >> 32) { len += 32; n >>= 32; }
    if (n >> 16) { len += 16; n >>= 16; }
    if (n >> 8) { len += 8; n >>= 8; }
    if (n >> 4) { len += 4; n >>= 4; }
    if (n >> 2) { len += 2; n >>= 2; }
    if (n >> 1) { len += 1; n >>= 1; }
    return len + (unsigned)n;
}

/* libdraco's IntSqrt (floor of the square root), the same Newton steps
 * from the same start: libdraco doubles r while quartering n down to
 * below 2, i.e. once for each i with n >= 2^(2i+1), so r = 2^k with
 * k = floor((L - 2) / 2) + 1 for an L-bit n >= 2 (1 below); computed from
 * L instead of up to 32 loop turns. */
static uint64_t ld_int_sqrt(uint64_t n)
{
    const unsigned len = ld_bit_length64(n);
    uint64_t r = len >= 2 ? (uint64_t)1 << ((len - 2) / 2 + 1) : 1u;
    if (n == 0)
        return 0;
    do {
        r = (r + n / r) / 2;
    } while (r * r > n);
    return r;
}

/* MeshPredictionSchemeTexCoordsPortablePredictor::ComputePredictedValue */
static lumo_status ld_tex_predict(ld_pred *p, uint32_t corner, const int32_t *data,
                                  int32_t id, int32_t out[2])
{
    const ld_ct *ct = p->seq->ct;
    const int32_t nid = ld_value_of_vertex(p, ld_vert(ct, ld_next_v(corner)));
    const int32_t pid = ld_value_of_vertex(p, ld_vert(ct, ld_prev_v(corner)));
    int32_t off;
    if (nid < 0 || pid < 0)
        return LUMO_ERR_CORRUPT;
    if (pid < id && nid < id) {
        int64_t nu = data[2 * nid], nv = data[2 * nid + 1];
        int64_t pu = data[2 * pid], pv = data[2 * pid + 1];
        int64_t tip[3], nx[3], pr[3], pn[3], cn[3], xpos[3], cx[3];
        uint64_t pn2, cx2, norm;
        int64_t dot, pnu, pnv, xu, xv, absmax, pn_absmax, cxu, cxv;
        unsigned c;
        if (pu == nu && pv == nv) {
            out[0] = (int32_t)pu;
            out[1] = (int32_t)pv;
            return LUMO_OK;
        }
        ld_corner_position(p, corner, tip);
        ld_corner_position(p, ld_next_v(corner), nx);
        ld_corner_position(p, ld_prev_v(corner), pr);
        for (c = 0; c < 3; ++c)
            pn[c] = pr[c] - nx[c];  /* int32 differences: no overflow */
        pn2 = (uint64_t)ld_add64(ld_add64(ld_mul64(pn[0], pn[0]), ld_mul64(pn[1], pn[1])),
                                 ld_mul64(pn[2], pn[2]));
        if (pn2 != 0) {
            for (c = 0; c < 3; ++c)
                cn[c] = tip[c] - nx[c];
            dot = ld_add64(ld_add64(ld_mul64(pn[0], cn[0]), ld_mul64(pn[1], cn[1])),
                           ld_mul64(pn[2], cn[2]));
            pnu = pu - nu;
            pnv = pv - nv;
            absmax = ld_abs64(nu) > ld_abs64(nv) ? ld_abs64(nu) : ld_abs64(nv);
            if ((uint64_t)absmax > (uint64_t)INT64_MAX / pn2)
                return LUMO_ERR_CORRUPT;
            xu = (int64_t)((uint64_t)nu * pn2 + (uint64_t)ld_mul64(dot, pnu));
            xv = (int64_t)((uint64_t)nv * pn2 + (uint64_t)ld_mul64(dot, pnv));
            pn_absmax = ld_abs64(pn[0]);
            if (ld_abs64(pn[1]) > pn_absmax) pn_absmax = ld_abs64(pn[1]);
            if (ld_abs64(pn[2]) > pn_absmax) pn_absmax = ld_abs64(pn[2]);
            if (pn_absmax <= 0 || dot > INT64_MAX / pn_absmax)
                return LUMO_ERR_CORRUPT;
            for (c = 0; c < 3; ++c) {
                xpos[c] = ld_add64(nx[c], ld_div64(ld_mul64(dot, pn[c]), (int64_t)pn2));
                cx[c] = ld_sub64(tip[c], xpos[c]);
            }
            cx2 = (uint64_t)ld_add64(ld_add64(ld_mul64(cx[0], cx[0]), ld_mul64(cx[1], cx[1])),
                                     ld_mul64(cx[2], cx[2]));
            norm = ld_int_sqrt(cx2 * pn2);
            cxu = (int64_t)((uint64_t)pnv * norm);
            cxv = (int64_t)((0u - (uint64_t)pnu) * norm);
            if (p->num_orient == 0)
                return LUMO_ERR_CORRUPT;
            if (p->orient[--p->num_orient]) {
                out[0] = (int32_t)ld_div64((int64_t)((uint64_t)xu + (uint64_t)cxu), (int64_t)pn2);
                out[1] = (int32_t)ld_div64((int64_t)((uint64_t)xv + (uint64_t)cxv), (int64_t)pn2);
            } else {
                out[0] = (int32_t)ld_div64((int64_t)((uint64_t)xu - (uint64_t)cxu), (int64_t)pn2);
                out[1] = (int32_t)ld_div64((int64_t)((uint64_t)xv - (uint64_t)cxv), (int64_t)pn2);
            }
            return LUMO_OK;
        }
    }
    off = 0;
    if (pid < id)
        off = pid * 2;
    if (nid < id) {
        off = nid * 2;
    } else if (id > 0) {
        off = (id - 1) * 2;
    } else {
        out[0] = out[1] = 0;
        return LUMO_OK;
    }
    out[0] = data[off];
    out[1] = data[off + 1];
    return LUMO_OK;
}

static lumo_status ld_tex_coords(ld_pred *p, int32_t *v, uint32_t n)
{
    uint32_t i;
    lumo_status st;
    if (p->comps != 2 || !p->pos || p->pos->num_portable != 3 || !p->seq->faces)
        return LUMO_ERR_CORRUPT;
    for (i = 0; i < n; ++i) {
        int32_t pred[2];
        if ((st = ld_tex_predict(p, p->seq->value_to_corner[i], v, (int32_t)i, pred)))
            return st;
        ld_original(p, pred, v + 2 * (size_t)i, v + 2 * (size_t)i);
    }
    return LUMO_OK;
}

/* The positions the geometric-normal fan walk reads: a corner's point
 * from the output face array, the point's position value through the
 * position attribute's point map. libdraco goes from the corner's vertex
 * to the normal's entry and back to the entry's first point
 * (GetPositionForCorner); every corner of one vertex holds that vertex's
 * position, so the corner's own point gives the same value in one load
 * less per indirection (positions are per mesh vertex: decoded with the
 * connectivity, never split by seams). */
typedef struct ld_nfan {
    ld_fan f;                 /* the walk's corner table (seams cut fans) */
    const uint32_t *faces;    /* corner -> point */
    uint32_t fmask;
    const uint32_t *pmap;     /* point -> position value; NULL: identity */
    const int32_t *pos;       /* position values, 3 components */
} ld_nfan;

static LD_FORCE_INLINE const int32_t *ld_nfan_pos(const ld_nfan *g, uint32_t c)
{
    uint32_t pt = g->faces[c] & g->fmask;
    if (g->pmap)
        pt = g->pmap[pt];
    return g->pos + 3u * (size_t)pt;
}

/* d = position at corner c - the fan centre */
static LD_FORCE_INLINE void ld_nfan_rel(const ld_nfan *g, uint32_t c, const int64_t cent[3],
                                        int64_t d[3])
{
    const int32_t *q = ld_nfan_pos(g, c);
    d[0] = q[0] - cent[0];
    d[1] = q[1] - cent[1];
    d[2] = q[2] - cent[2];
}

/* n += a x b, wrapping (libdraco's int64 CrossProduct, summed) */
static LD_FORCE_INLINE void ld_cross_add(uint64_t n[3], const int64_t a[3], const int64_t b[3])
{
    n[0] += (uint64_t)ld_sub64(ld_mul64(a[1], b[2]), ld_mul64(a[2], b[1]));
    n[1] += (uint64_t)ld_sub64(ld_mul64(a[2], b[0]), ld_mul64(a[0], b[2]));
    n[2] += (uint64_t)ld_sub64(ld_mul64(a[0], b[1]), ld_mul64(a[1], b[0]));
}

static LD_FORCE_INLINE void ld_copy3(int64_t d[3], const int64_t s[3])
{
    d[0] = s[0];
    d[1] = s[1];
    d[2] = s[2];
}

/* Area-weighted normal of the triangle fan around the corner's vertex
 * (MeshPredictionSchemeGeometricNormalPredictorArea: VertexCornersIterator
 * swings left to a border or back to the start, then right from the
 * start), scaled below 2^29. Each swing crosses the edge from the vertex
 * to one of the face's other corners, so the next face shares that
 * corner's position: one position read and one cross product per face
 * (libdraco: two reads through the entry map and two differences; the
 * same faces in the same order, so the same sums, on every consistent
 * corner table). `limit`: faces a walk may visit (a crafted table cannot
 * make it loop). */
static LD_FORCE_INLINE lumo_status ld_fan_normal(const ld_nfan *g, uint32_t corner, uint32_t limit,
                                                 int32_t out[3], int packed)
{
    const int32_t *q = ld_nfan_pos(g, corner);
    const int64_t cent[3] = {q[0], q[1], q[2]};
    uint64_t nrm[3] = {0, 0, 0};
    int64_t a[3], b[3], a0[3], n[3], sum;
    uint32_t c = corner, o, steps = 1;
    ld_nfan_rel(g, ld_next_v(c), cent, a);
    ld_copy3(a0, a);
    for (;;) {  /* left: the next face's next corner is this one's previous */
        ld_nfan_rel(g, ld_prev_v(c), cent, b);
        ld_cross_add(nrm, a, b);
        o = ld_fan_opp(&g->f, ld_next_v(c), packed);
        if (o == LD_INV)
            break;
        c = ld_next_v(o);
        if (c == corner)
            goto done;
        if (++steps > limit)
            return LUMO_ERR_LIMIT;
        ld_copy3(a, b);
    }
    c = corner;
    ld_copy3(a, a0);
    for (;;) {  /* right: the next face's previous corner is this one's next */
        o = ld_fan_opp(&g->f, ld_prev_v(c), packed);
        if (o == LD_INV)
            break;
        c = ld_prev_v(o);
        if (++steps > limit)
            return LUMO_ERR_LIMIT;
        ld_copy3(b, a);
        ld_nfan_rel(g, ld_next_v(c), cent, a);
        ld_cross_add(nrm, a, b);
    }
done:
    n[0] = (int64_t)nrm[0];
    n[1] = (int64_t)nrm[1];
    n[2] = (int64_t)nrm[2];
    sum = ld_add64(ld_add64(ld_abs64(n[0]), ld_abs64(n[1])), ld_abs64(n[2]));
    if (sum > ((int64_t)1 << 29)) {
        int64_t d = sum / ((int64_t)1 << 29);
        n[0] = ld_div64(n[0], d);
        n[1] = ld_div64(n[1], d);
        n[2] = ld_div64(n[2], d);
    }
    out[0] = (int32_t)n[0];
    out[1] = (int32_t)n[1];
    out[2] = (int32_t)n[2];
    return LUMO_OK;
}

static int32_t ld_abs32(int32_t v) { return (int32_t)(v < 0 ? 0u - (uint32_t)v : (uint32_t)v); }

/* OctahedronToolBox::CanonicalizeIntegerVector: scale onto the L1 sphere
 * of radius center. */
static void ld_canonicalize(const ld_pred *p, int32_t v[3])
{
    const int32_t center = p->oct_center;
    int64_t sum = ld_abs64(v[0]) + ld_abs64(v[1]) + ld_abs64(v[2]);
    int32_t r;
    if (sum == 0) {
        v[0] = center;
        return;
    }
    v[0] = (int32_t)(((int64_t)v[0] * center) / sum);
    v[1] = (int32_t)(((int64_t)v[1] * center) / sum);
    r = (int32_t)((uint32_t)center - (uint32_t)ld_abs32(v[0]) - (uint32_t)ld_abs32(v[1]));
    v[2] = v[2] >= 0 ? r : (int32_t)(0u - (uint32_t)r);
}

/* IntegerVectorToQuantizedOctahedralCoords + CanonicalizeOctahedralCoords */
static void ld_int_to_octa(const ld_pred *p, const int32_t v[3], int32_t out[2])
{
    const int32_t center = p->oct_center, maxv = p->oct_max_q - 1;
    int32_t s, t;
    if (v[0] >= 0) {
        s = ld_wrap_add(v[1], center);
        t = ld_wrap_add(v[2], center);
    } else {
        s = v[1] < 0 ? ld_abs32(v[2]) : ld_wrap_add(maxv, (int32_t)(0u - (uint32_t)ld_abs32(v[2])));
        t = v[2] < 0 ? ld_abs32(v[1]) : ld_wrap_add(maxv, (int32_t)(0u - (uint32_t)ld_abs32(v[1])));
    }
    if ((s == 0 && t == 0) || (s == 0 && t == maxv) || (s == maxv && t == 0)) {
        s = maxv;
        t = maxv;
    } else if (s == 0 && t > center) {
        t = center - (t - center);
    } else if (s == maxv && t < center) {
        t = center + (center - t);
    } else if (t == maxv && s < center) {
        s = center + (center - s);
    } else if (t == 0 && s > center) {
        s = center - (s - center);
    }
    out[0] = s;
    out[1] = t;
}

/* MeshPredictionSchemeGeometricNormalDecoder: predict from the fan normal,
 * a flip bit per value says the normal points the other way. */
static LD_FORCE_INLINE lumo_status ld_geometric_normal_run(ld_pred *p, int32_t *v, uint32_t n,
                                                           int packed)
{
    const uint32_t limit = p->seq->ct->num_corners + 1u;
    ld_nfan g;
    uint32_t i;
    lumo_status st;
    ld_fan_init(&g.f, p, 1);
    g.faces = p->seq->faces;
    g.fmask = p->seq->faces_mask;
    g.pmap = p->pos->point_to_value;
    g.pos = p->pos->values;
    for (i = 0; i < n; ++i) {
        int32_t vec[3], oct[2];
        if ((st = ld_fan_normal(&g, p->seq->value_to_corner[i], limit, vec, packed)))
            return st;
        ld_canonicalize(p, vec);
        if (ld_rabs_bit(&p->flip)) {
            vec[0] = -vec[0];
            vec[1] = -vec[1];
            vec[2] = -vec[2];
        }
        ld_int_to_octa(p, vec, oct);
        ld_original(p, oct, v + 2 * (size_t)i, v + 2 * (size_t)i);
    }
    return LUMO_OK;
}

static LD_NOINLINE lumo_status ld_geometric_normal(ld_pred *p, int32_t *v, uint32_t n)
{
    if (!p->pos || p->pos->num_portable != 3 || !p->seq->faces || p->seq->opposites)
        return LUMO_ERR_CORRUPT;
    return ld_ct_packed(p->seq->ct) ? ld_geometric_normal_run(p, v, n, 1)
                                     : ld_geometric_normal_run(p, v, n, 0);
}

int ld_pred_reads_table(const ld_pred *p)
{
    return ld_effective_method(p) != LD_PRED_DIFFERENCE;
}

int ld_pred_needs_opposites_only(const ld_pred *p)
{
    return ld_effective_method(p) == LD_PRED_PARALLELOGRAM;
}

lumo_status ld_pred_compute(ld_pred *p, int32_t *values, uint32_t num_entries)
{
    switch (ld_effective_method(p)) {
    case LD_PRED_DIFFERENCE:
        if (p->transform == LD_XFORM_WRAP)
            return ld_delta_wrap(p, values, num_entries);
        return ld_delta(p, values, num_entries);
    case LD_PRED_PARALLELOGRAM:
        if (p->comps == 3 && p->transform == LD_XFORM_WRAP)
            return ld_parallelogram_wrap3(p, values, num_entries);
        return ld_parallelogram_all(p, values, num_entries);
    case LD_PRED_CONSTRAINED_MULTI:
        return ld_multi_parallelogram(p, values, num_entries);
    case LD_PRED_TEX_COORDS_PORTABLE:
        return ld_tex_coords(p, values, num_entries);
    case LD_PRED_GEOMETRIC_NORMAL:
        return ld_geometric_normal(p, values, num_entries);
    default:
        return LUMO_ERR_UNSUPPORTED;
    }
}
