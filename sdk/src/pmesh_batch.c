/* pmesh_batch.c — applying one batch record of a progressive-mesh stream
 * (docs/progressive-mesh.md "Batch record"; seed 000 §4.2).
 *
 * Each vertex k of a batch is a vertex split, the inverse of the server's
 * half-edge collapse of k onto its lookup-table parent p. The client keeps,
 * for every vertex, the list of index-buffer corners that currently show
 * it; a split walks only p's list, moving to k the corners of p's fan
 * between the two wings (an interior split: only the fan's rank among
 * the fans p's ring geometry makes likely, or its first wing and length,
 * is coded) or those a bit mask selects (boundary and
 * non-manifold splits), then appends the faces that reappear. A split
 * record is one adaptive binary range code (pmesh_rc.h); its parents are
 * found by a scan of the vertices that may still split in the current
 * collapse round. The work is that of the batch: its vertices, their
 * parents' valences, the vertices the parent scans pass and the new
 * faces, never the mesh.
 *
 * A batch is checked whole before it is kept: the record's CRC and counts,
 * then the Draco payload is decoded into scratch memory, then the splits
 * run while logging every change; any error rolls the log back, so the
 * mesh stays at its last good level. */
#include <string.h>
#include "lumo/draco.h"
#include "lumo/pmesh.h"
#include "lumo_shared/pmesh_shared.h"
#include "lumo/wire.h"
#include "pmesh_rc.h"

#define NIL LUMO_PMESH_NIL

/* The base record's fields are LSB-first bit fields (lumo/wire.h); a split
 * record's are bits of its range code, fixed fields as direct bits (the
 * first one the least significant). A read past the block's end is an
 * error (nonzero), which every caller turns into CORRUPT or TRUNCATED. */
typedef struct {
    lumo_wire_bits wb;
    pmesh_rc       rc;
    int            range;   /* 1: a split record's range code */
} bitreader;

static int read_bits(bitreader *b, unsigned n, uint32_t *out)
{
    if (!b->range)
        return lumo_wire_bits_read(&b->wb, n, out) != LUMO_OK;
    *out = lumo_pmesh_rc_direct(&b->rc, n);
    return b->rc.over;
}

/* tb(c) of docs/progressive-mesh.md §2.3: a value in [0, c) in truncated
 * binary. With n = w(c) and u = 2^n - c, the first n - 1 bits x give x
 * when x < u, else one more bit b gives 2x + b - u. Always < c. */
static int read_trunc(bitreader *b, uint32_t c, uint32_t *out)
{
    unsigned n = lumo_pmesh_field_bits(c);
    uint32_t x, bit, u;
    if (n == 0)
        return *out = 0, 0;
    u = (uint32_t)(((uint64_t)1 << n) - c);
    if (read_bits(b, n - 1, &x))
        return -1;
    if (x < u)
        return *out = x, 0;
    if (read_bits(b, 1, &bit))
        return -1;
    *out = 2 * x + bit - u;
    return 0;
}

/* Elias gamma code of a value >= 1: z zero bits, a one, z low bits. */
static lumo_status read_gamma(bitreader *b, uint32_t *v)
{
    uint32_t z = 0, bit = 0, low;
    while (!bit) {
        if (read_bits(b, 1, &bit))
            return LUMO_ERR_TRUNCATED;
        if (!bit && ++z > 31)
            return LUMO_ERR_CORRUPT;
    }
    if (read_bits(b, z, &low))
        return LUMO_ERR_TRUNCATED;
    *v = (uint32_t)1 << z | low;
    return LUMO_OK;
}

/* ---- one batch in flight --------------------------------------------------- */
typedef struct {
    uint32_t index, first, count;
    const uint8_t *side, *draco;
    uint32_t side_bytes, draco_bytes;
} batch;

typedef struct {
    lumo_pmesh *pm;
    bitreader   br;
    const batch *b;
    const lumo_draco_attribute *res;  /* PREDICTED coding: the residuals */
    int         coded;       /* CODED positions: residuals in the range code */
    uint32_t    log_n;       /* journal entries (3 words each) */
    uint32_t    faces, moves;
    uint32_t    prev_parent; /* the last split's parent (also of the previous
                                record), NIL before the first split */
    uint32_t    round_first; /* first split vertex of the current round */
    uint32_t    last_fan;    /* the previous split was a fan split */
    uint32_t    last_same;   /* the previous split's albedo was its parent's */
    uint32_t    stamped;     /* splits whose parent's round_parent is set */
    uint32_t    split0;      /* the block's first split vertex: the record's
                                first vertex, in the base record the seed's
                                size (batch_parent and stamp_log count from it) */
    uint32_t   *ctx;         /* pm->ctx (pm->ctx_undo keeps the batch's start) */
} split_ctx;

/* One bit of adaptive context `c` of the split record's range code. */
static int read_ctx(split_ctx *s, uint32_t c, uint32_t *bit)
{
    *bit = lumo_pmesh_rc_bit(&s->br.rc, &s->ctx[c]);
    return s->br.rc.over;
}

/* The record's head (docs/progressive-mesh.md §2.2): what the decoder
 * cannot derive. The index, the first vertex and the vertex count follow
 * from the records applied; the CRC covers the index and everything but
 * itself. */
static lumo_status parse_record(const lumo_pmesh *pm, const uint8_t *r, size_t size, batch *b)
{
    lumo_pmesh_record_head rh;
    lumo_status st = lumo_pmesh_read_record_head(r, size, &rh);
    if (st)
        return st;
    size_t need = (size_t)rh.head_bytes + rh.side_bytes + rh.draco_bytes;
    if (size < need)
        return LUMO_ERR_TRUNCATED;
    if (size > need)
        return LUMO_ERR_CORRUPT;
    if (need > pm->h.max_batch_bytes)
        return LUMO_ERR_LIMIT;  /* the Draco scratch is sized for the largest record */
    if (pm->vertex_count == pm->h.vertices)
        return LUMO_ERR_STATE;  /* complete: there is no next batch */
    if ((st = lumo_pmesh_record_check(r, size, pm->batches_applied)))
        return st;              /* damaged, or not the next batch */
    const lumo_pmesh_header *h = &pm->h;
    b->index = pm->batches_applied, b->first = pm->vertex_count;
    b->count = b->first ? h->vertices - b->first : h->base_vertices;
    if (b->first && b->count > h->batch_vertices)
        b->count = h->batch_vertices;
    b->side_bytes = rh.side_bytes, b->draco_bytes = rh.draco_bytes;
    b->side = r + rh.head_bytes, b->draco = b->side + b->side_bytes;
    return LUMO_OK;
}

/* ---- positions: the Draco point cloud ------------------------------------- */
/* The albedo attribute of an HAS_ALBEDO stream: COLOR, uint8 x3. */
static lumo_status find_albedo(const lumo_pmesh *pm, const batch *b, const lumo_draco_mesh *m,
                               const lumo_draco_attribute **rgb)
{
    const lumo_draco_attribute *a = NULL;
    *rgb = NULL;
    if (!(pm->h.flags & LUMO_PMESH_HAS_ALBEDO))
        return LUMO_OK;
    for (uint32_t i = 0; i < m->num_attributes && !a; i++)
        if (m->attributes[i].type == LUMO_DRACO_COLOR)
            a = &m->attributes[i];
    if (!a || a->num_portable != 3 || a->xform != LUMO_DRACO_XFORM_NONE || a->data_type != LUMO_DRACO_DT_UINT8)
        return LUMO_ERR_CORRUPT;
    for (uint32_t p = 0; p < b->count; p++)
        for (unsigned c = 0; c < 3; c++)
            if ((uint32_t)lumo_draco_value(a, p, c) > 255u)
                return LUMO_ERR_RANGE;
    *rgb = a;
    return LUMO_OK;
}

/* The payload must be b->count points with the attribute the stream's
 * position coding names, on the stream's grid. */
static lumo_status check_positions(const lumo_pmesh *pm, const batch *b,
                                   const lumo_draco_mesh *m, const lumo_draco_attribute **pos)
{
    const lumo_pmesh_header *h = &pm->h;
    const lumo_draco_attribute *a = NULL;
    int parent = h->position_coding != LUMO_PMESH_POS_ABSOLUTE;  /* residuals */
    if (m->geometry != LUMO_DRACO_POINT_CLOUD || m->num_points != b->count || m->num_faces)
        return LUMO_ERR_CORRUPT;
    for (uint32_t i = 0; i < m->num_attributes && !a; i++)
        if (m->attributes[i].type == (parent ? LUMO_DRACO_GENERIC : LUMO_DRACO_POSITION))
            a = &m->attributes[i];
    if (!a || a->num_portable != 3 || a->num_components != 3)
        return LUMO_ERR_CORRUPT;
    if (parent && (a->xform != LUMO_DRACO_XFORM_NONE || a->data_type != LUMO_DRACO_DT_INT32))
        return LUMO_ERR_CORRUPT;
    if (!parent) {
        if (a->xform != LUMO_DRACO_XFORM_QUANTIZED || a->quant_bits != h->quant_bits ||
            a->range_bits != h->range_bits)
            return LUMO_ERR_CORRUPT;
        for (int c = 0; c < 3; c++)
            if (a->min_bits[c] != h->origin_bits[c])
                return LUMO_ERR_CORRUPT;  /* every payload shares the stream's grid */
    }
    *pos = a;
    return LUMO_OK;
}

static lumo_status decode_positions(lumo_pmesh *pm, const batch *b, const lumo_draco_attribute **pos,
                                    const lumo_draco_attribute **rgb, lumo_draco_mesh *m)
{
    lumo_arena a;
    lumo_draco_info info;
    lumo_status st = lumo_draco_peek(b->draco, b->draco_bytes, &info);
    if (st)
        return st;
    if (info.geometry != LUMO_DRACO_POINT_CLOUD || info.num_faces)
        return LUMO_ERR_CORRUPT;
    lumo_arena_init(&a, pm->scratch, pm->scratch_bytes);
    st = lumo_draco_decode(b->draco, b->draco_bytes, &a, m);
    if (st == LUMO_ERR_NOMEM)
        return LUMO_ERR_LIMIT;  /* bigger than the header promised */
    if (st || (st = check_positions(pm, b, m, pos)))
        return st;
    return find_albedo(pm, b, m, rgb);
}

/* 0..255 -> Q1.14 [0, 1], rounded. */
static void store_albedo(lumo_pmesh *pm, const batch *b, const lumo_draco_attribute *a)
{
    for (uint32_t i = 0; a && i < b->count; i++)
        for (unsigned c = 0; c < 3; c++) {
            int32_t v = lumo_draco_value(a, i, c);
            pm->albedo[3 * (size_t)(b->first + i) + c] = (lumo_q1_14)lumo_pmesh_albedo_q14((uint32_t)v);
        }
}

/* Grid integers of the batch's vertices into qpos (invisible until the
 * batch is kept): absolute values, or in a PREDICTED base mesh residuals
 * from the previous vertex. Split vertices of PREDICTED streams get theirs
 * during the split (predict_split). */
static lumo_status set_grid(lumo_pmesh *pm, uint32_t k, const int32_t *pred, const int32_t res[3])
{
    int32_t qmax = (int32_t)((1u << pm->h.quant_bits) - 1u);
    for (unsigned c = 0; c < 3; c++) {
        int32_t r = res[c];
        if (r < -qmax || r > qmax)
            return LUMO_ERR_RANGE;
        int32_t q = pred ? pred[c] + r : r;
        if (q < 0 || q > qmax)
            return LUMO_ERR_RANGE;
        pm->qpos[3 * (size_t)k + c] = q;
    }
    return LUMO_OK;
}

static lumo_status grid_value(lumo_pmesh *pm, uint32_t k, const int32_t *pred,
                              const lumo_draco_attribute *a, uint32_t i)
{
    int32_t res[3];
    for (unsigned c = 0; c < 3; c++)
        res[c] = lumo_draco_value(a, i, c);
    return set_grid(pm, k, pred, res);
}

static lumo_status grid_positions(lumo_pmesh *pm, const batch *b, const lumo_draco_attribute *a)
{
    int predicted = pm->h.position_coding != LUMO_PMESH_POS_ABSOLUTE;
    lumo_status st = LUMO_OK;
    if (predicted && b->first)
        return LUMO_OK;
    for (uint32_t i = 0; i < b->count && !st; i++) {
        uint32_t k = b->first + i;
        st = grid_value(pm, k, predicted && i ? pm->qpos + 3 * (size_t)(k - 1) : NULL, a, i);
    }
    return st;
}

/* Grid integer -> metres: origin + q * range / (2^bits - 1), rounded. */
static void store_positions(lumo_pmesh *pm, const batch *b)
{
    int64_t qmax = (int64_t)((1u << pm->h.quant_bits) - 1u);
    for (size_t at = 3 * (size_t)b->first; at < 3 * (size_t)(b->first + b->count); at++) {
        int32_t q = pm->qpos[at];
        pm->pos[at] = pm->origin[at % 3] + (int32_t)(((int64_t)q * pm->range + qmax / 2) / qmax);
    }
}

/* ---- the corner lists and their undo log ---------------------------------- */
static void list_push(lumo_pmesh *pm, uint32_t v, uint32_t corner)
{
    pm->next[corner] = pm->head[v];
    pm->head[v] = corner;
}

static void log_entry(split_ctx *s, uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t *e = s->pm->journal + 3 * (size_t)s->log_n++;
    e[0] = a, e[1] = b, e[2] = c;
}

static lumo_status add_face(split_ctx *s, uint32_t a, uint32_t b, uint32_t c)
{
    lumo_pmesh *pm = s->pm;
    if (s->faces >= s->pm->h.max_batch_faces || pm->face_count >= pm->h.faces)
        return LUMO_ERR_CORRUPT;  /* more faces than the header allows */
    uint32_t f = pm->face_count++, t[3] = {a, b, c};
    for (uint32_t i = 0; i < 3; i++) {
        pm->tris[3 * (size_t)f + i] = t[i];
        list_push(pm, t[i], 3 * f + i);
    }
    log_entry(s, NIL, f, 0);
    s->faces++;
    return LUMO_OK;
}

/* Undo the log newest first: every entry's corners are at the front of
 * their lists again when their turn comes. */
static void rollback_to(split_ctx *s, uint32_t keep)
{
    lumo_pmesh *pm = s->pm;
    while (s->log_n > keep) {
        const uint32_t *e = pm->journal + 3 * (size_t)--s->log_n;
        if (e[0] == NIL) {
            for (uint32_t i = 3; i-- > 0;) {
                uint32_t c = 3 * e[1] + i;
                pm->head[pm->tris[c]] = pm->next[c];
            }
            pm->face_count--;
            continue;
        }
        uint32_t c = e[0], prev = e[1], p = e[2];
        pm->head[pm->tris[c]] = pm->next[c];
        pm->tris[c] = p;
        if (prev == NIL)
            list_push(pm, p, c);
        else
            pm->next[c] = pm->next[prev], pm->next[prev] = c;
    }
}

/* ---- base mesh and vertex splits ------------------------------------------- */
/* The base record's first faces: nf faces of three distinct indices
 * below nv, each in tb(nv). */
static lumo_status read_base_faces(split_ctx *s, uint32_t nv, uint32_t nf)
{
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t t[3];
        for (int i = 0; i < 3; i++)
            if (read_trunc(&s->br, nv, &t[i]))
                return LUMO_ERR_TRUNCATED;
        if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
            return LUMO_ERR_RANGE;
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            return LUMO_ERR_CORRUPT;
        lumo_status st = add_face(s, t[0], t[1], t[2]);
        if (st)
            return st;
    }
    return LUMO_OK;
}

/* Walk p's corners; each mask bit 1 moves that corner to k. Every step
 * reads a bit, so the walk is bounded by the record's size. */
static lumo_status move_corners(split_ctx *s, uint32_t p, uint32_t k, uint32_t *lenp)
{
    lumo_pmesh *pm = s->pm;
    uint32_t prev = NIL, c = pm->head[p], bit;
    *lenp = 0;
    while (c != NIL) {
        uint32_t nextc = pm->next[c];
        if (read_ctx(s, LUMO_PMESH_CTX_MASK, &bit))
            return LUMO_ERR_TRUNCATED;
        if (!bit) {
            prev = c, c = nextc, (*lenp)++;
            continue;
        }
        if (s->moves >= s->pm->h.max_batch_moves)
            return LUMO_ERR_CORRUPT;
        if (prev == NIL)
            pm->head[p] = nextc;
        else
            pm->next[prev] = nextc;
        list_push(pm, k, c);
        pm->tris[c] = k;
        log_entry(s, c, prev, p);
        s->moves++;
        c = nextc;
    }
    return LUMO_OK;
}

/* Neighbour j of v's list: corner j/2, then its face's next (j even) or
 * previous (j odd) vertex. */
static uint32_t list_neighbour(const lumo_pmesh *pm, uint32_t v, uint32_t j)
{
    uint32_t c = pm->head[v];
    for (uint32_t i = j >> 1; c != NIL && i > 0; i--)
        c = pm->next[c];
    if (c == NIL)
        return NIL;  /* unreachable with exact lengths; rejected by the caller */
    uint32_t f = c / 3, r = c % 3;
    return pm->tris[3 * f + (r + 1 + (j & 1)) % 3];
}

/* A vertex named as a neighbour of the given lists in turn (each stage an
 * index with one escape value), else explicitly in w(k) bits. */
static lumo_status read_vertex(split_ctx *s, const uint32_t *lists, const uint32_t *lens, int nlists,
                               uint32_t k, uint32_t *x)
{
    uint32_t j;
    for (int l = 0; l < nlists; l++) {
        if (read_trunc(&s->br, 2 * lens[l] + 1, &j))
            return LUMO_ERR_TRUNCATED;
        if (j > 2 * lens[l])
            return LUMO_ERR_CORRUPT;
        if (j < 2 * lens[l]) {
            *x = list_neighbour(s->pm, lists[l], j);
            return LUMO_OK;
        }
    }
    return read_trunc(&s->br, k, x) ? LUMO_ERR_TRUNCATED : LUMO_OK;
}

/* The third vertex of a reappearing face: a neighbour of k (the wings of a
 * split border k's fan), else of p, else explicit. */
static lumo_status read_third(split_ctx *s, uint32_t p, uint32_t k, uint32_t lp, uint32_t lk,
                              uint32_t *x)
{
    uint32_t lists[2] = {k, p}, lens[2] = {lk, lp};
    return read_vertex(s, lists, lens, 2, k, x);
}

/* The split's kind: an adaptive bit (context: the previous split's kind),
 * 1 for a fan split (the usual interior split); else the code (direct bits
 * in reading order) 1 → a pair, mask split; 0 1 → one face; 0 0 + 4 bits
 * → n faces, every flip explicit. A pair is two faces of opposite winding
 * around (k, p), (k, p, x) first, so no flip is coded. */
static lumo_status read_split_kind(split_ctx *s, uint32_t *n, int *paired, int *fan)
{
    uint32_t bit;
    *paired = *fan = 1;
    *n = 2;
    if (read_ctx(s, LUMO_PMESH_CTX_KIND + s->last_fan, &bit))
        return LUMO_ERR_TRUNCATED;
    s->last_fan = bit;
    if (bit)
        return LUMO_OK;
    *fan = 0;
    if (read_bits(&s->br, 1, &bit))
        return LUMO_ERR_TRUNCATED;
    if (bit)
        return LUMO_OK;
    *paired = 0, *n = 1;
    if (read_bits(&s->br, 1, &bit))
        return LUMO_ERR_TRUNCATED;
    return bit || !read_bits(&s->br, 4, n) ? LUMO_OK : LUMO_ERR_TRUNCATED;
}

/* One reappearing face: (k, p, x) or, flipped, (k, x, p). *flip is read
 * unless `given` (0 or 1) says it. */
static lumo_status read_new_face(split_ctx *s, uint32_t p, uint32_t k, uint32_t lp, uint32_t lk,
                                 int given, uint32_t *flip_out)
{
    uint32_t flip = (uint32_t)given, x;
    lumo_status st;
    if (given < 0 && read_bits(&s->br, 1, &flip))
        return LUMO_ERR_TRUNCATED;
    *flip_out = flip;
    if ((st = read_third(s, p, k, lp, lk, &x)))
        return st;
    if (x >= k || x == p)
        return LUMO_ERR_CORRUPT;
    return flip ? add_face(s, k, x, p) : add_face(s, k, p, x);
}

/* One residual of a CODED stream (docs/progressive-mesh.md §2.3 step 5):
 * its class c (the bit length of |r|, at most quant_bits) in unary,
 * adaptive bits "c > j" by the ring's spread class sc on this axis (and,
 * for j = 0, whether `offset` is 0); then the c - 1 bits
 * under the leading one, most significant first, the first two adaptive
 * (by c and place), the rest direct; then, for c > 0, the sign (1:
 * negative), adaptive by c and `offset` (lumo_pmesh_sign_ctx), the
 * prediction's offset from the parent on this axis. Work: at most
 * 2 quant_bits + 1 bits. */
static lumo_status read_residual(split_ctx *s, uint32_t sc, int32_t offset, int32_t *r)
{
    uint32_t c = 0, bit = 1, v = 1, qbits = s->pm->h.quant_bits;
    while (c < qbits) {
        if (read_ctx(s, lumo_pmesh_res_ctx(sc, c, offset), &bit))
            return LUMO_ERR_TRUNCATED;
        if (!bit)
            break;
        c++;
    }
    if (c == 0)
        return *r = 0, LUMO_OK;
    for (uint32_t j = 1; j < c; j++) {
        int over = j < 3 ? read_ctx(s, lumo_pmesh_res_low_ctx(c, j - 1), &bit) : read_bits(&s->br, 1, &bit);
        if (over)
            return LUMO_ERR_TRUNCATED;
        v = v << 1 | bit;
    }
    if (read_ctx(s, lumo_pmesh_sign_ctx(c, offset), &bit))
        return LUMO_ERR_TRUNCATED;
    *r = bit ? -(int32_t)v : (int32_t)v;
    return LUMO_OK;
}

/* LATTICE streams: whether axis d copies a ring coordinate (the copy
 * flag, by how many ring vertices repeat a value), and which: its rank
 * among the ring's distinct values, nearest the prediction first, in
 * unary (docs/progressive-mesh.md §2.3 step 5). *copied is 0 when the
 * residual follows instead. Work: RING_MAX^2 at most. */
static lumo_status read_copy(split_ctx *s, const lumo_pmesh_ring *ring, unsigned d, int32_t *value,
                             int *copied)
{
    int32_t cand[LUMO_PMESH_RING_MAX];
    uint32_t ctx, bit, r = 0, m = lumo_pmesh_lattice_values(s->pm->qpos, ring, d, cand, &ctx);
    if (read_ctx(s, ctx, &bit))
        return LUMO_ERR_TRUNCATED;
    *copied = (int)bit;
    while (bit && r + 1 < m) {
        if (read_ctx(s, lumo_pmesh_copy_rank_ctx(r), &bit))
            return LUMO_ERR_TRUNCATED;
        r += bit;
    }
    *value = cand[r];
    return LUMO_OK;
}

/* k appears among its neighbours: lumo_pmesh_predict_position (shared
 * with the stream writer), plus the residual from the payload or, CODED,
 * from the range code (or, LATTICE, a coordinate copied from the ring).
 * Work: k's valence squared. */
static lumo_status predict_split(split_ctx *s, uint32_t k)
{
    lumo_pmesh *pm = s->pm;
    lumo_pmesh_ring ring;
    int32_t res[3];
    uint32_t p = pm->batch_parent[k - s->split0];
    lumo_pmesh_predict_position(pm->qpos, pm->tris, pm->head, pm->next, k, p,
                                pm->h.flags & LUMO_PMESH_LATTICE, &ring);
    if (!s->coded)
        return grid_value(pm, k, ring.pred, s->res, k - s->b->first);
    for (unsigned d = 0; d < 3; d++) {
        int copied = 0;
        int32_t value;
        lumo_status st = pm->h.flags & LUMO_PMESH_LATTICE ? read_copy(s, &ring, d, &value, &copied) : LUMO_OK;
        if (!st && copied)
            res[d] = value - ring.pred[d];  /* both on the grid: no overflow */
        else if (!st)
            st = read_residual(s, ring.sc[d], ring.pred[d] - pm->qpos[3 * (size_t)p + d], &res[d]);
        if (st)
            return st;
    }
    return set_grid(pm, k, ring.pred, res);
}

/* Explicit split: the mask over p's corners, then the faces. */
static lumo_status mask_split(split_ctx *s, uint32_t p, uint32_t k, uint32_t n, int paired)
{
    uint32_t lenp, flip = 0, moves_before = s->moves;
    lumo_status st = move_corners(s, p, k, &lenp);
    uint32_t lenk = s->moves - moves_before;
    for (uint32_t i = 0; i < n && !st; i++, lenp++, lenk++)
        st = read_new_face(s, p, k, lenp, lenk, paired ? (int)i : -1, &flip);
    return st;
}

/* Fan splits walk p's list at most this long (bounded work per split). */
#define FAN_MAX_CORNERS 255u

static uint32_t list_length(const lumo_pmesh *pm, uint32_t v, uint32_t cap)
{
    uint32_t n = 0;
    for (uint32_t c = pm->head[v]; c != NIL && n <= cap; c = pm->next[c])
        n++;
    return n;
}

/* Fan length m (moved corners): a fixed prefix code for the common 1 … 5
 * (an interior vertex of valence 6 moves 3). Bits in reading order:
 * 0 0 → 3, 1 0 → 4, 0 1 → 2, 1 1 0 b → 1 (b = 0) or 5 (b = 1),
 * 1 1 1 then gamma(m + 1) for any other m. */
static lumo_status read_fan_length(split_ctx *s, uint32_t *m)
{
    static const uint8_t two[4] = {3, 4, 2, 0};  /* index: first bit + 2 * second */
    uint32_t a, b;
    if (read_bits(&s->br, 1, &a) || read_bits(&s->br, 1, &b))
        return LUMO_ERR_TRUNCATED;
    if (!(a && b))
        return *m = two[a | b << 1], LUMO_OK;
    if (read_bits(&s->br, 1, &a))
        return LUMO_ERR_TRUNCATED;
    if (!a)
        return read_bits(&s->br, 1, &b) ? LUMO_ERR_TRUNCATED : (*m = b ? 5 : 1, LUMO_OK);
    lumo_status st = read_gamma(&s->br, m);
    return st ? st : (*m -= 1, LUMO_OK);
}

/* Move the corner of p's list whose face continues p with `a` (the first
 * one in list order) to k; *a becomes the face's vertex before p. */
static lumo_status fan_step(split_ctx *s, uint32_t p, uint32_t k, uint32_t *a)
{
    lumo_pmesh *pm = s->pm;
    uint32_t prev = NIL, c = pm->head[p];
    while (c != NIL && pm->tris[3 * (c / 3) + (c % 3 + 1) % 3] != *a)
        prev = c, c = pm->next[c];
    if (c == NIL || s->moves >= pm->h.max_batch_moves)
        return LUMO_ERR_CORRUPT;
    *a = pm->tris[3 * (c / 3) + (c % 3 + 2) % 3];
    if (prev == NIL)
        pm->head[p] = pm->next[c];
    else
        pm->next[prev] = pm->next[c];
    list_push(pm, k, c);
    pm->tris[c] = k;
    log_entry(s, c, prev, p);
    s->moves++;
    return LUMO_OK;
}

/* The first wing xa: the vertex right after p in corner i of p's list
 * (w(lp + 1) bits), or explicit when i = lp. */
static lumo_status read_wing(split_ctx *s, uint32_t p, uint32_t k, uint32_t lp, uint32_t *xa)
{
    uint32_t i, c = s->pm->head[p];
    if (read_trunc(&s->br, lp + 1, &i))
        return LUMO_ERR_TRUNCATED;
    if (i == lp)
        return read_trunc(&s->br, k, xa) ? LUMO_ERR_TRUNCATED : LUMO_OK;
    while (i--)
        c = s->pm->next[c];
    *xa = s->pm->tris[3 * (c / 3) + (c % 3 + 1) % 3];
    return LUMO_OK;
}

/* ---- fans ranked by geometry (docs/progressive-mesh.md §2.3 step 3;
 * the score is lumo_pmesh_fan_keys in pmesh_predict.c) ---- */

static void arc_gather(const lumo_pmesh *pm, uint32_t p, uint32_t n, lumo_pmesh_fan *g)
{
    uint32_t nx[LUMO_PMESH_ARC_MAX_CORNERS], pv[LUMO_PMESH_ARC_MAX_CORNERS], i = 0;
    for (uint32_t c = pm->head[p]; c != NIL; c = pm->next[c], i++) {
        const uint32_t *t = pm->tris + 3 * (size_t)(c / 3);
        nx[i] = t[(c % 3 + 1) % 3];
        pv[i] = t[(c % 3 + 2) % 3];
    }
    lumo_pmesh_fan_init(g, pm->qpos, pm->h.quant_bits, p, nx, pv, n);
}

/* Quickselect (Lomuto partition around the middle key): afterwards key[r]
 * is the one with r keys above it. Keys are distinct, so the result does
 * not depend on the method. Work: about 2 * count steps expected, count^2
 * at worst. */
static void arc_select(int64_t *key, uint32_t count, uint32_t r)
{
    uint32_t lo = 0, hi = count - 1;
    if (r == 0) {  /* the usual rank: one scan for the highest key */
        for (uint32_t k = 1; k < count; k++)
            key[0] = key[k] > key[0] ? key[k] : key[0];
        return;
    }
    while (lo < hi) {
        int64_t pivot = key[lo + (hi - lo) / 2], t;
        key[lo + (hi - lo) / 2] = key[hi], key[hi] = pivot;
        uint32_t at = lo;
        for (uint32_t k = lo; k < hi; k++)
            if (key[k] > pivot)
                t = key[k], key[k] = key[at], key[at++] = t;
        key[hi] = key[at], key[at] = pivot;
        if (at == r)
            return;
        if (r < at)
            hi = at - 1;
        else
            lo = at + 1;
    }
}

/* The rank r <= limit (docs/progressive-mesh.md §2.3 step 3): the class
 * b of r + 1 (its bit length less one) in unary, adaptive bits "class >
 * c" (context by the parent's corner count n and c) while class c + 1
 * fits the limit; then the b bits of r + 1 under its leading one, most
 * significant first, the first two adaptive (context by b and place). */
static lumo_status read_rank(split_ctx *s, uint32_t n, uint32_t limit, uint32_t *r)
{
    uint32_t b = 0, bit, v = 1;
    while ((2u << b) <= limit + 1) {
        if (read_ctx(s, lumo_pmesh_rank_ctx(n, b), &bit))
            return LUMO_ERR_TRUNCATED;
        if (!bit)
            break;
        b++;
    }
    for (uint32_t j = 0; j < b; j++) {
        int over = j < 2 ? read_ctx(s, LUMO_PMESH_CTX_RANK_LOW + 2 * b + j, &bit)
                         : read_bits(&s->br, 1, &bit);
        if (over)
            return LUMO_ERR_TRUNCATED;
        v = v << 1 | bit;
    }
    *r = v - 1;
    return *r > limit ? LUMO_ERR_CORRUPT : LUMO_OK;
}

/* The fan as a rank: *xa and *m, or *m = 0 for the escape (rank equal to
 * the candidate count) to the explicit wing and length. Work: the
 * candidates (at most ARC_MAX_CORNERS^2) once, then arc_select. */
static lumo_status read_arc(split_ctx *s, uint32_t p, uint32_t n, uint32_t *xa, uint32_t *m)
{
    lumo_pmesh *pm = s->pm;
    lumo_pmesh_fan g;
    uint32_t rank;
    lumo_status st;
    arc_gather(pm, p, n, &g);
    uint32_t count = lumo_pmesh_fan_keys(&g, pm->arc_key);
    if ((st = read_rank(s, n, count, &rank)))
        return st;
    *m = 0;
    if (rank == count)
        return LUMO_OK;
    arc_select(pm->arc_key, count, rank);
    uint32_t id = lumo_pmesh_fan_key_id(pm->arc_key[rank]);
    *xa = g.nx[id >> 8], *m = id & 0xffu;
    return LUMO_OK;
}

/* Fan split, the inverse of an interior half-edge collapse: the faces
 * (k, p, xa) and (k, xb, p) reappear, in that order, and the m faces of p's fan from xa
 * to xb (next vertex after p = xa, then each face's previous vertex)
 * move to k; only xa and m are coded, as a rank (read_arc) or
 * explicitly. */
static lumo_status fan_split(split_ctx *s, uint32_t p, uint32_t k)
{
    uint32_t xa = 0, m = 0, lp = list_length(s->pm, p, FAN_MAX_CORNERS);
    lumo_status st;
    if (lp > FAN_MAX_CORNERS)
        return LUMO_ERR_LIMIT;
    if (lp >= 1 && lp <= LUMO_PMESH_ARC_MAX_CORNERS && (st = read_arc(s, p, lp, &xa, &m)))
        return st;
    if (!m && ((st = read_wing(s, p, k, lp, &xa)) || (st = read_fan_length(s, &m))))
        return st;
    if (xa >= k || xa == p || m > lp)
        return LUMO_ERR_CORRUPT;
    uint32_t xb = xa;
    for (uint32_t i = 0; i < m; i++)
        if ((st = fan_step(s, p, k, &xb)))
            return st;
    if (xb >= k || xb == p)
        return LUMO_ERR_CORRUPT;
    return (st = add_face(s, k, p, xa)) ? st : add_face(s, k, xb, p);
}

/* A new round's first parent (docs/progressive-mesh.md §2.3 step 1): the
 * class c of p + 1 (1 ... w(k + 1)) in unary, adaptive bits "c > j" for
 * j = 1, 2, ... (none once c = w(k + 1)), then the c - 1 bits of p + 1
 * under its leading one as one (c - 1)-bit value of direct bits. p >= k
 * is left to the caller (RANGE). Work: at most 2 w(k + 1) bits. */
static lumo_status read_round_start(split_ctx *s, uint32_t k, uint32_t *p)
{
    uint32_t cmax = lumo_pmesh_field_bits(k + 1u), c = 1, bit = 1, low = 0;
    while (c < cmax && bit) {
        if (read_ctx(s, lumo_pmesh_start_ctx(c - 1u), &bit))
            return LUMO_ERR_TRUNCATED;
        c += bit;
    }
    if (read_bits(&s->br, c - 1u, &low))
        return LUMO_ERR_TRUNCATED;
    *p = ((uint32_t)1 << (c - 1u) | low) - 1u;
    return LUMO_OK;
}

/* The lookup-table parent of k (docs/progressive-mesh.md §2.3 step 1). The
 * splits of one independent-set round come sorted by parent, so after the
 * first split an adaptive bit says whether this one continues the round;
 * then the vertices after the previous parent and below the round's first
 * split vertex are scanned, each eligible one (lumo_pmesh_parent_ctx)
 * reading an adaptive bit, until a 1 names the parent. Else (a new round)
 * p follows in the round start code and the round starts at k. Work: the vertices passed
 * and their valences; a round passes each vertex once. */
static lumo_status read_parent(split_ctx *s, uint32_t k, uint32_t *p)
{
    lumo_pmesh *pm = s->pm;
    uint32_t bit = 0, v;
    if (s->prev_parent != NIL && read_ctx(s, LUMO_PMESH_CTX_ROUND, &bit))
        return LUMO_ERR_TRUNCATED;
    if (!bit) {
        s->round_first = k;
        return read_round_start(s, k, p);
    }
    for (v = s->prev_parent + 1; v < s->round_first; v++) {
        int c = lumo_pmesh_parent_ctx(pm->tris, pm->head, pm->next, pm->round_parent, v, s->round_first);
        if (c < 0)
            continue;
        if (read_ctx(s, (uint32_t)c, &bit))
            return LUMO_ERR_TRUNCATED;
        if (bit)
            return *p = v, LUMO_OK;
    }
    return LUMO_ERR_CORRUPT;  /* no parent before the round's first split */
}

/* CODED albedo of split vertex k (docs/progressive-mesh.md §2.3 step 6):
 * "the parent's" (adaptive, by the previous split's answer), else per
 * channel a residual from the parent's code: its class (bit length of |r|,
 * 0 ... 8) in unary by channel and place, the c - 1 bits under its leading
 * one as one direct value, the sign by channel. Written straight into the
 * albedo array: vertices past vertex_count are invisible until kept. */
static lumo_status read_split_albedo(split_ctx *s, uint32_t p, uint32_t k)
{
    lumo_q1_14 *a = s->pm->albedo;
    uint32_t same, ch;
    if (read_ctx(s, LUMO_PMESH_CTX_ALB_SAME + s->last_same, &same))
        return LUMO_ERR_TRUNCATED;
    s->last_same = same;
    for (ch = 0; ch < 3; ch++) {
        uint32_t pred = lumo_pmesh_albedo_code((uint32_t)a[3 * (size_t)p + ch]), c = 0, bit = 1, low = 0;
        int32_t v = (int32_t)pred;
        while (!same && c < LUMO_PMESH_ALB_CLASSES && bit) {
            if (read_ctx(s, LUMO_PMESH_CTX_ALB_CLASS + ch * LUMO_PMESH_ALB_CLASSES + c, &bit))
                return LUMO_ERR_TRUNCATED;
            c += bit;
        }
        if (c) {
            if (read_bits(&s->br, c - 1u, &low) || read_ctx(s, LUMO_PMESH_CTX_ALB_SIGN + ch, &bit))
                return LUMO_ERR_TRUNCATED;
            v += bit ? -(int32_t)((1u << (c - 1u)) | low) : (int32_t)((1u << (c - 1u)) | low);
        }
        if (v < 0 || v > 255)
            return LUMO_ERR_RANGE;
        a[3 * (size_t)k + ch] = (lumo_q1_14)lumo_pmesh_albedo_q14((uint32_t)v);
    }
    return LUMO_OK;
}

static lumo_status split(split_ctx *s, uint32_t k)
{
    uint32_t p, n;
    int paired, fan;
    lumo_status st;
    if ((st = read_parent(s, k, &p)))
        return st;
    if (p >= k)
        return LUMO_ERR_RANGE;
    s->pm->stamp_log[s->stamped++] = s->pm->round_parent[p];
    s->pm->round_parent[p] = s->round_first;
    s->prev_parent = p;
    s->pm->head[k] = NIL;
    s->pm->batch_parent[k - s->split0] = p;
    if ((st = read_split_kind(s, &n, &paired, &fan)))
        return st;
    if ((st = fan ? fan_split(s, p, k) : mask_split(s, p, k, n, paired)))
        return st;
    if ((s->res || s->coded) && (st = predict_split(s, k)))
        return st;
    return s->coded && s->pm->albedo ? read_split_albedo(s, p, k) : LUMO_OK;
}

/* Splits k = from ... to - 1: one range code (pmesh_rc.h) on the block's
 * bytes from `at` on (a split record's whole block; the base record's
 * after its seed), ending exactly where the writer's flush ends it. */
static lumo_status run_range_code(split_ctx *s, uint32_t from, uint32_t to, size_t at)
{
    lumo_status st = LUMO_OK;
    s->br.range = 1;
    s->split0 = from;
    if (lumo_pmesh_rc_init(&s->br.rc, s->b->side + at, s->b->side_bytes - (uint32_t)at))
        return LUMO_ERR_TRUNCATED;
    for (uint32_t k = from; k < to && !st; k++) {
        s->pm->split_log[k - from] = s->log_n;
        st = split(s, k);
    }
    if (!st && !lumo_pmesh_rc_done(&s->br.rc))
        return LUMO_ERR_CORRUPT;  /* bytes left over, or not the writer's flush */
    return st;
}

/* The seed's size in a CODED base record (docs/progressive-mesh.md §2.3
 * "Base record"): its vertex count s (1 ... b) and face count + 1, gamma
 * codes. A seed larger than the base mesh is RANGE; more faces than the
 * base mesh's, or a seed as large as the base mesh with fewer faces
 * (nothing would add them), CORRUPT. */
static lumo_status read_seed_size(split_ctx *s, uint32_t *nv, uint32_t *nf)
{
    const lumo_pmesh_header *h = &s->pm->h;
    lumo_status st = read_gamma(&s->br, nv);
    if (st || (st = read_gamma(&s->br, nf)))
        return st;
    *nf -= 1u;
    if (*nv > h->base_vertices)
        return LUMO_ERR_RANGE;
    if (*nf > h->base_faces || (*nv == h->base_vertices && *nf != h->base_faces))
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

/* CODED seed positions: quant_bits per grid integer, x, y, z per vertex
 * (every value fits the grid); with albedo, then 8 bits per channel. */
static lumo_status read_seed_attributes(split_ctx *s, uint32_t nv)
{
    uint32_t v;
    for (size_t at = 0; at < 3 * (size_t)nv; at++) {
        if (read_bits(&s->br, s->pm->h.quant_bits, &v))
            return LUMO_ERR_TRUNCATED;
        s->pm->qpos[at] = (int32_t)v;
    }
    for (size_t at = 0; s->pm->albedo && at < 3 * (size_t)nv; at++) {
        if (read_bits(&s->br, 8, &v))
            return LUMO_ERR_TRUNCATED;
        s->pm->albedo[at] = (lumo_q1_14)lumo_pmesh_albedo_q14(v);
    }
    return LUMO_OK;
}

/* The base block (docs/progressive-mesh.md §2.3 "Base record"): plain
 * bits, the base mesh's faces (Draco payload streams: their positions are
 * in the payload) or, CODED, the seed's size, faces, positions and
 * albedo; zero padding to a byte; then, when the seed is smaller than the
 * base mesh, the range code of its splits, else nothing (every byte
 * used). The base mesh must then have exactly base_faces faces. */
static lumo_status run_base_block(split_ctx *s)
{
    uint32_t pad, nv = s->b->count, nf = s->pm->h.base_faces;
    lumo_status st = s->coded ? read_seed_size(s, &nv, &nf) : LUMO_OK;
    if (!st)
        st = read_base_faces(s, nv, nf);
    if (!st && s->coded)
        st = read_seed_attributes(s, nv);
    if (st)
        return st;
    size_t used = (s->br.wb.pos + 7) / 8;
    if (used > s->b->side_bytes || (nv == s->b->count && used != s->b->side_bytes))
        return LUMO_ERR_CORRUPT;  /* trailing bytes */
    if (read_bits(&s->br, (unsigned)(8 * used - s->br.wb.pos), &pad) || pad)
        return LUMO_ERR_CORRUPT;  /* padding bits must be zero */
    if (nv < s->b->count && (st = run_range_code(s, nv, s->b->count, used)))
        return st;
    return s->pm->face_count == s->pm->h.base_faces ? LUMO_OK : LUMO_ERR_CORRUPT;
}

static lumo_status run_splits(split_ctx *s)
{
    lumo_status st = s->b->first == 0 ? run_base_block(s)
                                      : run_range_code(s, s->b->first, s->b->first + s->b->count, 0);
    if (st)
        return st;
    if (s->b->first + s->b->count == s->pm->h.vertices && s->pm->face_count != s->pm->h.faces)
        return LUMO_ERR_CORRUPT;  /* the last record completes the mesh */
    return LUMO_OK;
}

/* ---- normals of the touched vertices ---------------------------------------- */
static void mark_face(lumo_pmesh *pm, uint32_t f, uint32_t stamp, uint32_t *nd)
{
    for (uint32_t i = 0; i < 3; i++) {
        uint32_t v = pm->tris[3 * (size_t)f + i];
        if (pm->mark[v] != stamp)
            pm->mark[v] = stamp, pm->dirty[(*nd)++] = v;
    }
}

/* Scale an int64 vector down until it fits lumo_normalize3_q14's int32
 * input; direction is all that matters here. */
static void normal_from_sum(int64_t s[3], lumo_q1_14 out[3])
{
    int32_t v[3];
    while (s[0] > INT32_MAX / 2 || s[0] < -(INT32_MAX / 2) || s[1] > INT32_MAX / 2 ||
           s[1] < -(INT32_MAX / 2) || s[2] > INT32_MAX / 2 || s[2] < -(INT32_MAX / 2))
        s[0] /= 2, s[1] /= 2, s[2] /= 2;
    v[0] = (int32_t)s[0], v[1] = (int32_t)s[1], v[2] = (int32_t)s[2];
    if (lumo_normalize3_q14(v, out))
        out[0] = out[1] = out[2] = 0;
}

/* Area-weighted face normals from the grid integers: exact int64 sums. */
static void vertex_normal(lumo_pmesh *pm, uint32_t v)
{
    int64_t s[3] = {0, 0, 0};
    for (uint32_t c = pm->head[v]; c != NIL; c = pm->next[c]) {
        const uint32_t *t = pm->tris + 3 * (size_t)(c / 3);
        const int32_t *a = pm->qpos + 3 * (size_t)t[0], *b = pm->qpos + 3 * (size_t)t[1],
                      *d = pm->qpos + 3 * (size_t)t[2];
        int64_t e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        int64_t e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        s[0] += e1[1] * e2[2] - e1[2] * e2[1];
        s[1] += e1[2] * e2[0] - e1[0] * e2[2];
        s[2] += e1[0] * e2[1] - e1[1] * e2[0];
    }
    normal_from_sum(s, pm->nrm + 3 * (size_t)v);
}

/* Collect the vertices of every face the log entries from `from` on touch. */
static uint32_t mark_log(const split_ctx *s, uint32_t from, uint32_t stamp)
{
    lumo_pmesh *pm = s->pm;
    uint32_t nd = 0;
    for (uint32_t i = from; i < s->log_n; i++) {
        const uint32_t *e = pm->journal + 3 * (size_t)i;
        mark_face(pm, e[0] == NIL ? e[1] : e[0] / 3, stamp, &nd);
        if (e[0] != NIL && pm->mark[e[2]] != stamp)  /* p gained or lost the corner */
            pm->mark[e[2]] = stamp, pm->dirty[nd++] = e[2];
    }
    return nd;
}

static void refresh_normals(split_ctx *s, uint32_t from)
{
    uint32_t nd = mark_log(s, from, s->pm->batches_applied + 1);
    for (uint32_t i = 0; i < nd; i++)
        vertex_normal(s->pm, s->pm->dirty[i]);
}

lumo_status lumo_pmesh_apply(lumo_pmesh *pm, const uint8_t *record, size_t size)
{
    batch b;
    lumo_draco_mesh m;
    const lumo_draco_attribute *pos = NULL, *rgb = NULL;
    lumo_status st;
    if (!pm || !record)
        return LUMO_ERR_ARG;
    if (pm->rewound)
        return LUMO_ERR_STATE;
    int coded = pm->h.position_coding == LUMO_PMESH_POS_CODED;
    if ((st = parse_record(pm, record, size, &b)))
        return st;
    if (coded && b.draco_bytes)
        return LUMO_ERR_CORRUPT;  /* a CODED record has no payload */
    if (!coded && (st = decode_positions(pm, &b, &pos, &rgb, &m)))
        return st;
    int predicted = pm->h.position_coding == LUMO_PMESH_POS_PREDICTED;
    split_ctx s;
    memset(&s, 0, sizeof s);
    s.pm = pm, s.b = &b, s.res = predicted ? pos : NULL, s.coded = coded;
    s.br.wb = (lumo_wire_bits){b.side, (size_t)b.side_bytes * 8u, 0};
    s.prev_parent = pm->last_parent, s.round_first = pm->round_first, s.last_fan = pm->last_fan;
    s.last_same = pm->last_same;
    s.ctx = pm->ctx;
    memcpy(pm->ctx_undo, pm->ctx, LUMO_PMESH_CONTEXTS * sizeof *pm->ctx);
    /* absolute positions first: the fan ranks read the batch's earlier
     * vertices (qpos beyond vertex_count is invisible until kept) */
    if ((!coded && (st = grid_positions(pm, &b, pos))) || (st = run_splits(&s))) {
        rollback_to(&s, 0);
        while (s.stamped-- > 0)  /* newest first: a parent may repeat in new rounds */
            pm->round_parent[pm->batch_parent[s.stamped]] = pm->stamp_log[s.stamped];
        memcpy(pm->ctx, pm->ctx_undo, LUMO_PMESH_CONTEXTS * sizeof *pm->ctx);
        return st;
    }
    pm->last_parent = s.prev_parent, pm->round_first = s.round_first, pm->last_fan = s.last_fan;
    pm->last_same = s.last_same;
    store_positions(pm, &b);
    if (!coded)
        store_albedo(pm, &b, rgb);
    pm->split_log[b.first ? b.count : 0] = s.log_n;
    pm->log_n = s.log_n, pm->last_first = b.first;
    pm->vertex_count += b.count;
    refresh_normals(&s, 0);
    pm->batches_applied++;
    return LUMO_OK;
}

lumo_status lumo_pmesh_rewind(lumo_pmesh *pm, uint32_t vertices)
{
    if (!pm)
        return LUMO_ERR_ARG;
    if (!pm->batches_applied || vertices > pm->vertex_count ||
        vertices < (pm->last_first ? pm->last_first : pm->vertex_count))
        return LUMO_ERR_RANGE;
    pm->rewound = 1;
    if (vertices == pm->vertex_count)
        return LUMO_OK;
    split_ctx s;
    memset(&s, 0, sizeof s);
    s.pm = pm, s.log_n = pm->log_n, s.prev_parent = NIL;
    uint32_t keep = pm->split_log[vertices - pm->last_first];
    /* Vertices of the faces about to change get fresh normals afterwards. */
    uint32_t nd = mark_log(&s, keep, pm->batches_applied + 1);
    rollback_to(&s, keep);
    pm->vertex_count = vertices;
    pm->log_n = keep;
    for (uint32_t i = 0; i < nd; i++)
        if (pm->dirty[i] < vertices)
            vertex_normal(pm, pm->dirty[i]);
    return LUMO_OK;
}
