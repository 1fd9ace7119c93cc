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

/* The rounded mean of the corners of k's faces (k itself excluded), the
 * parent counted LUMO_PMESH_PARENT_WEIGHT more times. Grid integers are
 * non-negative, so the division rounds half up on every target. The same
 * walk gives the ring's extent per axis, whose bit length (times 3) is
 * that axis's spread class. */
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

void lumo_pmesh_predict_position(const int32_t *q, const uint32_t *tris, const uint32_t *head,
                                 const uint32_t *next, uint32_t k, uint32_t p, int32_t pred[3],
                                 uint32_t sc[3])
{
    int64_t sum[3] = {0, 0, 0};
    const int32_t *qp = q + 3 * (size_t)p;
    int32_t lo[3] = {qp[0], qp[1], qp[2]}, hi[3] = {qp[0], qp[1], qp[2]};
    uint32_t n = LUMO_PMESH_PARENT_WEIGHT, c;
    unsigned i, d;

    for (c = head[k]; c != LUMO_PMESH_NIL; c = next[c], n += 2) {
        const uint32_t *t = tris + 3 * (size_t)(c / 3);
        for (i = 0; i < 3; i++)
            if (t[i] != k) {
                for (d = 0; d < 3; d++)
                    sum[d] += q[3 * (size_t)t[i] + d];
                grow_box(q + 3 * (size_t)t[i], lo, hi);
            }
    }
    for (d = 0; d < 3; d++) {
        sum[d] += (int64_t)LUMO_PMESH_PARENT_WEIGHT * qp[d];
        pred[d] = (int32_t)((sum[d] + n / 2) / n);
        sc[d] = spread_class(lo[d], hi[d]);
    }
}

/* In 1/2048 (version 5's probability unit). */
static uint32_t res_prior(int32_t d)
{
    if (d <= -10)
        return 32u;
    if (d <= -5)
        return 1024u >> (uint32_t)(-5 - d);
    return d == -4 ? 1536u : 1856u;
}

void lumo_pmesh_init_contexts(uint32_t *ctx)
{
    uint32_t i, sc, j;
    for (i = 0; i < LUMO_PMESH_CONTEXTS; i++)
        ctx[i] = lumo_pmesh_ctx_make(LUMO_PMESH_RC_PROB_INIT, 0);
    for (sc = 0; sc < LUMO_PMESH_SPREAD_CTXS; sc++)
        for (j = 0; j < LUMO_PMESH_RES_CLASSES; j++) {
            uint32_t prior = lumo_pmesh_ctx_make(16u * res_prior((int32_t)j - (int32_t)sc),
                                                 LUMO_PMESH_RES_PRIOR_COUNT);
            ctx[lumo_pmesh_res_ctx(sc, j, 1)] = prior;
            if (j == 0)
                ctx[lumo_pmesh_res_ctx(sc, j, 0)] = prior;
        }
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
        const uint32_t *t = tris + 3 * (size_t)(c / 3);
        if (round_end(round_parent, t[(c % 3 + 1) % 3], round_first) ||
            round_end(round_parent, t[(c % 3 + 2) % 3], round_first))
            return -1;
    }
    if (!n)
        return -1;
    n = n < 3u ? 3u : n > 2u + LUMO_PMESH_PARENT_CTXS ? 2u + LUMO_PMESH_PARENT_CTXS : n;
    return (int)(LUMO_PMESH_CTX_PARENT + n - 3u);
}
