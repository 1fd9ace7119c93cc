/*
 * draco_edgebreaker.c — EdgeBreaker connectivity (paper §3; libdraco
 * MeshEdgebreakerDecoderImpl with the standard and valence traversal
 * decoders), attribute seams, and the assignment of points to corners.
 *
 * The decoder rebuilds libdraco's corner table exactly, including its
 * left-most corners as set during decoding, because attribute traversal
 * order, and therefore point order, depend on them.
 */
#include "draco_internal.h"

#define LD_TOPO_C 0u
#define LD_TOPO_S 1u
#define LD_TOPO_L 3u
#define LD_TOPO_R 5u
#define LD_TOPO_E 7u
#define LD_TOPO_INVALID 9u
#define LD_MAX_ATTR_DATA 16u
#define LD_VALENCE_CONTEXTS 6u   /* valences 2..7 */

/* Valence counters: 32-bit (default mode) or bytes saturating at 255 (lean;
 * only min(v, 7) is read). Passed by value: a local copy of the pointer,
 * which the byte stores (char stores alias anything) cannot force to be
 * reloaded. */
typedef union ld_valences {
    uint32_t *w;
    uint8_t *b;
} ld_valences;

typedef struct ld_attr_data {
    int32_t decoder_id;
    uint8_t connectivity_used;
    ld_rabs seams;
    uint8_t *seam;         /* per corner: opposite edge is a seam */
    uint8_t *vseam;        /* per mesh vertex: on a seam */
    uint32_t *rep;         /* point -> its attribute vertex's first point |
                              border flag << 31 (ld_ct.rep, ld_eb_points_run) */
    uint32_t num_avs;      /* attribute vertices (RecomputeVertices' count) */
    uint32_t ones;         /* interior edges marked as seams */
    uint8_t shared;        /* no interior seam: ct is the mesh's table
                              (ld_eb_attr_table), no rep or seam of its own */
    ld_ct ct;
} ld_attr_data;

struct ld_eb {
    uint8_t valence;
    uint32_t num_faces, num_corners, max_vertices, num_vertices, num_conn_vertices;
    uint32_t encoded_vertices;  /* V of the header */
    uint8_t lean;              /* LUMO_DRACO_LEAN: packed opposites */
    uint32_t *c2v, *lmc;
    uint32_t *opp32;           /* opposites, default mode */
    uint8_t *o24;              /* opposites while decoding, lean (ld_o24) */
    uint8_t *hole;
    uint8_t *lmc_top;          /* one past the left-most corners' block */
    uint8_t *o24_top;          /* one past the 24-bit opposites' block */
    uint8_t *seam_top;         /* one past the attributes' seam flags */
    uint8_t *opp_top;          /* one past the 32-bit opposites' block */
    /* after ld_eb_pack, without seams: work memory from table_lo up to
     * lmc_top holds the packed table's escapes and indices, then from
     * table_top the border bytes */
    uint8_t *table_lo, *table_top;
    uint8_t packed;            /* words hold packed opposites (ld_pot) */
    uint8_t vpoints;           /* attribute data, none with an interior seam:
                                  the vertices are the points and the output
                                  face array is the vertex map (ld_eb_renumber) */
    uint8_t released;          /* ld_eb_release_table has run */
    uint32_t *rep;             /* with seams: point -> its mesh vertex's first
                                  point | fan open << 31 (ld_ct.rep) */
    uint8_t *region;           /* with seams: the top of the blocks
                                  ld_eb_drop_dead moves (below the opposites) */
    uint32_t rep_cap;          /* entries of each rep map */
    ld_ct ct;
    uint32_t num_attr_data;
    ld_attr_data ad[LD_MAX_ATTR_DATA];
    int32_t pos_decoder;
    int8_t dec_att_data[LD_MAX_DECODERS];
    uint8_t dec_type[LD_MAX_DECODERS];
    uint8_t dec_traversal[LD_MAX_DECODERS];
    /* traversal symbols */
    ld_bits sym_bits;
    ld_rabs start_faces;
    /* valence coding */
    ld_valences val;
    uint8_t *ctx_symbols[LD_VALENCE_CONTEXTS];  /* 0..4, 5 = invalid */
    uint32_t ctx_count[LD_VALENCE_CONTEXTS];
    int active_ctx;
    uint32_t last_symbol;
    /* topology splits, stored in stream order and consumed from the back */
    uint32_t num_splits;
    uint32_t *split_source, *split_target;
    uint8_t *split_edge;
    /* work budget against crafted fans */
    uint64_t budget;
};

/* The mode and the opposite store, constant in a lean-only build (its
 * walks' default instances then fold away; with attribute data the lean
 * mode packs the table right after the connectivity, so every walk below
 * that picks an instance by the store runs on a packed table there). */
#define LD_EB_LEAN(e) (LD_LEAN_ONLY || (e)->lean)
#define LD_EB_PACKED(e) (LD_LEAN_ONLY || (e)->packed)

static int ld_eb_peek_vpoints(const ld_buf *at, uint32_t faces, uint32_t nad, int valence);

/* Bounded work: fan walks are charged here. */
static int ld_eb_charge(struct ld_eb *e)
{
    if (e->budget == 0)
        return 0;
    --e->budget;
    return 1;
}

/* The opposites while the connectivity is decoded: 32-bit ids (default) or
 * 24-bit ids (lean, packed afterwards by ld_eb_pack). `lean` is a
 * constant in the symbol loop's two instances, LD_EB_LEAN(e) elsewhere. */
static LD_FORCE_INLINE uint32_t ld_eb_opp(const struct ld_eb *e, uint32_t c, int lean)
{
    uint32_t o;
    if (!lean)
        return e->opp32[c];
    o = ld_o24(e->o24, c);
    return o == LD_O24_NONE ? LD_INV : o;
}

static LD_FORCE_INLINE int ld_has_opp(const struct ld_eb *e, uint32_t c, int lean)
{
    return lean ? ld_o24(e->o24, c) != LD_O24_NONE : e->opp32[c] != LD_INV;
}

static LD_FORCE_INLINE void ld_set_opp(struct ld_eb *e, uint32_t a, uint32_t b, int lean)
{
    if (lean) {
        ld_o24_set(e->o24, a, b);
        ld_o24_set(e->o24, b, a);
    } else {
        e->opp32[a] = b;
        e->opp32[b] = a;
    }
}

/* The same for an existing corner a and a corner b of the new face, whose
 * entry is written blind (ld_o24_put_new). Every symbol writes its new
 * face's three entries in corner order (ld_set_opp_new, ld_eb_no_opp):
 * each blind store's fourth byte is the next entry's, written next, or
 * the next face's first, written when that face is made. */
static LD_FORCE_INLINE void ld_set_opp_new(struct ld_eb *e, uint32_t a, uint32_t b, int lean)
{
    if (lean) {
        ld_o24_set(e->o24, a, b);
        ld_o24_put_new(e->o24, b, a);
    } else {
        e->opp32[a] = b;
        e->opp32[b] = a;
    }
}

/* A corner of the new face with no opposite yet (LD_O24_NONE: bit 23, the
 * traversal's flag, clear). */
static LD_FORCE_INLINE void ld_eb_no_opp(struct ld_eb *e, uint32_t c, int lean)
{
    if (lean)
        ld_o24_put_new(e->o24, c, LD_O24_NONE);
    else
        e->opp32[c] = LD_INV;
}

static LD_FORCE_INLINE uint32_t ld_eb_swing_left(const struct ld_eb *e, uint32_t c, int lean)
{
    const uint32_t o = ld_eb_opp(e, ld_next_v(c), lean);
    return o == LD_INV ? LD_INV : ld_next_v(o);
}

static LD_FORCE_INLINE uint32_t ld_eb_swing_right(const struct ld_eb *e, uint32_t c, int lean)
{
    const uint32_t o = ld_eb_opp(e, ld_prev_v(c), lean);
    return o == LD_INV ? LD_INV : ld_prev_v(o);
}

/* `sat`: the lean counters may pass 255 (else the caller checked they are
 * all small enough for plain byte adds). */
static LD_FORCE_INLINE void ld_valence_add(ld_valences val, uint32_t v, uint32_t n, int lean,
                                           int sat)
{
    if (lean && sat) {
        const uint32_t x = val.b[v] + n;
        val.b[v] = (uint8_t)(x > 255u ? 255u : x);
    } else if (lean) {
        val.b[v] = (uint8_t)(val.b[v] + n);
    } else {
        val.w[v] += n;
    }
}

static LD_FORCE_INLINE uint32_t ld_valence(ld_valences val, uint32_t v, int lean)
{
    return lean ? val.b[v] : val.w[v];
}

/* ---- header and split events ----------------------------------------------- */

static lumo_status ld_eb_splits(ld_dec *d, struct ld_eb *e)
{
    uint32_t n, i, last = 0;
    ld_bits bits;
    lumo_status st = ld_varint32(&d->buf, &n);
    if (st)
        return st;
    e->num_splits = n;
    if (n == 0)
        return LUMO_OK;
    if (n > e->num_faces)
        return LUMO_ERR_CORRUPT;
    e->split_source = ld_tmp(&d->mem, n, sizeof(uint32_t));
    e->split_target = ld_tmp(&d->mem, n, sizeof(uint32_t));
    e->split_edge = ld_tmp(&d->mem, n, 1);
    if (!e->split_source || !e->split_target || !e->split_edge)
        return LUMO_ERR_NOMEM;
    for (i = 0; i < n; ++i) {
        uint32_t delta, src;
        if ((st = ld_varint32(&d->buf, &delta)))
            return st;
        src = delta + last;
        if ((st = ld_varint32(&d->buf, &delta)))
            return st;
        if (delta > src)
            return LUMO_ERR_CORRUPT;
        e->split_source[i] = src;
        e->split_target[i] = src - delta;
        last = src;
    }
    ld_bits_start(&bits, &d->buf);
    for (i = 0; i < n; ++i)
        e->split_edge[i] = (uint8_t)(ld_bits_get(&bits, 1) & 1u);
    ld_bits_end(&bits, &d->buf);
    return LUMO_OK;
}

/* Standard traversal: symbols are a bit stream of its own size; then the
 * start-face and seam rABS streams follow. */
static lumo_status ld_eb_start_standard(ld_dec *d, struct ld_eb *e)
{
    uint64_t size;
    lumo_status st = ld_varint64(&d->buf, &size);
    if (st)
        return st;
    ld_bits_start(&e->sym_bits, &d->buf);  /* reads on past `size`, like libdraco */
    return ld_skip(&d->buf, size);
}

static lumo_status ld_eb_start_common(ld_dec *d, struct ld_eb *e)
{
    uint32_t i;
    lumo_status st = ld_rabs_start(&e->start_faces, &d->buf);
    for (i = 0; i < e->num_attr_data && !st; ++i)
        st = ld_rabs_start(&e->ad[i].seams, &d->buf);
    return st;
}

/* One context's symbols, kept as bytes. They are decoded as 32-bit words
 * into the output face array, which is not written before the symbol loop
 * and holds 3F words (a context holds at most F symbols): no transient
 * work memory. */
static lumo_status ld_ctx_symbols(ld_dec *d, uint32_t n, uint8_t **out)
{
    uint32_t *words = d->faces, j;
    uint8_t *bytes;
    lumo_status st;
    if ((st = ld_decode_symbols(&d->buf, &d->mem, n, 1, words, NULL)))
        return st;
    bytes = ld_tmp(&d->mem, n, 1);
    if (!bytes)
        return LUMO_ERR_NOMEM;
    for (j = 0; j < n; ++j)
        bytes[j] = (uint8_t)(words[j] > 4u ? 5u : words[j]);
    *out = bytes;
    return LUMO_OK;
}

static lumo_status ld_eb_start_valence(ld_dec *d, struct ld_eb *e)
{
    const size_t vsize = LD_EB_LEAN(e) ? 1u : sizeof(uint32_t);
    void *val = ld_tmp(&d->mem, e->max_vertices + 3u, vsize);
    unsigned i;
    lumo_status st;
    if (!val)
        return LUMO_ERR_NOMEM;
    memset(val, 0, ((size_t)e->max_vertices + 3u) * vsize);
    if (LD_EB_LEAN(e))
        e->val.b = val;
    else
        e->val.w = val;
    e->active_ctx = -1;
    for (i = 0; i < LD_VALENCE_CONTEXTS; ++i) {
        uint32_t n;
        if ((st = ld_varint32(&d->buf, &n)))
            return st;
        if (n > e->num_faces)
            return LUMO_ERR_CORRUPT;
        e->ctx_count[i] = n;
        if (n == 0)
            continue;
        /* libdraco ignores a failure here (the symbols stay zero); a
         * stream that fails to decode is rejected by lumo instead. */
        if ((st = ld_ctx_symbols(d, n, &e->ctx_symbols[i])))
            return st;
    }
    return LUMO_OK;
}

/* ---- traversal symbols ------------------------------------------------------- */

static LD_FORCE_INLINE uint32_t ld_eb_symbol(struct ld_eb *e)
{
    static const uint8_t to_topology[6] = {LD_TOPO_C, LD_TOPO_S, LD_TOPO_L, LD_TOPO_R, LD_TOPO_E,
                                           LD_TOPO_INVALID};
    uint32_t s;
    if (!e->valence) {
        s = ld_bits_get(&e->sym_bits, 1);
        if (s != LD_TOPO_C)
            s |= ld_bits_get(&e->sym_bits, 2) << 1;
        return s;
    }
    if (e->active_ctx < 0) {
        e->last_symbol = LD_TOPO_E;
        return LD_TOPO_E;
    }
    {
        uint32_t *count = &e->ctx_count[e->active_ctx];
        if (*count == 0)
            return LD_TOPO_INVALID;
        s = to_topology[e->ctx_symbols[e->active_ctx][--*count]];  /* bytes 0..5 */
    }
    e->last_symbol = s;
    return s;
}

/* The valences of the new face's vertices: by 1 at the corners the symbol
 * joins to the boundary, by 2 where it adds two edges (libdraco
 * MeshEdgebreakerTraversalValenceDecoder::NewActiveCornerReached). */
static LD_FORCE_INLINE void ld_valence_face(ld_valences val, uint32_t symbol, const uint32_t *c2v,
                                            uint32_t corner, uint32_t next, uint32_t prev,
                                            int lean, int sat)
{
    switch (symbol) {
    case LD_TOPO_C:
    case LD_TOPO_S:
        ld_valence_add(val, next, 1, lean, sat); ld_valence_add(val, prev, 1, lean, sat);
        break;
    case LD_TOPO_R:
        ld_valence_add(val, c2v[corner], 1, lean, sat);
        ld_valence_add(val, next, 1, lean, sat); ld_valence_add(val, prev, 2, lean, sat);
        break;
    case LD_TOPO_L:
        ld_valence_add(val, c2v[corner], 1, lean, sat);
        ld_valence_add(val, next, 2, lean, sat); ld_valence_add(val, prev, 1, lean, sat);
        break;
    case LD_TOPO_E:
        ld_valence_add(val, c2v[corner], 2, lean, sat);
        ld_valence_add(val, next, 2, lean, sat); ld_valence_add(val, prev, 2, lean, sat);
        break;
    default:
        break;
    }
}

/* Valence contexts: the valence of the next vertex selects the context of
 * the next symbol (libdraco MeshEdgebreakerTraversalValenceDecoder). */
/* `corner` is always the first corner of the face just decoded (every
 * symbol makes its new face the active one), so its next and previous
 * corners are corner + 1 and corner + 2. Lean byte counters: when the
 * three are below 128 no sum of this face's adds (at most 6) passes 255,
 * so plain byte adds do, and only high valences pay for saturation. */
static LD_FORCE_INLINE void ld_eb_new_active_corner(struct ld_eb *e, uint32_t corner, int lean)
{
    static const uint8_t ctx_of_valence[8] = {0, 0, 0, 1, 2, 3, 4, 5};  /* clamp to 2..7, - 2 */
    const ld_valences val = e->val;
    const uint32_t *c2v = e->c2v, sym = e->last_symbol;
    const uint32_t next = c2v[corner + 1u], prev = c2v[corner + 2u];
    uint32_t v;
    if (!lean)
        ld_valence_face(val, sym, c2v, corner, next, prev, 0, 0);
    else if ((val.b[next] | val.b[prev] |
              (sym == LD_TOPO_C || sym == LD_TOPO_S ? 0u : val.b[c2v[corner]])) < 128u)
        ld_valence_face(val, sym, c2v, corner, next, prev, 1, 0);
    else
        ld_valence_face(val, sym, c2v, corner, next, prev, 1, 1);
    v = ld_valence(val, next, lean);
    e->active_ctx = ctx_of_valence[v > 7u ? 7u : v];
}

static uint32_t ld_eb_new_vertex(struct ld_eb *e)
{
    e->lmc[e->num_vertices] = LD_INV;
    return e->num_vertices++;
}

/* ---- the symbol loop ----------------------------------------------------------- */

typedef struct ld_eb_state {
    uint32_t *stack, top, cap, max_top;  /* active corners */
    uint32_t *split_key, *split_val, split_mask;  /* open-addressed map */
    uint32_t *invalid, num_invalid, max_invalid;
    uint32_t faces;                /* faces decoded so far */
} ld_eb_state;

static void ld_split_put(ld_eb_state *s, uint32_t key, uint32_t corner)
{
    uint32_t h = (key * 2654435761u) & s->split_mask;
    while (s->split_key[h] != LD_INV && s->split_key[h] != key)
        h = (h + 1u) & s->split_mask;
    s->split_key[h] = key;
    s->split_val[h] = corner;
}

static uint32_t ld_split_get(const ld_eb_state *s, uint32_t key)
{
    uint32_t h;
    if (!s->split_key)
        return LD_INV;
    h = (key * 2654435761u) & s->split_mask;
    while (s->split_key[h] != LD_INV) {
        if (s->split_key[h] == key)
            return s->split_val[h];
        h = (h + 1u) & s->split_mask;
    }
    return LD_INV;
}

static int ld_valid_vertex(const struct ld_eb *e, uint32_t v)
{
    return v < e->num_vertices;
}

static LD_FORCE_INLINE lumo_status ld_eb_sym_c(struct ld_eb *e, ld_eb_state *s, uint32_t face,
                                              int lean)
{
    uint32_t a, b, x, corner = 3u * face, ap, bn;
    if (s->top == 0)
        return LUMO_ERR_CORRUPT;
    a = s->stack[s->top - 1];
    x = e->c2v[ld_next_v(a)];
    if (!ld_valid_vertex(e, x))
        return LUMO_ERR_CORRUPT;
    b = ld_next(e->lmc[x]);
    if (a == b || b == LD_INV || ld_has_opp(e, a, lean) || ld_has_opp(e, b, lean))
        return LUMO_ERR_CORRUPT;
    ld_eb_no_opp(e, corner, lean);
    ld_set_opp_new(e, a, corner + 1u, lean);
    ld_set_opp_new(e, b, corner + 2u, lean);
    ap = e->c2v[ld_prev_v(a)];
    bn = e->c2v[ld_next_v(b)];
    if (x == ap || x == bn || !ld_valid_vertex(e, ap))
        return LUMO_ERR_CORRUPT;
    e->c2v[corner] = x;
    e->c2v[corner + 1u] = bn;
    e->c2v[corner + 2u] = ap;
    e->lmc[ap] = corner + 2u;
    if (e->hole)
        e->hole[x] = 0;
    s->stack[s->top - 1] = corner;
    return LUMO_OK;
}

static LD_FORCE_INLINE lumo_status ld_eb_sym_rl(struct ld_eb *e, ld_eb_state *s, uint32_t face,
                                               int right, int lean)
{
    uint32_t a, corner = 3u * face, oc, cl, cr, nv, vr;
    if (s->top == 0)
        return LUMO_ERR_CORRUPT;
    a = s->stack[s->top - 1];
    if (ld_has_opp(e, a, lean))
        return LUMO_ERR_CORRUPT;
    oc = right ? corner + 2u : corner + 1u;
    cl = right ? corner + 1u : corner;
    cr = right ? corner : corner + 2u;
    ld_eb_no_opp(e, corner, lean);
    if (right) {
        ld_eb_no_opp(e, corner + 1u, lean);
        ld_set_opp_new(e, a, oc, lean);
    } else {
        ld_set_opp_new(e, a, oc, lean);
        ld_eb_no_opp(e, corner + 2u, lean);
    }
    if (e->num_vertices >= e->max_vertices)
        return LUMO_ERR_CORRUPT;
    nv = ld_eb_new_vertex(e);
    e->c2v[oc] = nv;
    e->lmc[nv] = oc;
    vr = e->c2v[ld_prev_v(a)];
    if (!ld_valid_vertex(e, vr))
        return LUMO_ERR_CORRUPT;
    e->c2v[cr] = vr;
    e->lmc[vr] = cr;
    e->c2v[cl] = e->c2v[ld_next_v(a)];
    s->stack[s->top - 1] = corner;
    return LUMO_OK;
}

static LD_FORCE_INLINE lumo_status ld_eb_sym_s(struct ld_eb *e, ld_eb_state *s, uint32_t face,
                                              uint32_t symbol_id, int lean)
{
    uint32_t a, b, corner = 3u * face, vp, vbp, cn, vn, first, split;
    if (s->top == 0)
        return LUMO_ERR_CORRUPT;
    b = s->stack[--s->top];
    split = ld_split_get(s, symbol_id);
    if (split != LD_INV)
        s->stack[s->top++] = split;  /* room: one was just popped */
    if (s->top == 0)
        return LUMO_ERR_CORRUPT;
    a = s->stack[s->top - 1];
    if (a == b || ld_has_opp(e, a, lean) || ld_has_opp(e, b, lean))
        return LUMO_ERR_CORRUPT;
    ld_eb_no_opp(e, corner, lean);
    ld_set_opp_new(e, b, corner + 1u, lean);
    ld_set_opp_new(e, a, corner + 2u, lean);
    vp = e->c2v[ld_prev_v(a)];
    e->c2v[corner] = vp;
    e->c2v[corner + 1u] = e->c2v[ld_next_v(a)];
    vbp = e->c2v[ld_prev_v(b)];
    cn = ld_next_v(b);
    vn = e->c2v[cn];
    if (!ld_valid_vertex(e, vp) || !ld_valid_vertex(e, vbp) || !ld_valid_vertex(e, vn))
        return LUMO_ERR_CORRUPT;
    e->c2v[corner + 2u] = vbp;
    e->lmc[vbp] = corner + 2u;
    if (e->valence)
        ld_valence_add(e->val, vp, ld_valence(e->val, vn, lean), lean, 1);
    e->lmc[vp] = e->lmc[vn];
    first = cn;
    while (cn != LD_INV) {
        if (!ld_eb_charge(e))
            return LUMO_ERR_LIMIT;
        e->c2v[cn] = vp;
        cn = ld_eb_swing_left(e, cn, lean);
        if (cn == first)
            return LUMO_ERR_CORRUPT;
    }
    e->lmc[vn] = LD_INV;
    if (s->invalid) {
        if (s->num_invalid >= s->max_invalid)
            return LUMO_ERR_CORRUPT;
        s->invalid[s->num_invalid++] = vn;
    }
    s->stack[s->top - 1] = corner;
    return LUMO_OK;
}

static LD_FORCE_INLINE lumo_status ld_eb_sym_e(struct ld_eb *e, ld_eb_state *s, uint32_t face,
                                              int lean)
{
    uint32_t corner = 3u * face, v;
    ld_eb_no_opp(e, corner, lean);
    ld_eb_no_opp(e, corner + 1u, lean);
    ld_eb_no_opp(e, corner + 2u, lean);
    if (e->num_vertices + 3u > e->max_vertices)
        return LUMO_ERR_CORRUPT;
    v = ld_eb_new_vertex(e);
    ld_eb_new_vertex(e);
    ld_eb_new_vertex(e);
    e->c2v[corner] = v;
    e->c2v[corner + 1u] = v + 1u;
    e->c2v[corner + 2u] = v + 2u;
    e->lmc[v] = corner;
    e->lmc[v + 1u] = corner + 1u;
    e->lmc[v + 2u] = corner + 2u;
    if (s->top >= s->cap)
        return LUMO_ERR_NOMEM;
    s->stack[s->top++] = corner;
    if (s->top > s->max_top)
        s->max_top = s->top;
    return LUMO_OK;
}

/* Splits whose source is the current symbol schedule an active corner for
 * the S symbol that will consume it. */
static LD_FORCE_INLINE lumo_status ld_eb_check_split(struct ld_eb *e, ld_eb_state *s,
                                                    uint32_t num_symbols, uint32_t symbol_id)
{
    const uint32_t enc_id = num_symbols - symbol_id - 1u;
    while (e->num_splits) {
        uint32_t i = e->num_splits - 1u, act, corner;
        if (e->split_source[i] > enc_id)
            return LUMO_ERR_CORRUPT;
        if (e->split_source[i] != enc_id)
            return LUMO_OK;
        if (e->split_target[i] > 0x7FFFFFFFu)
            return LUMO_ERR_CORRUPT;
        act = s->stack[s->top - 1];
        corner = e->split_edge[i] ? ld_next_v(act) : ld_prev_v(act);
        ld_split_put(s, num_symbols - e->split_target[i] - 1u, corner);
        e->num_splits--;
    }
    return LUMO_OK;
}

/* Close the remaining active boundaries: one bit says whether the start
 * face was an interior face that the encoder removed. */
static lumo_status ld_eb_start_faces(struct ld_eb *e, ld_eb_state *s)
{
    while (s->top) {
        uint32_t corner = s->stack[--s->top], vn, b, vx, c, vp, nc, k;
        if (!ld_rabs_bit(&e->start_faces))
            continue;
        if (s->faces >= e->num_faces)
            return LUMO_ERR_CORRUPT;
        vn = e->c2v[ld_next(corner)];
        if (!ld_valid_vertex(e, vn))
            return LUMO_ERR_CORRUPT;
        b = ld_next(e->lmc[vn]);
        vx = ld_vert(&e->ct, ld_next(b));
        if (!ld_valid_vertex(e, vx))
            return LUMO_ERR_CORRUPT;
        c = ld_next(e->lmc[vx]);
        if (corner == b || corner == c || b == c || b == LD_INV || c == LD_INV)
            return LUMO_ERR_CORRUPT;
        if (ld_has_opp(e, corner, LD_EB_LEAN(e)) || ld_has_opp(e, b, LD_EB_LEAN(e)) ||
            ld_has_opp(e, c, LD_EB_LEAN(e)))
            return LUMO_ERR_CORRUPT;
        vp = e->c2v[ld_next(c)];
        nc = 3u * s->faces++;
        ld_set_opp(e, nc, corner, LD_EB_LEAN(e));
        ld_set_opp(e, nc + 1u, b, LD_EB_LEAN(e));
        ld_set_opp(e, nc + 2u, c, LD_EB_LEAN(e));
        e->c2v[nc] = vx;
        e->c2v[nc + 1u] = vp;
        e->c2v[nc + 2u] = vn;
        for (k = 0; k < 3 && e->hole; ++k)
            if (e->c2v[nc + k] < e->num_vertices)
                e->hole[e->c2v[nc + k]] = 0;
    }
    return s->faces == e->num_faces ? LUMO_OK : LUMO_ERR_CORRUPT;
}

/* Without attributes, vertices merged away by S symbols are filled with
 * the last live vertices so the vertex ids stay dense. */
static lumo_status ld_eb_compact(struct ld_eb *e, ld_eb_state *s, uint32_t *num_out)
{
    uint32_t nv = e->num_vertices, i;
    for (i = 0; i < s->num_invalid; ++i) {
        uint32_t iv = s->invalid[i], src, c, start;
        int left = 1;
        if (nv == 0)
            return LUMO_ERR_CORRUPT;
        src = nv - 1u;
        while (e->lmc[src] == LD_INV) {
            if (--nv == 0)
                return LUMO_ERR_CORRUPT;
            src = nv - 1u;
        }
        if (src < iv)
            continue;
        start = c = e->lmc[src];
        while (c != LD_INV) {  /* VertexCornersIterator */
            if (!ld_eb_charge(e))
                return LUMO_ERR_LIMIT;
            if (e->c2v[c] != src)
                return LUMO_ERR_CORRUPT;
            e->c2v[c] = iv;
            if (left) {
                c = ld_eb_swing_left(e, c, LD_EB_LEAN(e));
                if (c == LD_INV) {
                    c = ld_eb_swing_right(e, start, LD_EB_LEAN(e));
                    left = 0;
                } else if (c == start) {
                    c = LD_INV;
                }
            } else {
                c = ld_eb_swing_right(e, c, LD_EB_LEAN(e));
            }
        }
        e->lmc[iv] = e->lmc[src];
        e->lmc[src] = LD_INV;
        nv--;
    }
    *num_out = nv;
    return LUMO_OK;
}

/* The symbol loop, instantiated for each opposite store. */
static LD_FORCE_INLINE lumo_status ld_eb_symbols(struct ld_eb *e, ld_eb_state *s,
                                                uint32_t num_symbols, int lean)
{
    uint32_t id;
    lumo_status st = LUMO_OK;
    for (id = 0; id < num_symbols && !st; ++id) {
        uint32_t face = s->faces++, sym = ld_eb_symbol(e);
        int split = 0;
        switch (sym) {  /* each writes its new face's opposites, in corner order */
        case LD_TOPO_C: st = ld_eb_sym_c(e, s, face, lean); break;
        case LD_TOPO_R:
        case LD_TOPO_L: st = ld_eb_sym_rl(e, s, face, sym == LD_TOPO_R, lean); split = 1; break;
        case LD_TOPO_S: st = ld_eb_sym_s(e, s, face, id, lean); break;
        case LD_TOPO_E: st = ld_eb_sym_e(e, s, face, lean); split = 1; break;
        default: st = LUMO_ERR_CORRUPT; break;
        }
        if (st)
            break;
        if (e->valence)
            ld_eb_new_active_corner(e, 3u * face, lean);
        if (split)
            st = ld_eb_check_split(e, s, num_symbols, id);
    }
    return st;
}

static lumo_status ld_eb_symbols_fast(struct ld_eb *e, ld_eb_state *s, uint32_t n)
{
    return ld_eb_symbols(e, s, n, 0);
}

static lumo_status ld_eb_symbols_lean(struct ld_eb *e, ld_eb_state *s, uint32_t n)
{
    return ld_eb_symbols(e, s, n, 1);
}

static lumo_status ld_eb_traverse(ld_dec *d, struct ld_eb *e, uint32_t num_symbols,
                                  uint32_t num_split_symbols)
{
    ld_eb_state s;
    lumo_status st;
    size_t cap;
    memset(&s, 0, sizeof s);
    if (e->num_splits) {
        uint32_t slots = 2u;
        while (slots < 2u * e->num_splits)
            slots <<= 1;
        s.split_key = ld_tmp(&d->mem, slots, sizeof(uint32_t));
        s.split_val = ld_tmp(&d->mem, slots, sizeof(uint32_t));
        if (!s.split_key || !s.split_val)
            return LUMO_ERR_NOMEM;
        memset(s.split_key, 0xFF, (size_t)slots * sizeof(uint32_t));
        s.split_mask = slots - 1u;
    }
    if (e->num_attr_data == 0) {
        s.max_invalid = num_split_symbols;  /* one merged vertex per S symbol */
        s.invalid = ld_tmp(&d->mem, (size_t)s.max_invalid + 1u, sizeof(uint32_t));
        if (!s.invalid)
            return LUMO_ERR_NOMEM;
    }
    /* the active-corner stack takes the free space; its depth is booked
     * when the symbols are done */
    s.stack = ld_free_space(&d->mem, &cap);
    s.cap = cap > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)cap;
    st = LD_EB_LEAN(e) ? ld_eb_symbols_lean(e, &s, num_symbols) : ld_eb_symbols_fast(e, &s, num_symbols);
    ld_free_used(&d->mem, (size_t)s.max_top * sizeof(uint32_t));
    if (st || (st = ld_eb_start_faces(e, &s)))
        return st;
    return ld_eb_compact(e, &s, &e->num_conn_vertices);
}

/* ---- attribute seams ----------------------------------------------------------- */

/* The mesh's corner table once the connectivity is decoded: 32-bit
 * opposites (default) or packed into the face words (lean, ld_eb_pack);
 * no seams. `packed` is a constant in each instance of the walks below:
 * the generic ld_opp tests the seam table, LD_INV and the storage at
 * every step. */
static LD_FORCE_INLINE uint32_t ld_eb_mopp(const struct ld_eb *e, uint32_t c, int packed)
{
    return packed ? ld_pot_opp(&e->ct.opp, c) : e->opp32[c];
}

static LD_FORCE_INLINE uint32_t ld_eb_mswing_right(const struct ld_eb *e, uint32_t c, int packed)
{
    const uint32_t o = ld_eb_mopp(e, ld_prev_v(c), packed);
    return o == LD_INV ? LD_INV : ld_prev_v(o);
}

/* The edge opposite corner c (its opposite o, or LD_INV) is a seam of a:
 * the faces still hold the mesh vertices. */
static void ld_add_seam(struct ld_eb *e, ld_attr_data *a, uint32_t c, uint32_t o)
{
    ld_seam_set(a->seam, c);
    a->vseam[ld_vert(&e->ct, ld_next(c))] = 1;
    a->vseam[ld_vert(&e->ct, ld_prev(c))] = 1;
    if (o != LD_INV) {
        ld_seam_set(a->seam, o);
        a->vseam[ld_vert(&e->ct, ld_next(o))] = 1;
        a->vseam[ld_vert(&e->ct, ld_prev(o))] = 1;
    }
}

/* Read before the table is packed (lean: on the 24-bit table), so that the
 * packing knows how many points the seams may make (ld_eb_pack_ids). */
static LD_FORCE_INLINE lumo_status ld_eb_seams_run(struct ld_eb *e, int lean)
{
    uint32_t f, k, i, reads = 0;
    for (f = 0; f < e->num_faces; ++f) {
        const uint32_t c0 = 3u * f, cs[3] = {c0, c0 + 1u, c0 + 2u};
        for (k = 0; k < 3; ++k) {
            uint32_t o = ld_eb_opp(e, cs[k], lean);
            if (o == LD_INV) {
                for (i = 0; i < e->num_attr_data; ++i)
                    ld_add_seam(e, &e->ad[i], cs[k], o);
                continue;
            }
            if (o < c0)  /* an earlier face's edge: its bit is read */
                continue;
            /* one bit per interior edge: at most 3F/2 (the arena need
             * counts seams in that many) */
            if (++reads > e->num_corners / 2u)
                return LUMO_ERR_CORRUPT;
            for (i = 0; i < e->num_attr_data; ++i)
                if (ld_rabs_bit(&e->ad[i].seams)) {
                    e->ad[i].ones++;
                    ld_add_seam(e, &e->ad[i], cs[k], o);
                }
        }
    }
    /* the coders end where the interior edges' bits end, as the
     * encoder's do: the arena need counts seams up to there */
    for (i = 0; i < e->num_attr_data; ++i)
        if (!ld_rabs_done(&e->ad[i].seams))
            return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

static lumo_status ld_eb_seams(struct ld_eb *e)
{
    return LD_EB_LEAN(e) ? ld_eb_seams_run(e, 1) : ld_eb_seams_run(e, 0);
}

/* The points a mesh may have, which the attributes' rep maps are sized
 * by before they are assigned: at most one per corner, and the V encoded
 * vertices with each seam edge of any attribute splitting its two end
 * vertices once (the bound the decode checks and the arena need takes,
 * from the seam coders' ones). */
static uint32_t ld_eb_point_cap(uint32_t corners, uint32_t verts, uint64_t ones)
{
    const uint64_t split = verts + 2u * ones;  /* verts <= corners < 2^28 */
    return split < corners ? (uint32_t)split : corners;
}

/* Interior seam edges of all attribute data (after ld_eb_seams). */
static uint64_t ld_eb_ones(const struct ld_eb *e)
{
    uint64_t ones = 0;
    uint32_t i;
    for (i = 0; i < e->num_attr_data; ++i)
        ones += e->ad[i].ones;
    return ones;
}

/* The ids the packed face words must hold: the vertices, and with seams
 * (points renumbered in place, ld_eb_points_run) the points' bound plus
 * one for the mark of a corner not yet given a point. The decode and the
 * arena need (escape width) ask alike. */
static uint32_t ld_eb_pack_ids(uint32_t vertices, uint32_t corners, uint32_t verts, uint64_t ones,
                               int seamed)
{
    const uint32_t pts = seamed ? ld_eb_point_cap(corners, verts, ones) + 1u : 0u;
    return pts > vertices ? pts : vertices;
}

/* A vertex is on a border when it has no left-most corner or that corner
 * has no swing left (DepthFirstTraverser's IsOnBoundary). */
static LD_FORCE_INLINE int ld_eb_on_border(uint32_t lc, const uint32_t *opp32, const uint8_t *o24,
                                           int lean)
{
    if (lc == LD_INV)
        return 1;
    if (lean)
        return ld_o24(o24, ld_next_v(lc)) == LD_O24_NONE;
    return opp32[ld_next_v(lc)] == LD_INV;
}

/* Without attribute seams the left-most corners serve only the traversal's
 * border test: keep that as one byte per vertex in the top of the table's
 * block (filled from the last vertex down, each byte lands above every
 * entry still to be read: byte v at >= 3n + v > 4v). */
/* On local copies of the tables: the byte stores could alias e's fields. */
static LD_FORCE_INLINE void ld_eb_border_fill(const uint32_t *lmc, const uint32_t *opp32,
                                              const uint8_t *o24, uint32_t n, uint8_t *border,
                                              int lean)
{
    uint32_t v;
    for (v = n; v-- > 0;)
        border[v] = (uint8_t)ld_eb_on_border(lmc[v], opp32, o24, lean);
}

static uint8_t *ld_eb_border(struct ld_eb *e)
{
    uint8_t *border = e->lmc_top - (((size_t)e->num_vertices + 7u) & ~(size_t)7u);
    if (LD_EB_LEAN(e))
        ld_eb_border_fill(e->lmc, NULL, e->o24, e->num_vertices, border, 1);
    else
        ld_eb_border_fill(e->lmc, e->opp32, NULL, e->num_vertices, border, 0);
    e->ct.border = border;
    e->ct.lmc = NULL;
    e->lmc = NULL;
    return border;
}

/* Only the depth-first traversal tests borders: when every attributes
 * decoder walks by prediction degree (-cl 10) no border bytes are kept.
 * The decode and the arena-need replay ask alike. */
static int ld_eb_border_needed(unsigned num_decoders, const uint8_t *dec_traversal)
{
    unsigned i;
    for (i = 0; i < num_decoders; ++i)
        if (dec_traversal[i] == 0)
            return 1;
    return 0;
}

/* Without seams, at the first sequence: the left-most corners become the
 * border bytes in the top of their block, or go. Returns where the dead
 * part of the block ends (the border bytes' start, else its top). */
static uint8_t *ld_eb_lmc_end(const ld_dec *d, struct ld_eb *e)
{
    if (ld_eb_border_needed(d->num_decoders, e->dec_traversal))
        return ld_eb_border(e);
    e->ct.lmc = NULL;
    e->lmc = NULL;
    return e->lmc_top;
}

/* Default mode: the left-most corners' block is released, the border bytes
 * (if any) stay in its top. */
static lumo_status ld_eb_drop_lmc(ld_dec *d, struct ld_eb *e)
{
    const uint8_t *end = ld_eb_lmc_end(d, e);
    ld_tmp_release(&d->mem, e->lmc_top);
    if (end == e->lmc_top)
        return LUMO_OK;
    return ld_tmp(&d->mem, e->ct.num_vertices, 1) == end ? LUMO_OK : LUMO_ERR_NOMEM;
}

/* Move `bytes` at src up to end at `top` (8-aligned); returns the start. */
static uint8_t *ld_move_up(uint8_t *top, const void *src, size_t bytes)
{
    uint8_t *dst = top - ((bytes + 7u) & ~(size_t)7u);
    memmove(dst, src, bytes);
    return dst;
}

/* The packed table's escapes and indices were moved `shift` bytes up. */
static void ld_pot_moved(ld_pot *t, size_t shift)
{
    t->esc += shift;
    t->coarse = (const uint32_t *)(const void *)((const uint8_t *)t->coarse + shift);
    t->fine = (const uint16_t *)(const void *)((const uint8_t *)t->fine + shift);
    t->base = (const int16_t *)(const void *)((const uint8_t *)t->base + shift);
}

/* The packed table's block, [bases][fine][coarse][escapes] from table_lo
 * to table_top, moves up to end at `top` (over dead work memory); returns
 * its new start. */
static uint8_t *ld_eb_lift_table(struct ld_eb *e, uint8_t *top)
{
    const size_t shift = (size_t)(top - e->table_top);
    memmove(e->table_lo + shift, e->table_lo, (size_t)(e->table_top - e->table_lo));
    ld_pot_moved(&e->ct.opp, shift);
    e->table_lo += shift;
    e->table_top = top;
    return e->table_lo;
}

/* Pack the opposites into the corner table's words (ld_pot) and shrink
 * the work memory to the packed table. Work memory grows down: before,
 * [left-most corners][24-bit opposites][coarse][fine][bases]; after,
 * without seams [border bytes][escapes][coarse][fine][bases], with seams
 * [left-most corners][escapes][coarse][fine][bases]. Everything moves up. */
static lumo_status ld_eb_pack(ld_dec *d, struct ld_eb *e)
{
    const uint32_t nc = e->num_corners;
    const unsigned vshift = ld_pot_vshift(ld_eb_pack_ids(e->num_vertices, nc, e->encoded_vertices,
                                                         ld_eb_ones(e), e->num_attr_data && !e->vpoints));
    const size_t cb = (((size_t)nc + 1023u) >> LD_POT_COARSE) * 4u;
    const size_t fb = (((size_t)nc + 15u) >> LD_POT_BLOCK) * 2u;
    const size_t bb = ld_pot_bases(nc) * 4u;
    ld_pot *t = &e->ct.opp;
    uint8_t *top = e->o24_top;
    uint32_t *coarse;
    uint16_t *fine;
    int16_t *base;
    size_t esc;
    if (vshift > LD_POT_MAX_VSHIFT)
        return LUMO_ERR_LIMIT;
    if (!e->num_attr_data)
        top = ld_eb_lmc_end(d, e);
    coarse = ld_tmp(&d->mem, cb, 1);
    fine = ld_tmp(&d->mem, fb, 1);
    base = ld_tmp(&d->mem, bb, 1);
    if (!coarse || !fine || !base)
        return LUMO_ERR_NOMEM;
    ld_pot_build(t, e->c2v, nc, vshift, e->o24, fine, coarse, base, &esc);
    e->ct.vmask = 0xFFFFFFFFu >> (32u - vshift);
    e->packed = 1;
    e->o24 = NULL;
    e->table_top = top;
    t->esc = ld_move_up(top, t->esc, esc);
    t->coarse = (const uint32_t *)(const void *)ld_move_up((uint8_t *)(uintptr_t)t->esc, coarse, cb);
    t->fine = (const uint16_t *)(const void *)ld_move_up((uint8_t *)(uintptr_t)t->coarse, fine, fb);
    t->base = (const int16_t *)(const void *)ld_move_up((uint8_t *)(uintptr_t)t->fine, base, bb);
    e->table_lo = (uint8_t *)(uintptr_t)t->base;
    ld_tmp_release(&d->mem, e->table_lo);
    return LUMO_OK;
}

/* Every table's c2v: the points, through its rep map (the mesh's border
 * flags are in its rep words; its left-most corners go unread); the
 * table copies follow the blocks ld_eb_drop_dead moves. */
static void ld_eb_sync_tables(struct ld_eb *e)
{
    uint32_t i;
    e->ct.rep = e->rep;
    for (i = 0; i < e->num_attr_data; ++i) {
        ld_attr_data *a = &e->ad[i];
        a->ct = e->ct;
        if (a->shared)
            continue;
        a->ct.seam = a->seam;
        a->ct.rep = a->rep;
    }
}

/* AssignPointsToCorners, with the attribute vertices of RecomputeVertices
 * named by their points instead of a vertex per corner (12 B/face per
 * attribute with seams, issue 25 round five). An attribute's seams cut a
 * mesh vertex's fan into its attribute vertices: on an open fan every
 * crossing starts a vertex, on a closed one each crossing does when there
 * are two or more (with one, RecomputeVertices starts the fan's only
 * vertex at it). A point is a fan segment no attribute's vertex changes
 * in; libdraco starts a closed fan at the first change of the first
 * attribute that has one (`dedup`). Per point and attribute, rep holds the
 * first point of the point's attribute vertex (on a closed fan the last
 * segment after the walk's last crossing is the first's vertex when no
 * crossing lies at the start) and, in bit 31, the vertex's border flag:
 * the mesh vertex ends a seam or border edge (vseam), as RecomputeVertices
 * set it. Every corner must get a point; an open fan must start at its
 * left end, and a closed one with vertex seam flags must be crossed (as
 * RecomputeVertices' swing left required). */
typedef struct ld_cut {
    const uint8_t *seam;
    uint32_t *rep;
    uint32_t k;        /* crossings of the fan */
    uint32_t seen;     /* ... met by the walk from the fan's start */
    uint32_t cur;      /* rep word of the walk's current vertex */
    uint32_t first;    /* ... of the walk's first vertex */
    uint8_t cuts;      /* its crossings change its vertex on this fan */
    uint8_t wrap;      /* the last segment is the first's vertex */
} ld_cut;

/* The fan of vertex v from its left-most corner c: its crossings per
 * attribute and whether it closes. */
static LD_FORCE_INLINE lumo_status ld_eb_fan_cuts(const struct ld_eb *e, uint32_t c, ld_cut *cut,
                                                  uint32_t n, uint64_t *budget, int *closed,
                                                  int packed)
{
    uint32_t act = c, i;
    *closed = 0;
    for (i = 0; i < n; ++i)
        cut[i].k = 0;
    for (;;) {
        const uint32_t nx = ld_eb_mswing_right(e, act, packed);
        if (nx == LD_INV)
            return LUMO_OK;
        if (*budget == 0)
            return LUMO_ERR_LIMIT;
        --*budget;
        for (i = 0; i < n; ++i)  /* the edge between act and nx */
            cut[i].k += (uint32_t)ld_seam(cut[i].seam, ld_next_v(nx));
        if (nx == c) {
            *closed = 1;
            return LUMO_OK;
        }
        act = nx;
    }
}

/* The fan's start: libdraco's dedup corner of a closed fan (the first
 * change of the first attribute with one), else c. */
static LD_FORCE_INLINE uint32_t ld_eb_fan_start(const struct ld_eb *e, uint32_t c, const ld_cut *cut,
                                                uint32_t n, int packed)
{
    uint32_t i, act;
    for (i = 0; i < n; ++i) {
        if (!cut[i].cuts)
            continue;
        for (act = ld_eb_mswing_right(e, c, packed); act != c;  /* closed: k >= 2 */
             act = ld_eb_mswing_right(e, act, packed))
            if (ld_seam(cut[i].seam, ld_next_v(act)))
                return act;
    }
    return c;
}

/* A new point: its rep word for the mesh (`mesh`) and every attribute. */
static LD_FORCE_INLINE lumo_status ld_eb_new_point(ld_cut *cut, uint32_t n, uint32_t *np,
                                                   uint32_t cap, uint32_t *mrep, uint32_t mesh)
{
    uint32_t i;
    if (*np >= cap)
        return LUMO_ERR_CORRUPT;
    mrep[*np] = mesh;
    for (i = 0; i < n; ++i)
        cut[i].rep[*np] = cut[i].cur;
    ++*np;
    return LUMO_OK;
}

/* A fan no attribute's seam or border crosses (no vertex seam flag; most
 * fans): one point, every attribute's vertex and the mesh's its first
 * point. Such a fan is closed (a border edge sets the flags of its ends,
 * ld_add_seam); on a crafted table whose walk still ends, it is open, as
 * the general walk would find. */
static LD_FORCE_INLINE lumo_status ld_eb_fan_point(struct ld_eb *e, uint32_t lc, ld_cut *cut,
                                                   uint32_t nown, uint32_t *np, uint32_t cap,
                                                   uint64_t *budget, uint32_t vmask, int packed)
{
    uint32_t *pts = e->c2v, c = lc, i;
    const uint32_t p0 = *np;
    lumo_status st;
    for (i = 0; i < nown; ++i)
        cut[i].cur = p0;
    if ((st = ld_eb_new_point(cut, nown, np, cap, e->rep, p0)))
        return st;
    do {
        if (*budget == 0)
            return LUMO_ERR_LIMIT;
        --*budget;
        pts[c] = (pts[c] & ~vmask) | p0;
        c = ld_eb_mswing_right(e, c, packed);
    } while (c != LD_INV && c != lc);
    if (c == LD_INV) {  /* open after all: a border, starting at its left end */
        e->rep[p0] |= LD_REP_BORDER;
        if (ld_eb_mopp(e, ld_next_v(lc), packed) != LD_INV)
            return LUMO_ERR_CORRUPT;
    }
    return LUMO_OK;
}

static LD_FORCE_INLINE lumo_status ld_eb_points_run(ld_dec *d, struct ld_eb *e, int packed)
{
    uint64_t budget = e->budget;  /* charged here as by ld_eb_charge */
    uint64_t sum = 0;
    uint32_t v, i, c, np = 0, live = 0, nown = 0, cap;
    /* the faces hold the vertex ids (and, packed, the opposites above
     * vmask): each corner's id becomes its point's, marked vmask until
     * then (ld_eb_pack_ids keeps vmask above every point) */
    uint32_t *pts = d->faces;
    const uint32_t vmask = e->ct.vmask;
    ld_attr_data *own[LD_MAX_ATTR_DATA];
    ld_cut cut[LD_MAX_ATTR_DATA];
    lumo_status st;
    /* only attributes with interior seams cut a fan (ld_eb_attr_tables) */
    for (i = 0; i < e->num_attr_data; ++i) {
        if (!e->ad[i].shared) {
            own[nown] = &e->ad[i];
            cut[nown].seam = e->ad[i].seam;
            cut[nown].rep = e->ad[i].rep;
            own[nown++]->num_avs = 0;
        }
    }
    cap = ld_eb_point_cap(e->num_corners, e->encoded_vertices, ld_eb_ones(e));
    for (c = 0; c < e->num_corners; ++c)
        pts[c] |= vmask;
    for (v = 0; v < e->num_vertices; ++v) {
        const uint32_t lc = e->lmc[v];
        uint32_t start, p0, mesh;
        int closed;
        if (lc == LD_INV)
            continue;
        live++;
        for (i = 0; i < nown && !own[i]->vseam[v]; ++i)
            ;
        if (i == nown) {  /* no seam or border ends here: one point */
            if ((st = ld_eb_fan_point(e, lc, cut, nown, &np, cap, &budget, vmask, packed)))
                return st;
            for (i = 0; i < nown; ++i)
                own[i]->num_avs++;
            continue;
        }
        if ((st = ld_eb_fan_cuts(e, lc, cut, nown, &budget, &closed, packed)))
            return st;
        if (!closed && ld_eb_mopp(e, ld_next_v(lc), packed) != LD_INV)
            return LUMO_ERR_CORRUPT;  /* an open fan starts at its left end */
        for (i = 0; i < nown; ++i) {
            const int vs = own[i]->vseam[v];
            if (vs && ((closed && cut[i].k == 0) || (!closed && !e->hole[v])))
                return LUMO_ERR_CORRUPT;
            cut[i].cuts = (uint8_t)(vs && (!closed || cut[i].k >= 2u));
            own[i]->num_avs += !cut[i].cuts ? 1u : closed ? cut[i].k : cut[i].k + 1u;
        }
        start = closed && !e->hole[v] ? ld_eb_fan_start(e, lc, cut, nown, packed) : lc;
        p0 = np;
        mesh = p0 | (closed ? 0u : LD_REP_BORDER);  /* a border: the fan is open */
        for (i = 0; i < nown; ++i) {
            cut[i].first = cut[i].cur = p0 | (own[i]->vseam[v] ? LD_REP_BORDER : 0u);
            cut[i].seen = 0;
            cut[i].wrap = (uint8_t)(cut[i].cuts && closed && !ld_seam(cut[i].seam, ld_next_v(start)));
        }
        if ((st = ld_eb_new_point(cut, nown, &np, cap, e->rep, mesh)))
            return st;
        pts[start] = (pts[start] & ~vmask) | p0;
        for (c = ld_eb_mswing_right(e, start, packed); c != LD_INV && c != start;
             c = ld_eb_mswing_right(e, c, packed)) {
            int fresh = 0;
            if (budget == 0)
                return LUMO_ERR_LIMIT;
            --budget;
            for (i = 0; i < nown; ++i) {
                if (!cut[i].cuts || !ld_seam(cut[i].seam, ld_next_v(c)))
                    continue;
                fresh = 1;
                cut[i].cur = ++cut[i].seen == cut[i].k && cut[i].wrap
                                 ? cut[i].first
                                 : np | (cut[i].cur & LD_REP_BORDER);
            }
            if (fresh && (st = ld_eb_new_point(cut, nown, &np, cap, e->rep, mesh)))
                return st;
            pts[c] = (pts[c] & ~vmask) | (np - 1u);
        }
    }
    for (c = 0; c < e->num_corners; ++c)  /* every corner in some fan */
        if ((pts[c] & vmask) == vmask)
            return LUMO_ERR_CORRUPT;
    /* the bounds of the arena need: the encoded vertices live (S were
     * merged), an attribute's vertices at most one per corner and V plus
     * two per seam edge, and the points at most the attribute vertices
     * together (each cut of a fan is some attribute's cut; a shared table
     * has one per live vertex) */
    for (i = 0; i < e->num_attr_data; ++i) {
        const ld_attr_data *a = &e->ad[i];
        sum += a->shared ? live : a->num_avs;
        if (!a->shared && (a->num_avs > e->num_corners || a->num_avs > live + 2u * (uint64_t)a->ones))
            return LUMO_ERR_CORRUPT;
    }
    if (np > sum || live > e->encoded_vertices)
        return LUMO_ERR_CORRUPT;
    e->ct.lmc = NULL;
    e->ct.border = NULL;
    e->ct.num_vertices = np;
    d->num_points = np;
    e->budget = budget;
    return LUMO_OK;
}

/* No attribute data with an interior seam (vpoints): AssignPointsToCorners
 * makes one point of each live vertex's fan, in vertex order, so the
 * vertex ids become the point ids: the face array, which holds the vertex
 * map (and, packed, the opposites in its high bits), is renumbered in
 * place, fan by fan, and the left-most corners and vertex seam flags move
 * down to the new ids. No corner table of its own and no point walk (12
 * B/face less than a separate vertex map). A corner is renumbered only by
 * its own vertex's fan and once (the old id is checked), and every corner
 * must be: a crafted table cannot leave a stale id in the output. */
static LD_FORCE_INLINE lumo_status ld_eb_renumber_run(ld_dec *d, struct ld_eb *e, int packed)
{
    uint64_t budget = e->budget;  /* charged here as by ld_eb_charge */
    uint32_t *words = e->c2v;
    const uint32_t vmask = e->ct.vmask;
    uint32_t v, i, np = 0, written = 0;
    for (v = 0; v < e->num_vertices; ++v) {
        const uint32_t first = e->lmc[v];
        uint32_t c = first;
        if (first == LD_INV)
            continue;
        do {
            if ((words[c] & vmask) != v)
                return LUMO_ERR_CORRUPT;
            if (budget == 0)
                return LUMO_ERR_LIMIT;
            --budget;
            words[c] = (words[c] & ~vmask) | np;
            ++written;
            c = ld_eb_mswing_right(e, c, packed);
        } while (c != LD_INV && c != first);
        e->lmc[np] = first;
        for (i = 0; i < e->num_attr_data; ++i)
            e->ad[i].vseam[np] = e->ad[i].vseam[v];
        ++np;
    }
    /* every corner renumbered; the live vertices are the header's V (the
     * arena need takes P = V) */
    if (written != e->num_corners || np != e->encoded_vertices)
        return LUMO_ERR_CORRUPT;
    e->budget = budget;
    e->num_vertices = np;
    e->ct.num_vertices = np;
    d->num_points = np;
    return LUMO_OK;
}

/* vpoints, after the renumbering: a vertex is on a border exactly when a
 * border edge ends there, which every attribute data's vertex seam flags
 * mark (no interior seam: ld_add_seam marked border edges only), so the
 * mesh's traversal reads those as its border bytes and the left-most
 * corners go: the work below them (the packed table, lean, and the vertex
 * seam flags) moves up over their block (4 B per vertex less next to the
 * values). Then the attribute data's tables are the mesh's. */
static void ld_eb_vpoints_tables(ld_dec *d, struct ld_eb *e)
{
    uint8_t *lo = ld_tmp_mark(&d->mem), *end = (uint8_t *)e->lmc;
    const size_t shift = (size_t)(e->lmc_top - end);
    ld_pot *t = &e->ct.opp;
    uint32_t i;
    memmove(lo + shift, lo, (size_t)(end - lo));
    if (e->packed)
        ld_pot_moved(t, shift);
    for (i = 0; i < e->num_attr_data; ++i)
        e->ad[i].vseam += shift;
    ld_tmp_release(&d->mem, lo + shift);
    e->lmc = NULL;
    e->ct.lmc = NULL;
    e->ct.border = e->ad[0].vseam;
    for (i = 0; i < e->num_attr_data; ++i) {  /* shared tables, as ld_eb_attr_tables */
        ld_attr_data *a = &e->ad[i];
        a->ct = e->ct;
        a->ct.seam = NULL;
        a->ct.border = a->vseam;
    }
}

/* With seams, the work memory from e->region down holds, top down: hole
 * flags, left-most corners and each attribute's vertex seam flags (read
 * only to assign the points), each own attribute's seam flags, the packed
 * table (lean), the mesh's rep map, each own attribute's rep map, then a
 * sequence's value -> corner map. A block dies when no decoder to come
 * reads it: an attribute's seam flags after its decoder's prediction, a
 * rep map after the last traversal of its table. ld_eb_drop_dead moves the
 * live blocks up over the dead ones, top down (each moves up, so a
 * memmove in order is safe), and the pointers with them; the arena-need
 * replay (ld_eb_need_drop_dead) books the same sizes. `from_seam` and
 * `from_rep`: the first decoder still to read seam flags and rep maps;
 * -1 before the decoders are known (the point assignment: only its own
 * blocks die). */
static size_t ld_eb_round8(size_t n) { return (n + 7u) & ~(size_t)7u; }

/* Whether decoder `from` or a later one reads the mesh's table. */
static int ld_eb_mesh_read(const ld_dec *d, const struct ld_eb *e, int from)
{
    int j;
    if (from < 0)
        return 1;
    for (j = from; j < (int)d->num_decoders; ++j) {
        const int8_t ad = e->dec_att_data[j];
        if (ad < 0 || e->dec_type[j] == 0 || e->ad[ad].shared)
            return 1;
    }
    return 0;
}

static uint8_t *ld_eb_drop_dead(ld_dec *d, struct ld_eb *e, int from_seam, int from_rep,
                              const uint32_t **v2c, uint32_t n_v2c)
{
    uint8_t *dst = e->region;
    const size_t rb = ld_eb_round8((size_t)e->rep_cap * 4u);
    uint32_t i;
    e->hole = NULL;  /* hole flags, left-most corners, vertex seam flags */
    e->lmc = NULL;
    for (i = 0; i < e->num_attr_data; ++i) {
        ld_attr_data *a = &e->ad[i];
        a->vseam = NULL;
        if (a->shared || !a->seam)
            continue;
        if (from_seam >= 0 && a->decoder_id < from_seam) {
            a->seam = NULL;
            continue;
        }
        a->seam = dst = ld_move_up(dst, a->seam, ld_seam_bytes(e->num_corners));
    }
    if (e->packed)
        dst = ld_eb_lift_table(e, dst);
    if (e->rep && ld_eb_mesh_read(d, e, from_rep))
        e->rep = (uint32_t *)(void *)(dst = ld_move_up(dst, e->rep, rb));
    else
        e->rep = NULL;
    for (i = 0; i < e->num_attr_data; ++i) {
        ld_attr_data *a = &e->ad[i];
        if (!a->rep)
            continue;
        if (from_rep >= 0 && a->decoder_id < from_rep)
            a->rep = NULL;
        else
            a->rep = (uint32_t *)(void *)(dst = ld_move_up(dst, a->rep, rb));
    }
    if (v2c)
        *v2c = (const uint32_t *)(const void *)ld_move_up(dst, (void *)(uintptr_t)*v2c,
                                                                (size_t)n_v2c * 4u);
    ld_tmp_release(&d->mem, v2c ? (uint8_t *)(uintptr_t)*v2c : dst);
    ld_eb_sync_tables(e);
    return dst;
}

static lumo_status ld_eb_points(ld_dec *d, struct ld_eb *e)
{
    lumo_status st;
    if (e->num_attr_data == 0) {  /* the output faces are the vertex map */
        d->num_points = e->num_conn_vertices;
        return LUMO_OK;
    }
    if (e->vpoints) {
        st = LD_EB_PACKED(e) ? ld_eb_renumber_run(d, e, 1) : ld_eb_renumber_run(d, e, 0);
        if (!st)
            ld_eb_vpoints_tables(d, e);
        return st;
    }
    st = LD_EB_PACKED(e) ? ld_eb_points_run(d, e, 1) : ld_eb_points_run(d, e, 0);
    if (!st)  /* the point assignment's own blocks go */
        ld_eb_drop_dead(d, e, -1, -1, NULL, 0);
    return st;
}

/* ---- entry points ----------------------------------------------------------------- */

static lumo_status ld_eb_alloc_attr_data(ld_dec *d, struct ld_eb *e);

static lumo_status ld_eb_alloc(ld_dec *d, struct ld_eb *e)
{
    uint32_t i;
    lumo_status st;
    const int seamed = e->num_attr_data && !e->vpoints;  /* interior seams */
    e->num_corners = 3u * e->num_faces;
    d->faces = ld_out(&d->mem, e->num_corners, sizeof(uint32_t));
    /* The corner table's vertex map is the output face array itself:
     * without seams, or without an interior one (vpoints), every vertex is
     * a point (renumbered in place to point order); with seams the points
     * are assigned over the vertex ids in place (ld_eb_points_run: no
     * vertex map of 12 B/face beside the faces, issue 25 round five). */
    e->c2v = d->faces;
    if (!LD_EB_LEAN(e)) {
        e->opp_top = ld_tmp_mark(&d->mem);
        e->opp32 = ld_tmp(&d->mem, e->num_corners, sizeof(uint32_t));
    }
    /* hole flags are read only to assign points along seams */
    e->region = ld_tmp_mark(&d->mem);
    e->hole = seamed ? ld_tmp(&d->mem, (size_t)e->max_vertices + 3u, 1) : NULL;
    e->lmc_top = ld_tmp_mark(&d->mem);  /* the border bytes take its top */
    e->lmc = ld_tmp(&d->mem, (size_t)e->max_vertices + 3u, sizeof(uint32_t));
    /* the seam reading's tables above the 24-bit table, which moves up
     * over the seam flags that go (ld_eb_attr_tables) before it is packed */
    if (e->lmc && (st = ld_eb_alloc_attr_data(d, e)))
        return st;
    if (LD_EB_LEAN(e)) {
        e->o24_top = ld_tmp_mark(&d->mem);  /* lowest: packed in place, ld_eb_pack */
        e->o24 = ld_tmp(&d->mem, 3u * (size_t)e->num_corners + 1u, 1);
    }
    if (!d->faces || !(e->o24 || e->opp32) || !e->lmc || (!e->hole && seamed))
        return LUMO_ERR_NOMEM;
    /* No fill of c2v and the opposites: every symbol writes the three
     * vertices of its face and clears its three opposites before anything
     * reads them (corners reach the decoder only from faces already
     * decoded). */
    if (e->hole)
        memset(e->hole, 1, (size_t)e->max_vertices + 3u);
    e->ct.c2v = e->c2v;
    e->ct.opp32 = e->opp32;
    e->ct.vmask = 0xFFFFFFFFu;
    e->ct.seam = NULL;
    e->ct.lmc = e->lmc;
    e->ct.num_corners = e->num_corners;
    e->pos_decoder = -1;
    e->budget = (uint64_t)64u * e->num_corners + 4096u;
    for (i = 0; i < e->num_attr_data; ++i) {
        ld_attr_data *a = &e->ad[i];
        a->decoder_id = -1;
        a->connectivity_used = 1;
    }
    return LUMO_OK;
}

/* The seam reading's tables: every vertex seam flag block, then every
 * corner seam flag block (lowest), so the seam flags of attributes without
 * interior seams can go when they are read (ld_eb_attr_tables). */
static lumo_status ld_eb_alloc_attr_data(ld_dec *d, struct ld_eb *e)
{
    uint32_t i;
    for (i = 0; i < e->num_attr_data; ++i) {
        ld_attr_data *a = &e->ad[i];
        a->vseam = ld_tmp(&d->mem, e->max_vertices + 1u, 1);
        if (!a->vseam)
            return LUMO_ERR_NOMEM;
        memset(a->vseam, 0, e->max_vertices + 1u);
    }
    e->seam_top = ld_tmp_mark(&d->mem);
    for (i = 0; i < e->num_attr_data; ++i) {
        ld_attr_data *a = &e->ad[i];
        a->seam = ld_tmp(&d->mem, ld_seam_bytes(e->num_corners), 1);
        if (!a->seam)
            return LUMO_ERR_NOMEM;
        memset(a->seam, 0, ld_seam_bytes(e->num_corners));
    }
    return LUMO_OK;
}

/* An attribute whose seam bits mark no interior edge splits no vertex (its
 * seams are the mesh's borders): its corner table is the mesh's, read with
 * its vertex seam flags as the depth-first walk's border bytes (a vertex
 * is on a border exactly when a border edge ends there, ld_add_seam), and
 * its seam flags go. The others keep their seam flags, moved up over the
 * dead ones, and get a rep word per point (ld_eb_points_run: 4 B per point
 * bound instead of a vertex per corner and a border byte per vertex). */
static lumo_status ld_eb_attr_tables(ld_dec *d, struct ld_eb *e)
{
    uint8_t *top = e->seam_top;
    uint32_t i, cap;
    lumo_status st;
    for (i = 0; i < e->num_attr_data; ++i) {
        ld_attr_data *a = &e->ad[i];
        /* Decided on the interior edges' bits, the only ones the encoder
         * writes and libdraco reads. The arena need, which cannot tell
         * interior edges from borders without the connectivity, counts
         * the ones up to where the coder ends (ld_rabs_done, checked by
         * ld_eb_seams_run): the same bits. (Round two counted the first
         * 3F/2 bits: on an open mesh the coder's output past its end held
         * ones, and colours without a seam kept a table of their own.) */
        a->shared = a->ones == 0;
        if (e->vpoints && !a->shared)
            return LUMO_ERR_CORRUPT;  /* the peek saw no one (ld_eb_peek_vpoints) */
        if (a->shared) {
            a->ct = e->ct;
            a->ct.seam = NULL;
            a->ct.lmc = NULL;
            a->ct.border = a->vseam;
            a->seam = NULL;
            continue;
        }
        top = ld_move_up(top, a->seam, ld_seam_bytes(e->num_corners));
        a->seam = top;
    }
    if (LD_EB_LEAN(e)) {  /* the 24-bit table moves up over the dead flags */
        e->o24 = ld_move_up(top, e->o24, 9u * (size_t)e->num_faces + 1u);
        e->o24_top = top;
        top = e->o24;
    }
    ld_tmp_release(&d->mem, top);
    if (LD_EB_LEAN(e) && (st = ld_eb_pack(d, e)))
        return st;
    if (e->vpoints)
        return LUMO_OK;
    cap = ld_eb_point_cap(e->num_corners, e->encoded_vertices, ld_eb_ones(e));
    e->rep_cap = cap;
    e->rep = ld_tmp(&d->mem, cap, sizeof(uint32_t));
    if (!e->rep)
        return LUMO_ERR_NOMEM;
    for (i = 0; i < e->num_attr_data; ++i) {
        ld_attr_data *a = &e->ad[i];
        if (a->shared)
            continue;
        a->rep = ld_tmp(&d->mem, cap, sizeof(uint32_t));
        if (!a->rep)
            return LUMO_ERR_NOMEM;
    }
    return LUMO_OK;
}

lumo_status ld_eb_decode_connectivity(ld_dec *d)
{
    struct ld_eb *e;
    uint8_t *mark;
    uint32_t verts, faces, symbols, splits;
    uint8_t type, nad;
    lumo_status st;
    if ((st = ld_u8(&d->buf, &type)))
        return st;
    if (type != 0 && type != 2)
        return LUMO_ERR_UNSUPPORTED;  /* predictive EdgeBreaker: pre-2.2 only */
    if ((st = ld_varint32(&d->buf, &verts)) || (st = ld_varint32(&d->buf, &faces)))
        return st;
    if (faces > (d->lean ? LD_MAX_EB_FACES : LD_MAX_FACES))
        return LUMO_ERR_LIMIT;
    if ((uint64_t)verts > (uint64_t)faces * 3u)
        return LUMO_ERR_CORRUPT;
    if ((st = ld_u8(&d->buf, &nad)) || (st = ld_varint32(&d->buf, &symbols)))
        return st;
    if (faces < symbols || faces > symbols + symbols / 3u)
        return LUMO_ERR_CORRUPT;
    if ((st = ld_varint32(&d->buf, &splits)))
        return st;
    if (splits > symbols)
        return LUMO_ERR_CORRUPT;
    if (nad > LD_MAX_ATTR_DATA)
        return LUMO_ERR_UNSUPPORTED;
    e = ld_tmp(&d->mem, 1, sizeof *e);
    if (!e)
        return LUMO_ERR_NOMEM;
    memset(e, 0, sizeof *e);
    d->eb = e;
    d->connectivity = type;
    e->lean = d->lean;
    e->valence = type == 2;
    e->num_faces = faces;
    e->num_attr_data = nad;
    e->max_vertices = verts + splits;
    e->encoded_vertices = verts;
    e->vpoints = (uint8_t)(nad && ld_eb_peek_vpoints(&d->buf, faces, nad, e->valence));
    if ((st = ld_eb_alloc(d, e)))
        return st;
    mark = ld_tmp_mark(&d->mem);  /* symbol-phase work memory from here */
    if ((st = ld_eb_splits(d, e)))
        return st;
    if (!e->valence && (st = ld_eb_start_standard(d, e)))
        return st;
    if ((st = ld_eb_start_common(d, e)))
        return st;
    if (e->valence && (st = ld_eb_start_valence(d, e)))
        return st;
    if ((st = ld_eb_traverse(d, e, symbols, splits)))
        return st;
    /* every announced vertex is created and, without seams (where merged
     * vertices are counted), S of them merge: the counts the arena need
     * (lumo_draco_arena_need) takes from the header */
    if (e->num_vertices != e->max_vertices || (!nad && e->num_conn_vertices != verts))
        return LUMO_ERR_CORRUPT;
    ld_tmp_release(&d->mem, mark);
    memset(&e->val, 0, sizeof e->val);
    e->ct.num_vertices = e->num_vertices;
    /* without seams the first sequence, which knows the traversals, drops
     * the left-most corners (default) or packs the table or reads it as
     * decoded (lean, ld_eb_reads_o24); with seams ld_eb_attr_tables packs
     * it once the seams are read */
    d->num_faces = faces;
    if (nad && (st = ld_eb_seams(e)))
        return st;
    if (nad && (st = ld_eb_attr_tables(d, e)))
        return st;
    return ld_eb_points(d, e);
}

lumo_status ld_eb_create_attributes_decoder(ld_dec *d, unsigned decoder, ld_seq *seq,
                                            uint8_t *traversal, uint8_t *vertex_attr)
{
    struct ld_eb *e = d->eb;
    int8_t att_data;
    uint8_t type, trav;
    lumo_status st;
    (void)seq;
    if ((st = ld_u8(&d->buf, (uint8_t *)&att_data)) || (st = ld_u8(&d->buf, &type)) ||
        (st = ld_u8(&d->buf, &trav)))
        return st;
    if (trav > 1)
        return LUMO_ERR_CORRUPT;
    if (att_data >= 0) {
        if ((uint32_t)att_data >= e->num_attr_data || e->ad[att_data].decoder_id >= 0)
            return LUMO_ERR_CORRUPT;
        e->ad[att_data].decoder_id = (int32_t)decoder;
    } else {
        if (e->pos_decoder >= 0)
            return LUMO_ERR_CORRUPT;
        e->pos_decoder = (int32_t)decoder;
    }
    if (type == 0) {  /* MESH_VERTEX_ATTRIBUTE */
        if (att_data >= 0)
            e->ad[att_data].connectivity_used = 0;
    } else if (trav != 0 || att_data < 0) {
        return LUMO_ERR_CORRUPT;
    }
    e->dec_att_data[decoder] = att_data;
    e->dec_type[decoder] = type;
    e->dec_traversal[decoder] = trav;
    *traversal = trav;
    *vertex_attr = type == 0;
    return LUMO_OK;
}

/* Lean, no seams: the 24-bit table is as the symbols left it. When the
 * stream's only attributes decoder is walked depth-first and none of its
 * attributes' predictions reads more of the table than each entry's
 * opposite corner (parallelograms, differences, none: positions at -cl
 * 3..8, and at -cl 4 the normals, texture coordinates and colours beside
 * them), the table is read as it is: the traversal flags faces in the
 * table, finds borders in the vertex map and gives each entry its
 * corner's opposite, and then the table goes (ld_eb_release_o24), so it
 * is never packed. Otherwise it is packed before the first traversal.
 * The decode and the arena-need replay (ld_eb_need_sequence) ask alike:
 * this of the decoder, then ld_peek_opposites_only of its attributes at
 * the stream's position (each point has one value). Round five asked
 * only of a decoder with one attribute; round six peeks past each
 * attribute's values to the next one's method (issue 25). */
static int ld_eb_o24_decoder(unsigned decoder, unsigned num_decoders, uint8_t traversal)
{
    return decoder == 0 && num_decoders == 1 && traversal == 0;
}

/* ... and the attributes asked for the decode: the stream's (all of its
 * only decoder's) as the arena-need scan keeps them. */
static int ld_eb_dec_opposites_only(const ld_dec *d)
{
    ld_need_attr a[LUMO_DRACO_MAX_ATTRIBUTES];
    uint32_t i;
    for (i = 0; i < d->num_attrs; ++i) {
        a[i].components = d->attrs[i].num_components;
        a[i].portable = d->attrs[i].num_portable;
        a[i].seq_type = d->attrs[i].modes.seq_type;
        a[i].data_type = d->attrs[i].data_type;
    }
    return ld_peek_opposites_only(&d->buf, a, d->num_attrs, d->num_points);
}

/* The 24-bit table moves up to end at `top`, over dead work memory. */
static void ld_eb_lift_o24(ld_dec *d, struct ld_eb *e, uint8_t *top)
{
    e->o24 = ld_move_up(top, e->o24, 9u * (size_t)e->num_faces + 1u);
    ld_tmp_release(&d->mem, e->o24);
}

/* Before the vertex map is allocated: the left-most corners become the
 * border bytes (ld_eb_border) and the table moves up over the rest ... */
static void ld_eb_keep_o24_begin(ld_dec *d, struct ld_eb *e)
{
    ld_eb_lift_o24(d, e, ld_eb_border(e));
}

/* ... then the vertex map starts as the border flags (-2 on a border,
 * else -1) and the table moves up over the bytes. */
static void ld_eb_fill_vmap(int32_t *restrict vmap, const uint8_t *restrict border, uint32_t n)
{
    uint32_t v;
    for (v = 0; v < n; ++v)
        vmap[v] = -1 - (int32_t)border[v];
}

static void ld_eb_keep_o24(ld_dec *d, struct ld_eb *e, int32_t *vmap)
{
    ld_eb_fill_vmap(vmap, e->ct.border, e->num_vertices);
    ld_eb_lift_o24(d, e, e->lmc_top);
    e->ct.border = NULL;
    e->ct.o24 = e->o24;
}

/* A table of a mesh with seams (ld_ct.rep: the mesh's or an attribute's):
 * the traversal's vertex -> value map is the output point map, read at
 * each vertex's first point; then every other point takes its vertex's
 * value (its first point is below it), so the predictions read a corner's
 * value through its point and no vertex map exists (issue 25 round
 * five). At most max_values values. */
static lumo_status ld_eb_rep_sequence(ld_dec *d, unsigned decoder, const ld_ct *ct,
                                      uint32_t max_values, ld_seq *seq)
{
    const uint32_t np = d->num_points, *rep = ct->rep;
    int32_t *map = ld_out(&d->mem, np, sizeof(int32_t));
    ld_order o;
    uint32_t p;
    lumo_status st;
    if (!map)
        return LUMO_ERR_NOMEM;
    o.vertex_to_value = map;
    if ((st = ld_traverse(&d->mem, ct, np, max_values, d->eb->dec_traversal[decoder], &o)))
        return st;
    for (p = 0; p < np; ++p) {  /* unvisited (-1, -3) is huge unsigned */
        const uint32_t x = (uint32_t)map[rep[p] & LD_REP_MASK];
        if (x >= o.num_values)
            return LUMO_ERR_CORRUPT;
        map[p] = (int32_t)x;
    }
    seq->num_entries = o.num_values;
    seq->faces = d->faces;
    seq->faces_mask = ct->vmask;
    seq->vertex_to_value = map;
    seq->value_to_corner = o.value_to_corner;
    seq->point_to_value = (uint32_t *)map;
    /* this traversal was the last of its table's rep map: the dead blocks
     * go before the values (the tables move: ct is a copy in e) */
    seq->work_top = ld_eb_drop_dead(d, d->eb, (int)decoder, (int)decoder + 1, &seq->value_to_corner,
                                  max_values);
    seq->ct = ct;
    return LUMO_OK;
}

/* The 24-bit table read as decoded (ld_eb_keep_o24): the traversal gave
 * each entry its corner's opposite already, which is all the decoder's
 * predictions read of the table (ld_eb_o24_decoder); the table goes at
 * once, the entries move up over it, and the faces are plain vertex ids
 * for every attribute of the decoder (round six: before, the table
 * stayed until the last attribute's prediction released it, so a
 * decoder of several attributes packed it instead). */
static void ld_eb_release_o24(ld_dec *d, ld_seq *seq)
{
    struct ld_eb *e = d->eb;
    const uint32_t *v2c = seq->value_to_corner, n = seq->num_entries;
    e->o24 = NULL;
    e->ct.o24 = NULL;
    seq->value_to_corner =
        (const uint32_t *)(const void *)ld_move_up(e->lmc_top, v2c, (size_t)n * 4u);
    seq->opposites = 1;
    ld_tmp_release(&d->mem, (uint8_t *)(uintptr_t)seq->value_to_corner);
}

lumo_status ld_eb_sequence(ld_dec *d, unsigned decoder, ld_seq *seq)
{
    struct ld_eb *e = d->eb;
    const ld_ct *ct = &e->ct;
    uint32_t vmap = e->num_vertices, c;
    int8_t ad = e->dec_att_data[decoder];
    ld_order o;
    int keep = 0;
    lumo_status st;
    if (ad >= 0) {
        if (e->dec_type[decoder] != 0)
            ct = &e->ad[ad].ct;
        if (e->ad[ad].ct.num_vertices > vmap)
            vmap = e->ad[ad].ct.num_vertices;
    }
    if (ct->rep)  /* with seams: an attribute's vertices, or the mesh's */
        return ld_eb_rep_sequence(d, decoder, ct, ct->seam ? e->ad[ad].num_avs : e->num_vertices,
                                  seq);
    /* else the vertices are the points: the face array is the vertex map,
     * the vertex -> value map the point map, decoded into the output */
    if (!LD_EB_LEAN(e) && !e->num_attr_data && e->lmc && (st = ld_eb_drop_lmc(d, e)))
        return st;  /* default, no seams, first sequence */
    if (e->o24 && !e->ct.o24) {  /* lean, no seams, first sequence */
        keep = ld_eb_o24_decoder(decoder, d->num_decoders, e->dec_traversal[0]) &&
               ld_eb_dec_opposites_only(d);
        if (!keep && (st = ld_eb_pack(d, e)))
            return st;
        if (keep)
            ld_eb_keep_o24_begin(d, e);
    }
    o.vertex_to_value = ld_out(&d->mem, vmap, sizeof(int32_t));
    if (!o.vertex_to_value)
        return LUMO_ERR_NOMEM;
    if (keep)
        ld_eb_keep_o24(d, e, o.vertex_to_value);
    /* read as decoded, the table leaves no room for the split vertices'
     * entries: a mesh without seams has d->num_points vertices in use */
    if ((st = ld_traverse(&d->mem, ct, vmap, keep ? d->num_points : vmap,
                          e->dec_traversal[decoder], &o)))
        return st;
    seq->num_entries = o.num_values;
    seq->faces = d->faces;
    seq->faces_mask = e->ct.vmask;
    seq->ct = ct;
    seq->vertex_to_value = o.vertex_to_value;
    seq->value_to_corner = o.value_to_corner;
    for (c = 0; c < d->num_points; ++c)  /* unvisited (-1) is huge unsigned */
        if ((uint32_t)o.vertex_to_value[c] >= o.num_values)
            return LUMO_ERR_CORRUPT;
    seq->point_to_value = (uint32_t *)o.vertex_to_value;
    if (keep)
        ld_eb_release_o24(d, seq);
    return LUMO_OK;
}

/* The last attributes decoder's only attribute: after its traversal the
 * border bytes are dead, and a parallelogram prediction reads of the
 * corner table only the opposite of each entry's corner. Move the entry
 * corners (or, for `opposites`, their opposite corners) up over the dead
 * blocks and release those, so neither the border bytes nor (for
 * `opposites`) the packed table's escapes stay next to the values. Only
 * for the mesh's own table (no seams: the point map is the vertex map). */
void ld_eb_release_table(ld_dec *d, ld_seq *seq, int opposites)
{
    struct ld_eb *e = d->eb;
    uint32_t *v2c = (uint32_t *)(uintptr_t)seq->value_to_corner, i;
    const uint32_t n = seq->num_entries;
    uint8_t *top;
    if (!e || e->num_attr_data || seq->ct != &e->ct || !(e->packed || e->opp32) || e->released)
        return;
    if (opposites && e->opp32)  /* one loop per store: no test per entry */
        for (i = 0; i < n; ++i)
            v2c[i] = v2c[i] == LD_INV ? LD_INV : e->opp32[v2c[i]];
    else if (opposites)
        for (i = 0; i < n; ++i)
            v2c[i] = v2c[i] == LD_INV ? LD_INV : ld_pot_opp(&e->ct.opp, v2c[i]);
    if (!e->packed) {  /* default: [opposites][border bytes] */
        top = opposites ? e->opp_top : (uint8_t *)e->opp32;
        if (opposites)
            e->opp32 = NULL;
        e->ct.opp32 = e->opp32;
    } else if (opposites) {
        ld_pot_strip(e->c2v, e->num_corners, e->ct.opp.vshift);
        e->packed = 0;
        memset(&e->ct.opp, 0, sizeof e->ct.opp);
        top = e->lmc_top;
    } else {  /* the packed table moves up over the border bytes */
        top = ld_eb_lift_table(e, e->lmc_top);
    }
    seq->value_to_corner = (const uint32_t *)(const void *)ld_move_up(top, v2c, (size_t)n * 4u);
    seq->opposites = (uint8_t)(opposites != 0);
    e->ct.border = NULL;
    e->released = 1;
    ld_tmp_release(&d->mem, (uint8_t *)(uintptr_t)seq->value_to_corner);
}

/* The end of a mesh decode: the face array holds vertex ids alone. */
void ld_eb_finish(ld_dec *d)
{
    struct ld_eb *e = d->eb;
    if (e && e->packed && e->c2v == d->faces)  /* no attribute data, or vpoints */
        ld_pot_strip(e->c2v, e->num_corners, e->ct.opp.vshift);
    if (e)
        e->packed = 0;
}

/* ---- the need before decoding (lumo_draco_arena_need) ----------------------- *
 * The replay of ld_eb_decode_connectivity and ld_eb_sequence on byte
 * counts. Exact from the header: faces F, vertices V + S (the decode
 * checks every created vertex is announced and, without seams, that S
 * vertices merge), the split table, the valence context symbols. Known
 * only after decoding: the active-corner stack (at most one corner per E
 * symbol, which creates 3 vertices), the traversal's stack or queue (a
 * face pushes at most one corner on the depth-first stack; on the degree
 * queues a face pushes its two neighbours, or one and moves on to the
 * other without a pop, so a start's walk never holds more nodes than its
 * faces + 1, and each start begins with empty queues), and with seams the
 * points and attribute vertices (bounded below by the seam bits). */

static uint32_t ld_eb_need_vertices(const ld_eb_need *e) { return e->verts + e->splits; }

static lumo_status ld_eb_need_splits(ld_buf *b, ld_need *k, uint32_t faces, uint32_t *num)
{
    uint32_t n, i, last = 0;
    ld_bits bits;
    lumo_status st = ld_varint32(b, &n);
    if (st)
        return st;
    *num = n;
    if (n == 0)
        return LUMO_OK;
    if (n > faces)
        return LUMO_ERR_CORRUPT;
    ld_need_tmp(k, n, sizeof(uint32_t));
    ld_need_tmp(k, n, sizeof(uint32_t));
    ld_need_tmp(k, n, 1);
    for (i = 0; i < n; ++i) {
        uint32_t delta, src;
        if ((st = ld_varint32(b, &delta)))
            return st;
        src = delta + last;
        if ((st = ld_varint32(b, &delta)))
            return st;
        if (delta > src)
            return LUMO_ERR_CORRUPT;
        last = src;
    }
    ld_bits_start(&bits, b);
    for (i = 0; i < n; ++i)
        (void)ld_bits_get(&bits, 1);
    ld_bits_end(&bits, b);
    return LUMO_OK;
}

/* Whether no attribute data's seam bits, up to where its coder ends
 * (ld_rabs_done), hold a one: no interior seam anywhere, so the decode
 * keeps no vertex map of its own (vpoints). Asked by the decode before it
 * allocates and by the arena need alike, on a copy of the stream at the
 * split data; stops at the first one. A stream it cannot read answers 0
 * (the decode then fails where it reads the same bytes). */
static int ld_eb_peek_vpoints(const ld_buf *at, uint32_t faces, uint32_t nad, int valence)
{
    const uint32_t edges = (uint32_t)((3u * (uint64_t)faces) / 2u);
    ld_buf b = *at;
    ld_need k;
    ld_rabs r;
    uint64_t size;
    uint32_t i, j, n;
    memset(&k, 0, sizeof k);
    if (ld_eb_need_splits(&b, &k, faces, &n))
        return 0;
    if (!valence && (ld_varint64(&b, &size) || ld_skip(&b, size)))
        return 0;
    for (i = 0; i <= nad; ++i) {  /* start faces, then one seam stream each */
        if (ld_rabs_start(&r, &b))
            return 0;
        for (j = 0; i > 0 && j < edges && !ld_rabs_done(&r); ++j)
            if (ld_rabs_bit(&r))
                return 0;
    }
    return 1;
}

static lumo_status ld_eb_need_symbols(ld_buf *b, ld_need *k, ld_eb_need *e)
{
    ld_rabs r;
    uint32_t i, n;
    uint64_t size;
    lumo_status st;
    if (!e->valence && ((st = ld_varint64(b, &size)) || (st = ld_skip(b, size))))
        return st;
    for (i = 0; i <= e->nad; ++i) {  /* start faces, then one seam stream each */
        const uint32_t edges = (uint32_t)((3u * (uint64_t)e->faces) / 2u);
        uint32_t j;
        if ((st = ld_rabs_start(&r, b)))
            return st;
        /* the decode reads one bit per interior edge, at most 3F/2, and
         * checks that the coder ends there (ld_rabs_done): the ones of
         * those bits are the interior seams */
        for (j = 0; i > 0 && j < edges && !ld_rabs_done(&r); ++j)
            e->seam_ones[i - 1u] += (uint32_t)ld_rabs_bit(&r);
    }
    if (!e->valence)
        return LUMO_OK;
    ld_need_tmp(k, (size_t)ld_eb_need_vertices(e) + 3u, LD_EB_LEAN(e) ? 1u : sizeof(uint32_t));
    for (i = 0; i < LD_VALENCE_CONTEXTS; ++i) {
        if ((st = ld_varint32(b, &n)))
            return st;
        if (n > e->faces)
            return LUMO_ERR_CORRUPT;
        if (n == 0)
            continue;
        if ((st = ld_need_symbols(b, k, n, 1, NULL)))
            return st;
        ld_need_tmp(k, n, 1);
    }
    return LUMO_OK;
}

/* The symbol loop's tables and its active-corner stack. */
static void ld_eb_need_traverse(ld_need *k, const ld_eb_need *e, uint32_t num_splits)
{
    const uint64_t max_e = ld_eb_need_vertices(e) / 3u;
    if (num_splits) {
        uint32_t slots = 2u;
        while (slots < 2u * num_splits)
            slots <<= 1;
        ld_need_tmp(k, slots, sizeof(uint32_t));
        ld_need_tmp(k, slots, sizeof(uint32_t));
    }
    if (e->nad == 0)
        ld_need_tmp(k, (size_t)e->splits + 1u, sizeof(uint32_t));
    ld_need_free(k, (size_t)ld_need_pick(k, e->symbols ? 1u : 0u,
                                         max_e < e->symbols ? max_e : e->symbols) * 4u);
}

/* ld_eb_pack: the indices below the 24-bit table, then escapes and
 * indices moved up to end at work level `top`. How many corners escape is
 * known only after decoding: none at best, every corner at worst. */
static void ld_eb_need_pack(ld_need *k, ld_eb_need *e, size_t top)
{
    const uint64_t corners = 3u * (uint64_t)e->faces;
    uint64_t ones = 0;
    uint32_t i;
    unsigned vshift;
    size_t ew, cb, fb, bb;
    for (i = 0; i < e->nad; ++i)
        ones += e->seam_ones[i];
    vshift = ld_pot_vshift(ld_eb_pack_ids((uint32_t)ld_eb_need_vertices(e), (uint32_t)corners, e->verts,
                                          ones, e->nad && !e->vpoints));
    ew = vshift > LD_POT_MAX_VSHIFT ? 3u : ld_pot_escape_width((uint32_t)corners, vshift);
    cb = ld_need_bytes((size_t)((corners + 1023u) >> LD_POT_COARSE), 4u);
    fb = ld_need_bytes((size_t)((corners + 15u) >> LD_POT_BLOCK), 2u);
    bb = ld_need_bytes(ld_pot_bases(corners), 4u);
    ld_need_tmp(k, cb, 1);
    ld_need_tmp(k, fb, 1);
    ld_need_tmp(k, bb, 1);
    e->w_table = ld_need_bytes((size_t)ld_need_pick(k, 0u, corners), ew) + cb + fb + bb;
    ld_need_release(k, top + e->w_table);
}

static uint64_t ld_eb_need_ones(const ld_eb_need *e)
{
    uint64_t ones = 0;
    uint32_t i;
    for (i = 0; i < e->nad; ++i)
        ones += e->seam_ones[i];
    return ones;
}

/* ld_eb_drop_dead's blocks as work in use: the seam flags, the packed
 * table and the rep maps still read from decoders from_seam and from_rep
 * on, under the work above them. */
static int ld_eb_need_decoder_of(const ld_eb_need *e, uint32_t ad)
{
    unsigned j;
    for (j = 0; j < e->num_decoders; ++j)
        if (e->dec_att_data[j] == (int8_t)ad)
            return (int)j;
    return -1;
}

static size_t ld_eb_need_drop_dead(const ld_eb_need *e, int from_seam, int from_rep)
{
    const size_t rb = ld_need_bytes(ld_eb_point_cap(3u * e->faces, e->verts, ld_eb_need_ones(e)), 4u);
    size_t w = e->w_region + (e->lean ? e->w_table : 0u);
    int mesh = from_rep < 0;
    uint32_t i;
    unsigned j;
    for (j = from_rep < 0 ? 0u : (unsigned)from_rep; j < e->num_decoders; ++j)
        mesh |= e->dec_att_data[j] < 0 || e->dec_type[j] == 0 || e->ad_shared[e->dec_att_data[j]];
    w += mesh ? rb : 0u;
    for (i = 0; i < e->nad; ++i) {
        const int dec = ld_eb_need_decoder_of(e, i);
        if (e->ad_shared[i])
            continue;
        if (from_seam < 0 || dec >= from_seam)
            w += ld_need_bytes(ld_seam_bytes(3u * e->faces), 1);
        if (from_rep < 0 || dec >= from_rep)
            w += rb;
    }
    return w;
}

lumo_status ld_eb_need_connectivity(ld_buf *b, ld_need *k, ld_eb_need *e, int lean)
{
    uint32_t verts, faces, symbols, splits, num_splits, i, own = 0;
    uint64_t ones = 0;
    size_t mark, seam_top, top;
    uint8_t type, nad;
    lumo_status st;
    if ((st = ld_u8(b, &type)))
        return st;
    if (type != 0 && type != 2)
        return LUMO_ERR_UNSUPPORTED;
    if ((st = ld_varint32(b, &verts)) || (st = ld_varint32(b, &faces)))
        return st;
    if (faces > (lean ? LD_MAX_EB_FACES : LD_MAX_FACES))
        return LUMO_ERR_LIMIT;
    if ((uint64_t)verts > (uint64_t)faces * 3u)
        return LUMO_ERR_CORRUPT;
    if ((st = ld_u8(b, &nad)) || (st = ld_varint32(b, &symbols)))
        return st;
    if (faces < symbols || faces > symbols + symbols / 3u)
        return LUMO_ERR_CORRUPT;
    if ((st = ld_varint32(b, &splits)))
        return st;
    if (splits > symbols)
        return LUMO_ERR_CORRUPT;
    if (nad > LD_MAX_ATTR_DATA)
        return LUMO_ERR_UNSUPPORTED;
    memset(e, 0, sizeof *e);
    e->valence = type == 2;
    e->lean = (uint8_t)lean;
    e->faces = faces;
    e->verts = verts;
    e->splits = splits;
    e->symbols = symbols;
    e->nad = nad;
    e->vpoints = (uint8_t)(nad && ld_eb_peek_vpoints(b, faces, nad, e->valence));
    /* ld_eb_decode_connectivity, ld_eb_alloc */
    ld_need_tmp(k, 1, sizeof(struct ld_eb));
    ld_need_out(k, 3u * (size_t)faces, sizeof(uint32_t));
    e->w_opp_top = k->work;
    if (!lean)
        ld_need_tmp(k, 3u * (size_t)faces, sizeof(uint32_t));
    e->w_region = k->work;
    if (nad && !e->vpoints)
        ld_need_tmp(k, (size_t)ld_eb_need_vertices(e) + 3u, 1);
    e->w_lmc_top = k->work;
    ld_need_tmp(k, (size_t)ld_eb_need_vertices(e) + 3u, sizeof(uint32_t));
    for (i = 0; i < nad; ++i)  /* ld_eb_alloc_attr_data */
        ld_need_tmp(k, (size_t)ld_eb_need_vertices(e) + 1u, 1);
    seam_top = k->work;
    for (i = 0; i < nad; ++i)
        ld_need_tmp(k, ld_seam_bytes(3u * faces), 1);
    if (lean)
        ld_need_tmp(k, 9u * (size_t)faces + 1u, 1);
    mark = k->work;
    if ((st = ld_eb_need_splits(b, k, faces, &num_splits)) || (st = ld_eb_need_symbols(b, k, e)))
        return st;
    ld_eb_need_traverse(k, e, num_splits);
    ld_need_release(k, mark);
    /* ld_eb_attr_tables: shared when the interior edges' bits hold no
     * one (ld_eb_need_symbols counted them); the 24-bit table moves up
     * under the seam flags kept, and is packed there */
    for (i = 0; i < nad; ++i) {
        e->ad_shared[i] = e->seam_ones[i] == 0;
        own += !e->ad_shared[i];
        ones += e->seam_ones[i];
    }
    top = seam_top + own * ld_need_bytes(ld_seam_bytes(3u * faces), 1);
    if (lean && nad) {
        ld_need_release(k, top + ld_need_bytes(9u * (size_t)faces + 1u, 1));
        ld_eb_need_pack(k, e, top);
    } else if (nad) {
        ld_need_release(k, top);
    }
    for (i = 0; nad && !e->vpoints && i <= nad; ++i)  /* the mesh's and the own tables' rep maps */
        if (i == nad || !e->ad_shared[i])
            ld_need_tmp(k, ld_eb_point_cap(3u * faces, e->verts, ones), sizeof(uint32_t));
    if (nad && !e->vpoints)  /* ld_eb_points: the point assignment's blocks go */
        ld_need_release(k, ld_eb_need_drop_dead(e, -1, -1));
    if (e->vpoints)  /* ld_eb_vpoints_tables: the left-most corners go */
        ld_need_release(k, k->work - ld_need_bytes((size_t)ld_eb_need_vertices(e) + 3u, 4u));
    e->table_live = nad == 0;
    return LUMO_OK;
}

/* ld_eb_create_attributes_decoder's reading and checks. */
lumo_status ld_eb_need_decoder(ld_buf *b, ld_eb_need *e, unsigned decoder)
{
    int8_t att_data;
    uint8_t type, trav;
    lumo_status st;
    if ((st = ld_u8(b, (uint8_t *)&att_data)) || (st = ld_u8(b, &type)) || (st = ld_u8(b, &trav)))
        return st;
    if (trav > 1)
        return LUMO_ERR_CORRUPT;
    if (att_data >= 0) {
        if ((uint32_t)att_data >= e->nad || e->ad_used[att_data])
            return LUMO_ERR_CORRUPT;
        e->ad_used[att_data] = 1;
    } else {
        if (e->pos_used)
            return LUMO_ERR_CORRUPT;
        e->pos_used = 1;
    }
    if (type != 0 && (trav != 0 || att_data < 0))
        return LUMO_ERR_CORRUPT;
    e->dec_att_data[decoder] = att_data;
    e->dec_type[decoder] = type;
    e->dec_traversal[decoder] = trav;
    return LUMO_OK;
}

/* Vertices of attribute data `ad`'s corner table: the value count of its
 * per-corner decoder (every one is visited), when the scan learnt it. */
static uint64_t ld_eb_need_attr_vertices(ld_need *k, const ld_eb_need *e, int ad)
{
    const uint64_t corners = 3u * (uint64_t)e->faces, split = e->verts + 2u * (uint64_t)e->seam_ones[ad];
    uint32_t d;
    for (d = 0; d < e->num_decoders; ++d)
        if (e->dec_att_data[d] == ad && e->dec_type[d] != 0 && e->known[d] != LD_NEED_UNKNOWN)
            return e->known[d];
    return ld_need_pick(k, 1u, split < corners ? split : corners);
}

/* Points cut every vertex fan where any attribute's seams cut it, so
 * max_i A_i <= points <= sum_i A_i (A_i: vertices of attribute data i;
 * the decode checks the upper bound), and at most one per corner. */
uint64_t ld_eb_need_points(ld_need *k, const ld_eb_need *e)
{
    const uint64_t corners = 3u * (uint64_t)e->faces;
    uint64_t sum = 0, max = 0, split = e->verts, a;
    uint32_t i;
    if (e->nad == 0 || e->vpoints)  /* vpoints: the decode checks P = V */
        return e->verts;
    for (i = 0; i < e->nad; ++i) {
        a = ld_eb_need_attr_vertices(k, e, (int)i);
        sum += a;
        max = a > max ? a : max;
        split += 2u * (uint64_t)e->seam_ones[i];
    }
    sum = sum < split ? sum : split;
    return ld_need_pick(k, max, sum < corners ? sum : corners);
}

void ld_eb_need_sequence(ld_need *k, ld_eb_need *e, unsigned decoder, ld_need_seq *s,
                         const ld_buf *b)
{
    const int8_t ad = e->dec_att_data[decoder];
    /* the mesh's corner table, or an attribute's that shares it */
    const int own = ad < 0 || e->dec_type[decoder] == 0 || e->ad_shared[ad];
    const uint64_t corners = 3u * (uint64_t)e->faces;
    /* vertices of the table traversed, and the vertex map's size */
    /* vpoints: the vertices are the V points (ld_eb_renumber_run) */
    const int vmap_faces = !e->nad || e->vpoints;
    const uint64_t verts = e->vpoints ? e->verts : ld_eb_need_vertices(e);
    const uint64_t nv = own ? verts : ld_eb_need_attr_vertices(k, e, ad);
    uint64_t vmap = verts, points = ld_eb_need_points(k, e);
    const size_t o24 = ld_need_bytes(9u * (size_t)e->faces + 1u, 1);
    size_t mark;
    int keep = 0;
    /* with seams every table's vertex map is the output point map
     * (ld_eb_rep_sequence) */
    const int rep = !vmap_faces;
    if (ad >= 0 && !e->ad_shared[ad] && ld_eb_need_attr_vertices(k, e, ad) > vmap)
        vmap = ld_eb_need_attr_vertices(k, e, ad);
    if (!e->nad && !e->settled) {  /* ld_eb_sequence: the left-most corners */
        const size_t border = ld_eb_border_needed(e->num_decoders, e->dec_traversal)
                                  ? ld_need_bytes(ld_eb_need_vertices(e), 1)
                                  : 0u;
        e->settled = 1;
        keep = LD_EB_LEAN(e) && ld_eb_o24_decoder(decoder, e->num_decoders, e->dec_traversal[0]) &&
               ld_peek_opposites_only(b, s->attrs, s->count, (uint32_t)points);
        if (!LD_EB_LEAN(e)) {  /* ld_eb_drop_lmc */
            ld_need_release(k, e->w_lmc_top);
            if (border)
                ld_need_tmp(k, ld_eb_need_vertices(e), 1);
        } else if (!keep) {
            ld_eb_need_pack(k, e, e->w_lmc_top + border);
        } else {  /* ld_eb_keep_o24_begin: the table moves up over the left-most corners */
            ld_need_release(k, e->w_lmc_top + border + o24);
        }
    }
    if (vmap_faces)
        ld_need_out(k, (size_t)vmap, sizeof(int32_t));
    else if (rep)
        ld_need_out(k, (size_t)points, sizeof(uint32_t));
    else
        ld_need_tmp(k, (size_t)vmap, sizeof(int32_t));
    if (keep)  /* ld_eb_keep_o24: ... and over the border bytes */
        ld_need_release(k, e->w_lmc_top + o24);
    ld_need_tmp(k, (size_t)(keep ? points : nv), sizeof(uint32_t));  /* value -> corner */
    mark = k->work;
    if (!keep)  /* else the face flags are in the table (degree walk: per corner) */
        ld_need_tmp(k, e->dec_traversal[decoder] ? (size_t)corners : e->faces, 1);
    if (e->dec_traversal[decoder]) {
        ld_need_free(k, (size_t)ld_need_pick(k, 0u, (uint64_t)e->faces + 1u) * 8u);
    } else {
        ld_need_free(k, (size_t)ld_need_pick(k, 2u, (uint64_t)e->faces + 2u) * 4u);
    }
    ld_need_release(k, mark);
    if (keep)  /* ld_eb_release_o24: the entries move up over the table */
        ld_eb_need_release(e, k, (uint32_t)points, 1);
    s->work_top = 0;
    if (rep) {  /* ld_eb_rep_sequence: the dead blocks go, the value -> corner map moves up */
        s->work_top = ld_eb_need_drop_dead(e, (int)decoder, (int)decoder + 1);
        ld_need_release(k, s->work_top + ld_need_bytes((size_t)nv, sizeof(uint32_t)));
    }
    /* values: every point's value (no seams); with seams one per vertex
     * visited, learnt from a tagged stream (else at most nv) */
    s->uncertain = 0;
    if (vmap_faces)
        s->entries = (uint32_t)points;
    else if (e->known[decoder] != LD_NEED_UNKNOWN)
        s->entries = e->known[decoder];
    else {
        s->entries = (uint32_t)nv;
        s->uncertain = 1;
    }
    s->num_corners = (uint32_t)corners;
    s->mesh = 1;
    s->eb = e;
}

void ld_eb_need_release(ld_eb_need *e, ld_need *k, uint32_t entries, int opposites)
{
    const size_t opp = ld_need_bytes(3u * (size_t)e->faces, 4u);
    const size_t top = !LD_EB_LEAN(e) ? e->w_opp_top + (opposites ? 0u : opp)
                                : e->w_lmc_top + (opposites ? 0u : e->w_table);
    if (!e->table_live)
        return;
    ld_need_release(k, top + ld_need_bytes(entries, sizeof(uint32_t)));
    e->table_live = 0;
}
