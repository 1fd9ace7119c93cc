/* pm_stream.c — the progressive-mesh stream writer (docs/progressive-mesh.md).
 *
 * The writer replays exactly what the client (sdk/src/pmesh_batch.c) will
 * do: the same per-vertex corner lists, updated in the same order, so each
 * vertex split can be told cheaply: for an interior split, which of p's
 * fans moves to k (its rank among the fans the geometry of p's ring
 * makes likely, or its first wing and length); otherwise
 * which of p's corners move (one bit each) and which neighbour closes each
 * reappearing face (a short index into the corners around k and p). Seed
 * 000 §4.2 sends vertices, faces and lookup tables; here the lookup-table
 * entry of k is its parent p, found by a scan of the vertices after the
 * previous split's parent that may still split in this round (the splits
 * of one collapse round are numbered by increasing parent, pm_build.c),
 * an adaptive bit each. A split record is one adaptive binary range code
 * (pm/pm_rc.h), whose probabilities the writer replays as the decoder
 * keeps them. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "lumo/wire.h"
#include "lumo/pmesh.h"
#include "package/package_write.h"
#include "lumo_shared/pmesh_shared.h"
#include "pm/pm_rc.h"
#include "pm/pm_stream.h"

#define NIL LUMO_PMESH_NIL

/* ---- bytes (srv_buf, package_write.h) and bits ----------------------------- */
/* The base block's bit fields, or (rc set) a split record's range code,
 * whose fixed fields are direct bits. */
typedef struct { srv_buf b; size_t nbits; srv_pm_rc *rc; } bitwriter;

/* Bits spent so far (fractional in a range code). */
static double spent(const bitwriter *w)
{
    return w->rc ? w->rc->cost : (double)w->nbits;
}

/* Grow the buffer by the zero bytes the field reaches into, then write it
 * with the wire layer's bit writer (lumo/wire.h: the reader's inverse). */
static void put_bits(bitwriter *w, uint32_t v, unsigned n)
{
    static const uint8_t zero[5];
    if (w->rc) {
        srv_pm_rc_direct(w->rc, v, n);
        return;
    }
    size_t bytes = (w->nbits + n + 7) >> 3;
    if (bytes > w->b.len)
        srv_buf_put(&w->b, zero, bytes - w->b.len);
    if (!w->b.failed)
        lumo_wire_put_bits(w->b.p, w->nbits, v, n);
    w->nbits += n;
}

/* tb(c) (docs/progressive-mesh.md §2.3): v in [0, c) in truncated binary.
 * With n = w(c) and u = 2^n - c, the first u values take n - 1 bits, the
 * others (v + u) >> 1 in n - 1 bits then (v + u) & 1. Mirrors read_trunc. */
static void put_trunc(bitwriter *w, uint32_t v, uint32_t c)
{
    unsigned n = lumo_pmesh_field_bits(c);
    uint32_t u = n ? (uint32_t)(((uint64_t)1 << n) - c) : 0;
    if (n == 0)
        return;
    if (v < u) {
        put_bits(w, v, n - 1);
        return;
    }
    put_bits(w, (v + u) >> 1, n - 1);
    put_bits(w, (v + u) & 1u, 1);
}

/* ---- the client's state, replayed --------------------------------------------- */
typedef struct {
    const srv_pm *pm;
    int32_t  *q;              /* grid integers, 3 per vertex */
    int32_t  *res;            /* their residuals from the client's prediction */
    uint32_t *disp, *next, *head;
    uint32_t  face_count;
    uint32_t  faces, moves;   /* of the batch being written */
    srv_pm_stream_stats st;   /* where the bits go (options->stats gets a copy) */
    unsigned  quant_bits;     /* grid bits (the fan ranking shifts by them) */
    int       rank_escape;    /* options->fan_rank_escape */
    int       coded;          /* LUMO_PMESH_POS_CODED: positions in the blocks */
    int       lattice;        /* LUMO_PMESH_LATTICE: coordinates may copy the ring's */
    uint32_t  round_first;    /* first split vertex of the current round */
    uint32_t *round_parent;   /* per vertex: round start of its last round as a parent */
    uint32_t  last_fan;       /* the previous split was a fan split */
    uint32_t  last_same;      /* the previous split's albedo was its parent's */
    uint32_t  ctx[LUMO_PMESH_CONTEXTS];  /* the decoder's contexts, replayed */
} replay;

/* One adaptive bit of context c (mirrors read_ctx in pmesh_batch.c). */
static void put_ctx(replay *r, bitwriter *w, uint32_t c, uint32_t bit)
{
    r->st.ctx_bits[c][bit]++;
    srv_pm_rc_bit(w->rc, &r->ctx[c], bit);
}

/* Split kinds as the writer records them: a fan split, a pair (mask
 * split), or 1 ... 15 faces (mask split, flips coded). */
#define KIND_FAN  0u
#define KIND_PAIR 16u

/* Bits written since *mark go to *field of the stats. */
static void count_bits(const bitwriter *w, double *mark, double *field)
{
    *field += spent(w) - *mark;
    *mark = spent(w);
}

static void list_push(replay *r, uint32_t v, uint32_t c)
{
    r->next[c] = r->head[v];
    r->head[v] = c;
}

static void add_face(replay *r, const uint32_t t[3])
{
    uint32_t f = r->face_count++;
    for (uint32_t i = 0; i < 3; i++) {
        r->disp[3 * f + i] = t[i];
        list_push(r, t[i], 3 * f + i);
    }
    r->faces++;
}

/* Mirrors read_residual() in pmesh_batch.c: the class c of |v| (its bit
 * length) in adaptive unary by the spread class sc (no end bit at
 * quant_bits), the c - 1 bits under the leading one (the first two
 * adaptive), then the sign, adaptive by c and the sign of `offset` (the
 * prediction's offset from the parent). */
static void put_residual(replay *r, bitwriter *w, uint32_t sc, int32_t offset, int32_t v)
{
    uint32_t a = (uint32_t)(v < 0 ? -v : v), c = 0;
    while (a >> c)
        c++;
    for (uint32_t j = 0; j < r->quant_bits && j <= c; j++)
        put_ctx(r, w, lumo_pmesh_res_ctx(sc, j, offset), j < c);
    if (c == 0)
        return;
    for (uint32_t i = c - 1; i-- > 0;) {
        uint32_t bit = a >> i & 1u, j = c - 2 - i;
        if (j < 2)
            put_ctx(r, w, lumo_pmesh_res_low_ctx(c, j), bit);
        else
            put_bits(w, bit, 1);
    }
    put_ctx(r, w, lumo_pmesh_sign_ctx(c, offset), v < 0);
}

/* LATTICE streams (mirrors read_copy in pmesh_batch.c): the copy flag,
 * and for a coordinate found among the ring's values its rank in unary.
 * Returns whether it was copied (else the residual follows). */
static int put_copy(replay *r, bitwriter *w, const lumo_pmesh_ring *ring, unsigned d, int32_t value)
{
    int32_t cand[LUMO_PMESH_RING_MAX];
    uint32_t ctx, m = lumo_pmesh_lattice_values(r->q, ring, d, cand, &ctx), rank = 0;
    while (rank < m && cand[rank] != value)
        rank++;
    put_ctx(r, w, ctx, rank < m);
    for (uint32_t j = 0; rank < m && j + 1 < m && j <= rank; j++)
        put_ctx(r, w, lumo_pmesh_copy_rank_ctx(j), j < rank);
    return rank < m;
}

/* Mirrors read_split_albedo() in pmesh_batch.c: "the parent's", else per
 * channel the residual's class in unary, the bits under its leading one,
 * the sign. */
static void put_albedo(replay *r, bitwriter *w, uint32_t p, uint32_t k)
{
    const uint8_t *a = r->pm->albedo;
    uint32_t same = !memcmp(a + 3 * (size_t)p, a + 3 * (size_t)k, 3);
    double mark = spent(w);
    put_ctx(r, w, LUMO_PMESH_CTX_ALB_SAME + r->last_same, same);
    r->last_same = same;
    for (uint32_t ch = 0; !same && ch < 3; ch++) {
        int32_t v = (int32_t)a[3 * (size_t)k + ch] - (int32_t)a[3 * (size_t)p + ch];
        uint32_t m = (uint32_t)(v < 0 ? -v : v), c = 0;
        while (m >> c)
            c++;
        for (uint32_t j = 0; j < LUMO_PMESH_ALB_CLASSES && j <= c; j++)
            put_ctx(r, w, LUMO_PMESH_CTX_ALB_CLASS + ch * LUMO_PMESH_ALB_CLASSES + j, j < c);
        if (c) {
            put_bits(w, m - (1u << (c - 1u)), c - 1u);
            put_ctx(r, w, LUMO_PMESH_CTX_ALB_SIGN + ch, v < 0);
        }
    }
    count_bits(w, &mark, &r->st.albedo_bits);
}

/* The residual of k from the decoder's own prediction
 * (lumo_pmesh_predict_position, sdk/src/pmesh_predict.c); CODED streams
 * write it into the range code (or, LATTICE, a copied coordinate), then
 * the albedo. */
static void predict(replay *r, bitwriter *w, uint32_t k)
{
    lumo_pmesh_ring ring;
    uint32_t p = r->pm->parent[k];
    lumo_pmesh_predict_position(r->q, r->disp, r->head, r->next, k, p, r->lattice, &ring);
    double mark = spent(w);
    for (int d = 0; d < 3; d++) {
        int32_t v = r->q[3 * (size_t)k + d] - ring.pred[d];
        r->res[3 * (size_t)k + d] = v;
        if (r->coded && !(r->lattice && put_copy(r, w, &ring, (unsigned)d, r->q[3 * (size_t)k + d])))
            put_residual(r, w, ring.sc[d], ring.pred[d] - r->q[3 * (size_t)p + d], v);
    }
    count_bits(w, &mark, &r->st.pos_bits);
    if (r->coded && r->pm->albedo)
        put_albedo(r, w, p, k);
}

static uint32_t write_moves(replay *r, bitwriter *w, uint32_t p, uint32_t k)
{
    uint32_t prev = NIL, c = r->head[p], lenp = 0;
    while (c != NIL) {
        uint32_t nextc = r->next[c];
        int move = srv_pm_resolve(r->pm, r->pm->tris[c], k + 1) == k;
        put_ctx(r, w, LUMO_PMESH_CTX_MASK, (uint32_t)move);
        if (!move) {
            prev = c, c = nextc, lenp++;
            continue;
        }
        if (prev == NIL)
            r->head[p] = nextc;
        else
            r->next[prev] = nextc;
        list_push(r, k, c);
        r->disp[c] = k;
        r->moves++;
        c = nextc;
    }
    return lenp;
}

/* Index of x among the neighbours of v's list (corner j/2, next vertex
 * for even j, previous for odd), or 2 * len for the escape. */
static uint32_t find_neighbour(const replay *r, uint32_t v, uint32_t len, uint32_t x)
{
    uint32_t j = 0;
    for (uint32_t c = r->head[v]; c != NIL && j < 2 * len; c = r->next[c], j += 2) {
        uint32_t f = c / 3, q = c % 3;
        if (r->disp[3 * f + (q + 1) % 3] == x)
            return j;
        if (r->disp[3 * f + (q + 2) % 3] == x)
            return j + 1;
    }
    return 2 * len;
}

/* Mirrors read_vertex() in pmesh_batch.c: a neighbour of each list in
 * turn (index or escape), else explicit. */
static void write_vertex(const replay *r, bitwriter *w, const uint32_t *lists, const uint32_t *lens,
                         int nlists, uint32_t k, uint32_t x)
{
    for (int l = 0; l < nlists; l++) {
        uint32_t j = find_neighbour(r, lists[l], lens[l], x);
        put_trunc(w, j, 2 * lens[l] + 1);
        if (j < 2 * lens[l])
            return;
    }
    put_trunc(w, x, k);
}

/* Mirrors read_third(): among k's neighbours, else p's, else explicit. */
static void write_third(const replay *r, bitwriter *w, uint32_t p, uint32_t k, uint32_t lp,
                        uint32_t lk, uint32_t x)
{
    uint32_t lists[2] = {k, p}, lens[2] = {lk, lp};
    write_vertex(r, w, lists, lens, 2, k, x);
}

/* Face f at level k + 1 is (k, p, x) (flip 0) or (k, x, p) (flip 1):
 * its flip, or -1 when it is neither. */
static int face_flip(const replay *r, uint32_t f, uint32_t p, uint32_t k)
{
    uint32_t t[3];
    for (int i = 0; i < 3; i++)
        t[i] = srv_pm_resolve(r->pm, r->pm->tris[3 * (size_t)f + i], k + 1);
    if (t[0] != k)
        return -1;  /* pm_build.c rotates k to corner 0 */
    return t[1] == p ? 0 : t[2] == p ? 1 : -1;
}

static int write_new_face(replay *r, bitwriter *w, uint32_t f, uint32_t p, uint32_t k, uint32_t lp,
                          uint32_t lk, int flip_implied)
{
    int flip = face_flip(r, f, p, k);
    if (flip < 0)
        return -1;  /* a reappearing face always holds edge (k, p), k first */
    uint32_t t[3];
    for (int i = 0; i < 3; i++)
        t[i] = srv_pm_resolve(r->pm, r->pm->tris[3 * (size_t)f + i], k + 1);
    if (!flip_implied)
        put_bits(w, (uint32_t)flip, 1);
    write_third(r, w, p, k, lp, lk, flip ? t[1] : t[2]);
    add_face(r, t);
    return 0;
}

#define FAN_MAX_CORNERS 255u  /* as in pmesh_batch.c */

static void put_gamma(bitwriter *w, uint32_t v)
{
    unsigned z = 0;
    while (v >> (z + 1))
        z++;
    put_bits(w, 0, z);
    put_bits(w, 1, 1);
    put_bits(w, v & (((uint32_t)1 << z) - 1), z);
}

/* Mirrors read_fan_length() in pmesh_batch.c. */
static void put_fan_length(bitwriter *w, uint32_t m)
{
    if (m >= 2 && m <= 4)
        put_bits(w, m == 3 ? 0 : m == 4 ? 1 : 2, 2);  /* first bit in bit 0 */
    else if (m == 1 || m == 5)
        put_bits(w, 3, 2), put_bits(w, 0, 1), put_bits(w, m == 5, 1);
    else
        put_bits(w, 7, 3), put_gamma(w, m + 1);
}

static int moves_to_k(const replay *r, uint32_t c, uint32_t k)
{
    return srv_pm_resolve(r->pm, r->pm->tris[c], k + 1) == k;
}

/* The corner fan_step() in pmesh_batch.c takes: the first of p's list,
 * not yet taken, whose face continues p with a. */
static uint32_t fan_corner(const replay *r, uint32_t p, uint32_t a, const uint32_t *taken, uint32_t nt)
{
    for (uint32_t c = r->head[p]; c != NIL; c = r->next[c]) {
        int used = 0;
        for (uint32_t i = 0; i < nt && !used; i++)
            used = taken[i] == c;
        if (!used && r->disp[3 * (c / 3) + (c % 3 + 1) % 3] == a)
            return c;
    }
    return NIL;
}

/* Can the client derive the moves by walking p's fan from xa (the third
 * vertex of the flip-0 face) to xb (of the flip-1 face)? Then *m is the
 * number of moves. */
static int fan_plan(const replay *r, uint32_t p, uint32_t k, uint32_t xa, uint32_t xb, uint32_t *m)
{
    uint32_t lp = 0, want = 0, taken[FAN_MAX_CORNERS + 1], a = xa;
    for (uint32_t c = r->head[p]; c != NIL; c = r->next[c], lp++)
        want += (uint32_t)moves_to_k(r, c, k);
    if (lp > FAN_MAX_CORNERS)
        return 0;
    for (*m = 0; *m < want; (*m)++) {
        uint32_t c = fan_corner(r, p, a, taken, *m);
        if (c == NIL || !moves_to_k(r, c, k))
            return 0;
        taken[*m] = c;
        a = r->disp[3 * (c / 3) + (c % 3 + 2) % 3];
    }
    return a == xb;
}

/* ---- fans ranked by geometry: the decoder's own ranking
 * (lumo_pmesh_fan_keys, sdk/src/pmesh_predict.c), so both order the
 * candidates identically ---- */

static void arc_gather(const replay *r, uint32_t p, uint32_t n, lumo_pmesh_fan *g)
{
    uint32_t nx[LUMO_PMESH_ARC_MAX_CORNERS], pv[LUMO_PMESH_ARC_MAX_CORNERS], i = 0;
    for (uint32_t c = r->head[p]; c != NIL; c = r->next[c], i++) {
        nx[i] = r->disp[3 * (c / 3) + (c % 3 + 1) % 3];
        pv[i] = r->disp[3 * (c / 3) + (c % 3 + 2) % 3];
    }
    lumo_pmesh_fan_init(g, r->q, r->quant_bits, p, nx, pv, n);
}

/* Rank of the fan (xa, m) among the candidates (the keys above its own),
 * or their count when it is not one of them (the escape). */
static uint32_t arc_rank(const lumo_pmesh_fan *g, uint32_t xa, uint32_t m)
{
    int64_t keys[LUMO_PMESH_ARC_MAX_CORNERS * LUMO_PMESH_ARC_MAX_CORNERS], want = 0;
    uint32_t it = 0, above = 0, found = 0, count = lumo_pmesh_fan_keys(g, keys);
    while (it < g->n && g->nx[it] != xa)
        it++;
    for (uint32_t c = 0; c < count; c++)
        if (lumo_pmesh_fan_key_id(keys[c]) == (it << 8 | m))
            want = keys[c], found = 1;
    for (uint32_t c = 0; c < count; c++)
        above += keys[c] > want;
    return found ? above : count;
}

/* Mirrors read_rank() in pmesh_batch.c: the class b of r + 1 (its bit
 * length less one) in adaptive unary while a larger class fits the limit,
 * then the b bits of r + 1 below its leading one, most significant first,
 * the first two adaptive. */
static void put_rank(replay *r, bitwriter *w, uint32_t n, uint32_t limit, uint32_t rank)
{
    uint32_t v = rank + 1, b = 0;
    while ((v >> (b + 1)) != 0)
        b++;
    for (uint32_t c = 0; (2u << c) <= limit + 1; c++) {
        put_ctx(r, w, lumo_pmesh_rank_ctx(n, c), c < b);
        if (c == b)
            break;
    }
    for (uint32_t i = b; i-- > 0;) {
        uint32_t bit = v >> i & 1u, j = b - 1 - i;
        if (j < 2)
            put_ctx(r, w, LUMO_PMESH_CTX_RANK_LOW + 2 * b + j, bit);
        else
            put_bits(w, bit, 1);
    }
}

/* The explicit fan (read_wing, read_fan_length): the first corner of
 * L(p) whose next vertex is xa (or the escape, then xa), then m. */
static void write_wing_length(const replay *r, bitwriter *w, uint32_t p, uint32_t k, uint32_t lp,
                              uint32_t xa, uint32_t m)
{
    uint32_t wing = 0;
    for (uint32_t c = r->head[p]; c != NIL && r->disp[3 * (c / 3) + (c % 3 + 1) % 3] != xa; c = r->next[c])
        wing++;
    put_trunc(w, wing, lp + 1);
    if (wing == lp)
        put_trunc(w, xa, k);
    put_fan_length(w, m);
}

/* Mirrors fan_split() in pmesh_batch.c: the fan's rank, or the escape
 * then the explicit first wing and length. */
static void write_fan(replay *r, bitwriter *w, uint32_t p, uint32_t k, uint32_t f0,
                      uint32_t xa, uint32_t m)
{
    uint32_t lp = 0, a = xa;
    for (uint32_t c = r->head[p]; c != NIL; c = r->next[c])
        lp++;
    uint32_t rank = 1, count = 0;
    if (lp >= 1 && lp <= LUMO_PMESH_ARC_MAX_CORNERS) {
        lumo_pmesh_fan g;
        arc_gather(r, p, lp, &g);
        count = arc_rank(&g, NIL, 0);
        rank = r->rank_escape ? count : arc_rank(&g, xa, m);
        put_rank(r, w, lp, count, rank);
    }
    if (rank < count)
        r->st.arc_ranked++;
    else
        write_wing_length(r, w, p, k, lp, xa, m);
    for (uint32_t i = 0; i < m; i++) {
        uint32_t prev = NIL, c = r->head[p];
        while (r->disp[3 * (c / 3) + (c % 3 + 1) % 3] != a)
            prev = c, c = r->next[c];
        a = r->disp[3 * (c / 3) + (c % 3 + 2) % 3];
        if (prev == NIL)
            r->head[p] = r->next[c];
        else
            r->next[prev] = r->next[c];
        list_push(r, k, c);
        r->disp[c] = k;
        r->moves++;
    }
    for (uint32_t f = f0; f < f0 + 2; f++) {
        uint32_t t[3];
        for (int i = 0; i < 3; i++)
            t[i] = srv_pm_resolve(r->pm, r->pm->tris[3 * (size_t)f + i], k + 1);
        add_face(r, t);
    }
}

/* The third vertex of face f at level k + 1. */
static uint32_t third(const replay *r, uint32_t f, uint32_t k, int flip)
{
    return srv_pm_resolve(r->pm, r->pm->tris[3 * (size_t)f + (flip ? 1 : 2)], k + 1);
}

/* ---- parents (mirrors read_parent): continue the round by a scan of
 * the eligible vertices after prev, or start a new one explicitly ---- */
static int parent_ctx(const replay *r, uint32_t v)
{
    return lumo_pmesh_parent_ctx(r->disp, r->head, r->next, r->round_parent, v, r->round_first);
}

/* Mirrors read_round_start(): p + 1 as its class in adaptive unary, then
 * the bits under its leading one as one (c - 1)-bit value. */
static void put_round_start(replay *r, bitwriter *w, uint32_t p, uint32_t k)
{
    uint32_t v = p + 1u, c = 0, cmax = lumo_pmesh_field_bits(k + 1u);
    while (v >> c)
        c++;
    for (uint32_t j = 1; j < cmax && j <= c; j++)
        put_ctx(r, w, lumo_pmesh_start_ctx(j - 1u), j < c);
    put_bits(w, v - ((uint32_t)1 << (c - 1u)), c - 1u);
}

static void put_parent(replay *r, bitwriter *w, uint32_t p, uint32_t prev, uint32_t k)
{
    uint32_t cont = 0;
    if (prev != NIL) {
        cont = p > prev && p < r->round_first && parent_ctx(r, p) >= 0;
        put_ctx(r, w, LUMO_PMESH_CTX_ROUND, cont);
    }
    if (!cont) {
        r->round_first = k;
        put_round_start(r, w, p, k);
    }
    for (uint32_t v = prev + 1; cont && v <= p; v++) {
        int c = parent_ctx(r, v);
        if (c >= 0)
            put_ctx(r, w, (uint32_t)c, v == p);
    }
    r->round_parent[p] = r->round_first;
}

/* Mirrors read_split_kind(): the fan bit, then a mask split's kind code. */
static void put_kind(replay *r, bitwriter *w, uint32_t kind)
{
    uint32_t fan = kind == KIND_FAN;
    put_ctx(r, w, LUMO_PMESH_CTX_KIND + r->last_fan, fan);
    r->last_fan = fan;
    if (fan)
        return;
    if (kind == KIND_PAIR)
        put_bits(w, 1, 1);
    else if (kind == 1)
        put_bits(w, 2, 2);
    else
        put_bits(w, 0, 2), put_bits(w, kind, 4);
}

static int write_split(replay *r, bitwriter *w, uint32_t k, uint32_t prev)
{
    const srv_pm *pm = r->pm;
    uint32_t p = pm->parent[k], moves0 = r->moves;
    double mark = spent(w);
    put_parent(r, w, p, prev, k);
    count_bits(w, &mark, &r->st.parent_bits);
    uint32_t f0 = r->face_count, n = 0;
    while (f0 + n < pm->faces && pm->level[f0 + n] == k + 1)
        n++;
    /* the kind code of read_split_kind() in pmesh_batch.c */
    int paired = n == 2 && face_flip(r, f0, p, k) == 0 && face_flip(r, f0 + 1, p, k) == 1;
    uint32_t m = 0, xa = paired ? third(r, f0, k, 0) : 0;
    int fan = paired && fan_plan(r, p, k, xa, third(r, f0 + 1, k, 1), &m);
    if (fan) {
        put_kind(r, w, KIND_FAN);
        count_bits(w, &mark, &r->st.kind_bits);
        r->st.fans++;
        write_fan(r, w, p, k, f0, xa, m);
        count_bits(w, &mark, &r->st.fan_bits);
        predict(r, w, k);
        return 0;
    }
    if (!paired && (n < 1 || n > 15))
        return -1;
    put_kind(r, w, paired ? KIND_PAIR : n);
    count_bits(w, &mark, &r->st.kind_bits);
    uint32_t lenp = write_moves(r, w, p, k), lenk = r->moves - moves0;
    for (uint32_t i = 0; i < n; i++, lenp++, lenk++)
        if (write_new_face(r, w, f0 + i, p, k, lenp, lenk, paired))
            return -1;
    count_bits(w, &mark, &r->st.mask_bits);
    predict(r, w, k);
    return 0;
}

/* Splits k = from ... to - 1 as one range code (docs/progressive-mesh.md
 * §2.3), its flushed bytes appended to w's: a split record's whole block,
 * or the base record's after its seed. prev: the parent of the split
 * before `from` (NIL for none). 0, or -1 for a level it cannot express. */
static int write_range_code(replay *r, bitwriter *w, uint32_t from, uint32_t to, uint32_t prev)
{
    srv_pm_rc code;
    bitwriter rw = {{0}, 0, &code};
    int rc = 0;
    srv_pm_rc_init(&code);
    for (uint32_t k = from; k < to && !rc; prev = r->pm->parent[k++])
        rc = write_split(r, &rw, k, prev);
    srv_pm_rc_flush(&code);
    srv_buf_put(&w->b, code.out.p ? code.out.p : (const uint8_t *)"", code.out.len);
    w->b.failed |= code.out.failed;
    w->nbits = 8 * w->b.len;
    free(code.out.p);
    return rc;
}

/* The base record's block (docs/progressive-mesh.md §2.3 "Base record"),
 * mirroring run_base_block() in pmesh_batch.c. Streams with Draco
 * payloads: the base mesh's faces resolved at b, each index in tb(b),
 * plain bits. CODED streams: the seed's vertex count and face count + 1
 * as gamma codes, its faces resolved at s in tb(s), its grid integers
 * (and albedo) as plain bits; then, when the seed is smaller than the base
 * mesh, after the zero padding, one range code holding the splits s ..
 * b - 1 exactly as a split record codes them: the contexts and the round
 * state (parents, round start, stamps, kinds, albedo answers) carry on
 * into the split records. Their bits stay out of the stats (split records
 * only). Returns write_split's -1 for a level it cannot express. */
static int write_base(replay *r, bitwriter *w)
{
    const srv_pm *pm = r->pm;
    uint32_t b = pm->base_vertices, s = r->coded ? pm->seed_vertices : b;
    uint32_t sf = r->coded ? pm->seed_faces : pm->base_faces;
    if (r->coded) {
        put_gamma(w, s);
        put_gamma(w, sf + 1u);
    }
    for (uint32_t f = 0; f < sf; f++) {
        uint32_t t[3];
        for (int i = 0; i < 3; i++) {
            t[i] = srv_pm_resolve(pm, pm->tris[3 * (size_t)f + i], s);
            put_trunc(w, t[i], s);
        }
        add_face(r, t);
    }
    for (size_t at = 0; r->coded && at < 3 * (size_t)s; at++)
        put_bits(w, (uint32_t)r->q[at], r->quant_bits);
    for (size_t at = 0; r->coded && pm->albedo && at < 3 * (size_t)s; at++)
        put_bits(w, pm->albedo[at], 8);
    for (uint32_t v = 0; !r->coded && v < b; v++)  /* PREDICTED payload: from the previous vertex */
        for (int c = 0; c < 3; c++)
            r->res[3 * (size_t)v + c] = r->q[3 * (size_t)v + c] - (v ? r->q[3 * (size_t)(v - 1) + c] : 0);
    if (s == b)
        return 0;
    srv_pm_stream_stats keep = r->st;  /* the stats count the split records */
    int rc = write_range_code(r, w, s, b, NIL);
    r->st = keep;
    return rc;
}

/* ---- records -------------------------------------------------------------------- */
static void grid_of(const srv_pm *pm, int bits, srv_draco_quant *q)
{
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (uint32_t v = 0; v < pm->vertices; v++)
        for (int c = 0; c < 3; c++) {
            float x = pm->xyz[3 * (size_t)v + c];
            lo[c] = x < lo[c] ? x : lo[c];
            hi[c] = x > hi[c] ? x : hi[c];
        }
    srv_draco_grid(lo, hi, bits, q);
}

static uint32_t f32bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

/* Grid integer of x: round((x - origin) / range * (2^bits - 1)), clamped;
 * the client turns it back into metres (pmesh_batch.c store_positions). */
static void quantize(const srv_pm *pm, const srv_draco_quant *q, int32_t *out)
{
    double qmax = (double)((1u << q->bits) - 1u);
    for (size_t i = 0; i < 3 * (size_t)pm->vertices; i++) {
        double t = ((double)pm->xyz[i] - q->origin[i % 3]) / q->range * qmax;
        int32_t v = (int32_t)floor(t + 0.5);
        out[i] = v < 0 ? 0 : v > (int32_t)qmax ? (int32_t)qmax : v;
    }
}

/* The batch's Draco payload: the residuals the replay recorded (split
 * vertices from their neighbours' mean, base vertices from the previous
 * one), or absolute positions on the shared grid. */
static lumo_status encode_payload(const replay *r, uint32_t first, uint32_t count,
                                  const srv_pm_stream_options *o, const srv_draco_quant *q,
                                  uint8_t **drc, size_t *len)
{
    const uint8_t *rgb = r->pm->albedo ? r->pm->albedo + 3 * (size_t)first : NULL;
    if (r->coded)
        return *drc = NULL, *len = 0, LUMO_OK;  /* in the blocks */
    if (o->position_coding == LUMO_PMESH_POS_ABSOLUTE)
        return srv_draco_encode_points(r->pm->xyz + 3 * (size_t)first, rgb, count, q, o->draco, drc, len);
    return srv_draco_encode_ints(r->res + 3 * (size_t)first, rgb, count, 3, o->draco, drc, len);
}

/* The record: the block's size doubled (plus 1 when a Draco payload
 * follows) and the payload's size as varints, the CRC-32 of the record's
 * index (a varint, not sent), those varints, the block and the payload;
 * then the block and the payload (docs/progressive-mesh.md §2.2). */
static lumo_status write_record(srv_buf *out, uint32_t index, uint32_t first, uint32_t count,
                                const replay *r, const bitwriter *w, const srv_pm_stream_options *o,
                                const srv_draco_quant *q, srv_pm_batch_info *info)
{
    uint8_t *drc = NULL, head[LUMO_PMESH_BATCH_HEAD_MAX], idx[LUMO_WIRE_VARINT32_MAX];
    size_t drc_len = 0;
    lumo_status st = encode_payload(r, first, count, o, q, &drc, &drc_len);
    if (st)
        return st;
    size_t hn = lumo_wire_put_varint(head, (uint32_t)w->b.len * 2u + (drc_len != 0));
    if (drc_len)
        hn += lumo_wire_put_varint(head + hn, (uint32_t)drc_len);
    uint32_t crc = lumo_wire_crc32(0, idx, lumo_wire_put_varint(idx, index));
    crc = lumo_wire_crc32(crc, head, hn);
    crc = lumo_wire_crc32(crc, w->b.p ? w->b.p : (const uint8_t *)"", w->b.len);
    crc = lumo_wire_crc32(crc, drc, drc_len);
    *info = (srv_pm_batch_info){first, count, r->faces, r->moves, out->len,
                                hn + 4 + w->b.len + drc_len, w->b.len, drc_len};
    srv_buf_put(out, head, hn);
    srv_buf_u32(out, crc);
    srv_buf_put(out, w->b.p ? w->b.p : (const uint8_t *)"", w->b.len);
    srv_buf_put(out, drc, drc_len);
    free(drc);
    return out->failed ? LUMO_ERR_NOMEM : LUMO_OK;
}

/* The header (docs/progressive-mesh.md §2.1) into d (LUMO_PMESH_HEADER_MAX
 * bytes); returns its length. */
static size_t write_header(uint8_t *d, const srv_pm *pm, const srv_pm_stream_options *o,
                           const srv_draco_quant *q, uint32_t nb, const srv_pm_batch_info *bi)
{
    uint32_t maxf = 0, maxm = 0, maxb = 0;
    for (uint32_t i = 0; i < nb; i++) {
        maxf = bi[i].face_count > maxf ? bi[i].face_count : maxf;
        maxm = bi[i].move_count > maxm ? bi[i].move_count : maxm;
        maxb = bi[i].bytes > maxb ? (uint32_t)bi[i].bytes : maxb;
    }
    uint32_t counts[8] = {pm->vertices, pm->faces, pm->base_vertices, pm->base_faces,
                          o->batch_vertices, maxf, maxm, maxb};
    size_t n = 7;
    lumo_wire_put_le32(d, LUMO_PMESH_MAGIC);
    lumo_wire_put_le16(d + 4, (uint16_t)LUMO_PMESH_VERSION);
    for (int i = 0; i < 8; i++)
        n += lumo_wire_put_varint(d + n, counts[i]);
    d[n++] = (uint8_t)q->bits, d[n++] = (uint8_t)o->position_coding;
    d[n++] = (uint8_t)((pm->albedo != NULL) | (o->lattice > 0) << 1);
    for (int i = 0; i < 3; i++, n += 4)
        lumo_wire_put_le32(d + n, f32bits(q->origin[i]));
    lumo_wire_put_le32(d + n, f32bits(q->range)), n += 4;
    d[6] = (uint8_t)(n + 4);
    lumo_wire_put_le32(d + n, lumo_wire_crc32(0, d, n));
    return n + 4;
}

/* ---- per-mesh choices (docs/progressive-mesh.md §2.1) ---- */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double srv_pm_median_edge(const srv_pm *pm)
{
    size_t n = 3 * (size_t)pm->faces;
    double *len = n ? malloc(n * sizeof *len) : NULL, m;
    if (!len)
        return 0;
    for (size_t c = 0; c < n; c++) {
        const float *a = pm->xyz + 3 * (size_t)pm->tris[c];
        const float *b = pm->xyz + 3 * (size_t)pm->tris[c - c % 3 + (c % 3 + 1) % 3];
        double d[3] = {(double)a[0] - b[0], (double)a[1] - b[1], (double)a[2] - b[2]};
        len[c] = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    qsort(len, n, sizeof *len, cmp_double);
    m = len[n / 2];
    free(len);
    return m;
}

int srv_pm_stream_auto_bits(const srv_pm *pm)
{
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (size_t i = 0; i < 3 * (size_t)pm->vertices; i++) {
        lo[i % 3] = pm->xyz[i] < lo[i % 3] ? pm->xyz[i] : lo[i % 3];
        hi[i % 3] = pm->xyz[i] > hi[i % 3] ? pm->xyz[i] : hi[i % 3];
    }
    double range = 0, edge = srv_pm_median_edge(pm);
    for (int c = 0; c < 3; c++)
        range = hi[c] - lo[c] > range ? hi[c] - lo[c] : range;
    int bits = SRV_PM_MIN_AUTO_BITS;
    /* the grid step range / (2^bits - 1) at most edge / EDGE_STEPS */
    while (bits < SRV_PM_MAX_AUTO_BITS && range * SRV_PM_EDGE_STEPS > edge * (double)((1u << bits) - 1u))
        bits++;
    return bits;
}

uint32_t srv_pm_stream_auto_batch(const srv_pm *pm)
{
    uint32_t b = SRV_PM_BATCH;
    while (b < SRV_PM_MAX_BATCH && pm->vertices / SRV_PM_BATCHES_MAX > b)
        b *= 2;
    return b < SRV_PM_MAX_BATCH ? b : SRV_PM_MAX_BATCH;
}

void srv_pm_stream_default_options(srv_pm_stream_options *o)
{
    o->batch_vertices = 0;  /* per mesh: srv_pm_stream_auto_batch */
    o->quant_bits = 0;      /* per mesh: srv_pm_stream_auto_bits */
    o->draco = srv_draco_default_settings();
    o->position_coding = LUMO_PMESH_POS_CODED;
    o->stats = NULL;
    o->fan_rank_escape = 0;
    o->lattice = -1;
}

static double field_bits(const srv_pm_stream_stats *st)
{
    return st->parent_bits + st->kind_bits + st->fan_bits + st->mask_bits + st->pos_bits + st->albedo_bits;
}

/* A written split record's share of the stats: fields_before is
 * field_bits() before its splits. */
static void tally_record(srv_pm_stream_stats *st, double fields_before, uint32_t count,
                         const srv_pm_batch_info *bi)
{
    st->splits += count;
    st->other_bits += 8.0 * (double)bi->side_bytes - (field_bits(st) - fields_before);
    st->draco_bytes += bi->draco_bytes;
    st->frame_bytes += bi->bytes - bi->side_bytes - bi->draco_bytes;
}

static lumo_status write_batches(replay *r, const srv_pm_stream_options *o,
                                 const srv_draco_quant *q, srv_buf *out, srv_pm_batch_info *bi,
                                 uint32_t nb)
{
    const srv_pm *pm = r->pm;
    /* the first split vertex: the seed's size in a CODED stream */
    uint32_t split0 = r->coded ? pm->seed_vertices : pm->base_vertices;
    for (uint32_t i = 0; i < nb; i++) {
        uint32_t first = i ? pm->base_vertices + (i - 1) * o->batch_vertices : 0;
        uint32_t count = i ? pm->vertices - first : pm->base_vertices;
        if (i && count > o->batch_vertices)
            count = o->batch_vertices;
        bitwriter w = {{0}, 0, NULL};
        r->faces = r->moves = 0;
        double fields_before = field_bits(&r->st);
        int rc = 0;   /* write_split: -1 for a level it cannot express */
        lumo_status st = LUMO_OK;
        /* parents run on across records (a round rarely ends at a record's
         * end), from the base record's splits on */
        uint32_t prev0 = i && first - 1 >= split0 ? pm->parent[first - 1] : NIL;
        rc = i ? write_range_code(r, &w, first, first + count, prev0) : write_base(r, &w);
        if (!rc && !w.b.failed)
            st = write_record(out, i, first, count, r, &w, o, q, &bi[i]);
        if (!rc && !st && i)
            tally_record(&r->st, fields_before, count, &bi[i]);
        free(w.b.p);
        if (rc || st || w.b.failed) {
            fprintf(stderr, "lumo pm stream: cannot write batch %u\n", i);
            return rc ? LUMO_ERR_CORRUPT : st ? st : LUMO_ERR_NOMEM;
        }
    }
    return LUMO_OK;
}

/* One stream with every choice made (o->lattice 0 or 1). */
static lumo_status build_once(const srv_pm *pm, const srv_pm_stream_options *o, uint8_t **out,
                              size_t *len, srv_pm_batch_info **batches, uint32_t *nbatches)
{
    uint32_t rest = pm->vertices - pm->base_vertices;
    uint32_t nb = 1 + rest / o->batch_vertices + (rest % o->batch_vertices != 0);
    srv_draco_quant q;
    grid_of(pm, o->quant_bits, &q);
    replay r;
    memset(&r, 0, sizeof r);
    r.pm = pm, r.rank_escape = o->fan_rank_escape;
    r.coded = o->position_coding == LUMO_PMESH_POS_CODED;
    r.lattice = r.coded && o->lattice > 0;
    r.q = malloc(12 * (size_t)pm->vertices), r.res = malloc(12 * (size_t)pm->vertices);
    r.disp = malloc(12 * (size_t)pm->faces + 4), r.next = malloc(12 * (size_t)pm->faces + 4);
    r.head = malloc(4 * (size_t)pm->vertices);
    r.round_parent = calloc(pm->vertices, 4);
    lumo_pmesh_init_contexts(r.ctx);
    srv_pm_batch_info *bi = calloc(nb, sizeof *bi);
    srv_buf recs = {0}, s = {0};
    uint8_t header[LUMO_PMESH_HEADER_MAX];
    lumo_status rc = LUMO_ERR_NOMEM;
    if (!r.q || !r.res || !r.disp || !r.next || !r.head || !r.round_parent || !bi)
        goto done;
    quantize(pm, &q, r.q);
    r.quant_bits = (unsigned)q.bits;
    memset(r.head, 0xff, 4 * (size_t)pm->vertices);
    rc = write_batches(&r, o, &q, &recs, bi, nb);
    if (!rc && recs.failed)
        rc = LUMO_ERR_NOMEM;
    if (rc)
        goto done;
    /* the header's counts are known now; the records move behind it */
    size_t hn = write_header(header, pm, o, &q, nb, bi);
    srv_buf_put(&s, header, hn);
    srv_buf_put(&s, recs.p, recs.len);
    if (s.failed) {
        rc = LUMO_ERR_NOMEM;
        goto done;
    }
    for (uint32_t i = 0; i < nb; i++)
        bi[i].offset += hn;
    if (o->stats)
        *o->stats = r.st;
    *out = s.p, *len = s.len, s.p = NULL;
    if (batches)
        *batches = bi, bi = NULL;
    if (nbatches)
        *nbatches = nb;
    rc = LUMO_OK;
done:
    free(r.q);
    free(r.res);
    free(r.disp);
    free(r.next);
    free(r.head);
    free(r.round_parent);
    free(bi);
    free(recs.p);
    free(s.p);
    return rc;
}

lumo_status srv_pm_stream_build(const srv_pm *pm, const srv_pm_stream_options *o, uint8_t **out,
                                size_t *len, srv_pm_batch_info **batches, uint32_t *nbatches)
{
    srv_pm_stream_options def;
    if (!o) {
        srv_pm_stream_default_options(&def);
        o = &def;
    }
    if (!pm->vertices || o->quant_bits < 0 || o->quant_bits > (int)LUMO_PMESH_MAX_QBITS)
        return LUMO_ERR_ARG;
    srv_pm_stream_options chosen = *o;
    if (!chosen.batch_vertices)
        chosen.batch_vertices = srv_pm_stream_auto_batch(pm);
    if (!chosen.quant_bits)
        chosen.quant_bits = srv_pm_stream_auto_bits(pm);
    if (chosen.position_coding != LUMO_PMESH_POS_CODED)
        chosen.lattice = 0;
    if (chosen.lattice >= 0)
        return build_once(pm, &chosen, out, len, batches, nbatches);
    /* per mesh: with lattice copies only where they make the stream smaller */
    srv_pm_stream_stats st[2];
    srv_pm_batch_info *bi[2] = {NULL, NULL};
    uint8_t *s[2] = {NULL, NULL};
    size_t n[2] = {0, 0};
    lumo_status rc = LUMO_OK;
    for (int l = 0; l < 2 && !rc; l++) {
        chosen.lattice = l, chosen.stats = &st[l];
        rc = build_once(pm, &chosen, &s[l], &n[l], batches ? &bi[l] : NULL, nbatches);
    }
    int keep = !rc && n[1] < n[0];
    free(s[!keep]), free(bi[!keep]);
    if (rc) {
        free(s[keep]), free(bi[keep]);
        return rc;
    }
    if (o->stats)
        *o->stats = st[keep];
    if (batches)
        *batches = bi[keep];
    *out = s[keep], *len = n[keep];
    return LUMO_OK;
}
