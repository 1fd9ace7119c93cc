/*
 * pmesh_predict.c — what a vertex split predicts from the geometry already
 * held: the ranking of its candidate fans (docs/progressive-mesh.md §2.3
 * step 3) and its position (step 5). One definition for the stream writer
 * (server/pm_stream.c) and the batch decoder (pmesh_batch.c): both must
 * predict identically, bit for bit.
 *
 * Fans:
 * After the collapse of k onto p, the vertices k brought into p's ring lie
 * about two edges from p, the others one, and k usually takes about half
 * of p's fan: the moved fan is most likely a half-fan whose inner ring
 * vertices are farthest from p. The candidates (i, m): corner i of L(p)
 * (the first one whose next vertex is nx[i]) and m moved corners, walking
 * on through succ. On grid integers of at most ARC_BITS bits, with
 * ring = sum_i |nx[i] - p|^2, the score is 16 * (the sum over the m - 1
 * inner vertices pv[j] of n |pv[j] - p|^2 - ring) - 3 ring (m - (n-1)/2)^2,
 * |score| < 2^44; the key score * 4096 + 4095 - (i << 8 | m) orders the
 * candidates (higher score first, then smaller i, then smaller m) in one
 * int64 comparison. The weights are measured (docs/progressive-mesh.md §4).
 */
#include "lumo/pmesh.h"
#include "lumo_shared/pmesh_shared.h"

#define FAN_N LUMO_PMESH_ARC_MAX_CORNERS

/* Squared distance of grid points a and p, each coordinate >> shift. */
static int64_t fan_dist2(const int32_t *q, uint32_t a, uint32_t p, unsigned shift)
{
    int64_t s = 0;
    unsigned d;
    for (d = 0; d < 3; d++) {
        int64_t e = (int64_t)(q[3 * (size_t)a + d] >> shift) - (q[3 * (size_t)p + d] >> shift);
        s += e * e;
    }
    return s;
}

void lumo_pmesh_fan_init(lumo_pmesh_fan *g, const int32_t *q, unsigned quant_bits, uint32_t p,
                         const uint32_t *nx, const uint32_t *pv, uint32_t n)
{
    unsigned shift = quant_bits > LUMO_PMESH_ARC_BITS ? quant_bits - LUMO_PMESH_ARC_BITS : 0;
    int64_t ring = 0;
    uint32_t i, j;

    for (i = 0; i < n; i++) {
        g->nx[i] = nx[i];
        ring += fan_dist2(q, nx[i], p, shift);
    }
    g->n = n, g->ring = ring;
    for (i = 0; i < n; i++) {
        for (j = 0; j < i && nx[j] != nx[i]; j++)
            ;
        g->first[i] = (uint8_t)j;
        for (j = 0; j < n && nx[j] != pv[i]; j++)
            ;
        g->succ[i] = j < n ? (uint8_t)j : LUMO_PMESH_FAN_NONE;
        g->w[i] = 16 * ((int64_t)n * fan_dist2(q, pv[i], p, shift) - ring);
    }
}

/* The length term 3 ring (m - (n - 1) / 2)^2 is worked out once per m. */
uint32_t lumo_pmesh_fan_keys(const lumo_pmesh_fan *g, int64_t *key)
{
    int64_t length_cost[FAN_N + 1];
    uint32_t count = 0, i, m, j;

    for (m = 1; m <= g->n; m++) {
        int64_t d = (int64_t)m - (int64_t)(g->n - 1) / 2;
        length_cost[m] = 3 * g->ring * d * d;
    }
    for (i = 0; i < g->n; i++) {
        int64_t inner = 0;
        if (g->first[i] != i)
            continue;
        for (m = 1, j = i; m <= g->n; m++) {
            key[count++] = (inner - length_cost[m]) * 4096 + (int64_t)(4095u - (i << 8 | m));
            if (g->succ[j] == LUMO_PMESH_FAN_NONE)
                break;
            inner += g->w[j];
            j = g->succ[j];
        }
    }
    return count;
}

/* The ring's box per axis; its extent's bit length (times 3) is that
 * axis's spread class. */
static void grow_box(const int32_t *v, int32_t lo[3], int32_t hi[3])
{
    for (unsigned d = 0; d < 3; d++) {
        lo[d] = v[d] < lo[d] ? v[d] : lo[d];
        hi[d] = v[d] > hi[d] ? v[d] : hi[d];
    }
}

static uint32_t spread_class(int32_t lo, int32_t hi)
{
    uint32_t extent = 3u * (uint32_t)(hi - lo), sc = 0;  /* < 3 * 2^20: no overflow */
    while (extent >> sc)
        sc++;
    return sc < LUMO_PMESH_SPREAD_CTXS ? sc : LUMO_PMESH_SPREAD_CTXS - 1u;
}

/* Weights of p, the wings and the inner ring, in 1/16, by how often
 * inner vertices appear among k's faces' corners (each inner vertex of a
 * closed fan twice): 0, 1-2, 3-4, more. */
static const uint8_t BLEND[4][3] = {{7, 9, 0}, {7, 4, 5}, {7, 2, 7}, {8, 0, 8}};
/* The parallelograms' share of the prediction, in 1/16 (version 8:
 * measured 1 to 3 on the 11k and 48k dragons and the cow, 1 best). */
#define PAR_WEIGHT 1

/* Both: the vertices after (o[0]) and before (o[1]) corner c in its face.
 * Inlined on every target: the Cortex-M3 build (-Os) called it once per
 * corner of the parent scan (board replay: 6.36 -> 6.17 M a geometry batch). */
static inline __attribute__((always_inline)) void corner_sides(const uint32_t *tris, uint32_t c,
                                                          uint32_t o[2])
{
    const uint32_t *t = tris + (c - c % 3);
    unsigned i = c % 3;
    o[0] = t[i == 2 ? 0 : i + 1], o[1] = t[i == 0 ? 2 : i - 1];
}

/* Keep v among the ring's first RING_MAX distinct vertices. */
static void ring_keep(lumo_pmesh_ring *r, uint32_t v)
{
    uint32_t i;
    for (i = 0; i < r->n; i++)
        if (r->vert[i] == v)
            return;
    if (r->n < LUMO_PMESH_RING_MAX)
        r->vert[r->n++] = v;
}

/* A wing is a vertex sharing a face with k and p; at most WINGS_MAX are
 * told apart (a split adds at most 15 faces on (k, p), a manifold one 2). */
#define WINGS_MAX 16u

static uint32_t find_wings(const uint32_t *tris, const uint32_t *head, const uint32_t *next,
                           uint32_t k, uint32_t p, uint32_t *wing)
{
    uint32_t n = 0, c;
    for (c = head[k]; c != LUMO_PMESH_NIL && n < WINGS_MAX; c = next[c]) {
        uint32_t o[2];
        corner_sides(tris, c, o);
        if (o[0] == p)
            wing[n++] = o[1];
        if (o[1] == p && n < WINGS_MAX)
            wing[n++] = o[0];
    }
    return n;
}

static int among(const uint32_t *set, uint32_t n, uint32_t v)
{
    while (n--)
        if (set[n] == v)
            return 1;
    return 0;
}

/* The rounded mean of n grid values summing to sum (both >= 0), or
 * fallback when there are none. A 32-bit division when the sum allows
 * (always, in practice): the same quotient, and a Cortex-M3 divides 32
 * bits in hardware but 64 in a library call. */
static int64_t mean_or(int64_t sum, uint32_t n, int32_t fallback)
{
    if (!n)
        return fallback;
    if (sum + n / 2 <= (int64_t)UINT32_MAX)
        return (uint32_t)(sum + n / 2) / n;
    return (sum + n / 2) / n;
}

/* The ring's bend along its normal, carried over to k (§2.3 step 5): on a
 * curved surface p stands off the plane of its ring by h, and k, one
 * edge away on the same surface, stands off its prediction by about
 * BEND_NUM / BEND_DEN of that. N is the sum of the cross products (a - p) x
 * (b - p) over k's faces (k, a, b), scaled down to 15 bits per axis; h the
 * offset of p from the ring's mean along N. Rings of more than
 * BEND_MAX_CORNERS corners (no surface to speak of) are not bent. All
 * integer: |N| < 2^15, |p - mean| * count < 2^28, products < 2^62. */
#define BEND_NUM 3
#define BEND_DEN 8
#define BEND_MAX_CORNERS 64u

static int64_t div_round(int64_t num, int64_t den)  /* den > 0; half away from 0 */
{
    return (num >= 0 ? num + den / 2 : num - den / 2) / den;
}

/* Add corner c's cross product (a - p) x (b - p) to n (one of at most
 * BEND_MAX_CORNERS: each below 2^43, their sum fits int64). */
static void add_cross(const int32_t *q, const int32_t *qp, const uint32_t o[2], int64_t n[3])
{
    const int32_t *a = q + 3 * (size_t)o[0], *b = q + 3 * (size_t)o[1];
    int64_t u[3], v[3];
    unsigned d;
    for (d = 0; d < 3; d++)
        u[d] = (int64_t)a[d] - qp[d], v[d] = (int64_t)b[d] - qp[d];
    n[0] += u[1] * v[2] - u[2] * v[1];
    n[1] += u[2] * v[0] - u[0] * v[2];
    n[2] += u[0] * v[1] - u[1] * v[0];
}

/* The bend from N (the summed cross products) and the ring's sums. */
static void curvature(const int32_t *qp, int64_t n[3], const int64_t rsum[3], uint32_t count,
                      int32_t bend[3])
{
    int64_t big = 0, h = 0, nn = 0;
    unsigned d, shift = 0;
    for (d = 0; d < 3; d++)
        big = n[d] > big ? n[d] : -n[d] > big ? -n[d] : big;
    while (big >> shift >= (int64_t)1 << 15)
        shift++;
    for (d = 0; d < 3; d++)  /* halved `shift` times, truncating toward 0 */
        n[d] = n[d] < 0 ? -(-n[d] >> shift) : n[d] >> shift;
    for (d = 0; d < 3; d++) {
        h += ((int64_t)qp[d] * count - rsum[d]) * n[d];
        nn += n[d] * n[d];
    }
    if (!nn || !count)
        return;
    for (d = 0; d < 3; d++)
        bend[d] = (int32_t)div_round(BEND_NUM * h * n[d], (int64_t)BEND_DEN * count * nn);
}

/* The parallelograms of k's wings (docs/progressive-mesh.md §2.3 step 5):
 * for each wing w, the first face of L(p) holding w beside p whose third
 * vertex x is neither k nor a wing lies across the edge (p, w) from k's
 * face (k, p, w), and k would sit at p + w - x on a regular mesh (the
 * single-rate coders' parallelogram rule). Each point is clamped to the
 * ring's box, so the sums stay non-negative; returns how many were found. */
static uint32_t parallelograms(const int32_t *q, const uint32_t *tris, const uint32_t *head,
                               const uint32_t *next, uint32_t k, uint32_t p, const uint32_t *wing,
                               uint32_t nwing, const int32_t lo[3], const int32_t hi[3], int64_t sum[3])
{
    const int32_t *qp = q + 3 * (size_t)p;
    uint32_t n = 0, i, c, d;
    for (i = 0; i < nwing; i++)
        for (c = head[p]; c != LUMO_PMESH_NIL; c = next[c]) {
            uint32_t o[2], x;
            corner_sides(tris, c, o);
            if (o[0] != wing[i] && o[1] != wing[i])
                continue;
            x = o[0] == wing[i] ? o[1] : o[0];
            if (x == k || among(wing, nwing, x))
                continue;
            for (d = 0; d < 3; d++) {
                int32_t g = qp[d] + q[3 * (size_t)wing[i] + d] - q[3 * (size_t)x + d];
                sum[d] += g < lo[d] ? lo[d] : g > hi[d] ? hi[d] : g;
            }
            n++;
            break;
        }
    return n;
}

/* The prediction blends three points of k's ring (docs/progressive-mesh.md
 * §2.3 step 5): the parent p, the mean of the wings (the vertices sharing
 * a face with both k and p) and the mean of the inner ring (k's other
 * neighbours, each counted once per face of k it is in), with weights in
 * 1/16 by the inner ring's corner count. Why: a collapsed edge is short
 * (that made it cheap), so k lies about halfway between p and the
 * neighbours it brought, not at its ring's centroid; the wings, beside
 * the edge, say little once there are inner vertices (weights fitted by
 * least absolute error on the bunny and the 11k and 48k dragons, §4.1).
 * Grid integers are non-negative, so the division rounds half up on every
 * target; the bend (above) is added and the sum clamped to the ring's box,
 * which the same walk gives. */
void lumo_pmesh_predict_position(const int32_t *q, const uint32_t *tris, const uint32_t *head,
                                 const uint32_t *next, uint32_t k, uint32_t p, int keep_ring,
                                 lumo_pmesh_ring *ring)
{
    int64_t wsum[3] = {0, 0, 0}, isum[3] = {0, 0, 0};
    const int32_t *qp = q + 3 * (size_t)p;
    int32_t lo[3] = {qp[0], qp[1], qp[2]}, hi[3] = {qp[0], qp[1], qp[2]};
    uint32_t wing[WINGS_MAX], nwing = find_wings(tris, head, next, k, p, wing);
    int64_t normal[3] = {0, 0, 0};
    uint32_t nw = 0, ni = 0, corners = 0, c;
    unsigned s, d;

    ring->n = 1, ring->vert[0] = p;
    for (c = head[k]; c != LUMO_PMESH_NIL; c = next[c]) {
        uint32_t o[2];
        corner_sides(tris, c, o);
        if (++corners <= BEND_MAX_CORNERS)
            add_cross(q, qp, o, normal);
        for (s = 0; s < 2; s++) {
            uint32_t v = o[s];
            const int32_t *qv = q + 3 * (size_t)v;
            int is_w = among(wing, nwing, v);
            if (v == p)
                continue;
            grow_box(qv, lo, hi);
            if (keep_ring)
                ring_keep(ring, v);
            nw += (uint32_t)is_w, ni += (uint32_t)!is_w;
            for (d = 0; d < 3; d++)
                *(is_w ? &wsum[d] : &isum[d]) += qv[d];  /* < 2^30 corners of 2^20: fits */
        }
    }
    {
        const uint8_t *w = BLEND[ni == 0 ? 0 : ni <= 2 ? 1 : ni <= 4 ? 2 : 3];
        int32_t bend[3] = {0, 0, 0};
        int64_t rsum[3] = {wsum[0] + isum[0], wsum[1] + isum[1], wsum[2] + isum[2]};
        int64_t psum[3] = {0, 0, 0};
        uint32_t npar = parallelograms(q, tris, head, next, k, p, wing, nwing, lo, hi, psum);
        if (corners <= BEND_MAX_CORNERS)
            curvature(qp, normal, rsum, nw + ni, bend);
        for (d = 0; d < 3; d++) {
            int64_t blend = w[0] * (int64_t)qp[d] + w[1] * mean_or(wsum[d], nw, qp[d]) +
                            w[2] * mean_or(isum[d], ni, qp[d]);
            int64_t v = npar ? (blend * (16 - PAR_WEIGHT) + 16 * PAR_WEIGHT * mean_or(psum[d], npar, 0) + 128) / 256
                             : (blend + 8) / 16;
            v += bend[d];
            ring->pred[d] = (int32_t)(v < lo[d] ? lo[d] : v > hi[d] ? hi[d] : v);
            ring->sc[d] = spread_class(lo[d], hi[d]);
        }
    }
}

static uint32_t distance(int32_t a, int32_t b)
{
    return a > b ? (uint32_t)a - (uint32_t)b : (uint32_t)b - (uint32_t)a;
}

/* Does x come before y: nearer the prediction, then smaller. */
static int nearer(int32_t x, int32_t y, int32_t pred)
{
    uint32_t dx = distance(x, pred), dy = distance(y, pred);
    return dx != dy ? dx < dy : x < y;
}

uint32_t lumo_pmesh_lattice_values(const int32_t *q, const lumo_pmesh_ring *ring, unsigned d,
                                   int32_t *cand, uint32_t *copy_ctx)
{
    uint32_t m = 0, i, j, rep;
    for (i = 0; i < ring->n; i++) {
        int32_t v = q[3 * (size_t)ring->vert[i] + d];
        for (j = 0; j < m && cand[j] != v; j++)
            ;
        if (j < m)
            continue;
        for (j = m++; j > 0 && nearer(v, cand[j - 1], ring->pred[d]); j--)
            cand[j] = cand[j - 1];
        cand[j] = v;
    }
    rep = ring->n - m;
    *copy_ctx = LUMO_PMESH_CTX_COPY + (rep < LUMO_PMESH_COPY_CTXS ? rep : LUMO_PMESH_COPY_CTXS - 1u);
    return m;
}

void lumo_pmesh_init_contexts(uint32_t *ctx)
{
    for (uint32_t i = 0; i < LUMO_PMESH_CONTEXTS; i++)
        ctx[i] = lumo_pmesh_prior[i]
                     ? lumo_pmesh_ctx_make(lumo_pmesh_prior[i] * LUMO_PMESH_PRIOR_UNIT, LUMO_PMESH_PRIOR_COUNT)
                     : lumo_pmesh_ctx_make(LUMO_PMESH_RC_PROB_INIT, 0);
}

/* Eligible parents of a continued round (pmesh_shared.h): a face, and no
 * neighbour split in this round. The bucket is the valence clamped to
 * 3 ... 3 + PARENT_CTXS - 1 (parents of a round have 7-8 faces rather
 * than 6: the collapse took one or two). */
static int round_end(const uint32_t *round_parent, uint32_t u, uint32_t round_first)
{
    return u >= round_first || round_parent[u] == round_first;
}

int lumo_pmesh_parent_ctx(const uint32_t *tris, const uint32_t *head, const uint32_t *next,
                          const uint32_t *round_parent, uint32_t v, uint32_t round_first)
{
    uint32_t n = 0, c;
    for (c = head[v]; c != LUMO_PMESH_NIL; c = next[c], n++) {
        uint32_t o[2];
        corner_sides(tris, c, o);
        if (round_end(round_parent, o[0], round_first) || round_end(round_parent, o[1], round_first))
            return -1;
    }
    if (!n)
        return -1;
    n = n < 3u ? 3u : n > 2u + LUMO_PMESH_PARENT_CTXS ? 2u + LUMO_PMESH_PARENT_CTXS : n;
    return (int)(LUMO_PMESH_CTX_PARENT + n - 3u);
}
