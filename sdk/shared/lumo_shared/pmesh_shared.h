/*
 * lumo_shared/pmesh_shared.h — what the progressive-mesh stream's writer
 * (server/pm) and its decoder (sdk/src/pmesh_batch.c) must agree on beyond
 * the public format: the codes' parameters, the fan ranking and the
 * position prediction (docs/progressive-mesh.md §2.3). Not client API: an
 * application never needs it; the implementations live in
 * sdk/src/pmesh_predict.c and are linked from liblumo.a by both sides, so
 * the two orders cannot drift apart.
 */
#ifndef LUMO_SHARED_PMESH_SHARED_H
#define LUMO_SHARED_PMESH_SHARED_H

#include <stdint.h>
#include "lumo/pmesh.h"

/* Split records are one adaptive binary range code (docs/progressive-mesh.md
 * §2.3, "Range code"; LZMA's coder with counted contexts): a context is
 * one uint32, its probability of a 0 in PROB_BITS bits (low 16 bits), the
 * number of bits it has coded (bits 16 ... 23, at most COUNT_MAX) and its
 * rate s (bits 24 ... 26).
 * After every coded bit the probability moves by 1/2^s of its distance to
 * 0 or 1, s = floor(log2(count + 2)) clamped to RATE_MAX: a fresh context
 * learns fast (s = 1 after its first bit, as a Krichevsky-Trofimov
 * estimate would), a busy one averages over about 2^RATE_MAX bits
 * (version 5 moved every context by 1/32 with 11-bit probabilities: the
 * 871k dragon 0.95% larger, the bunny 0.4%). The range is renormalised a
 * byte at a time below TOP. The decoder is sdk/src/pmesh_rc.c, the
 * encoder server/pm/pm_rc.c. */
#define LUMO_PMESH_RC_PROB_BITS 15u
#define LUMO_PMESH_RC_PROB_INIT (1u << (LUMO_PMESH_RC_PROB_BITS - 1))
#define LUMO_PMESH_RC_RATE_MAX  7u
#define LUMO_PMESH_RC_COUNT_MAX ((1u << LUMO_PMESH_RC_RATE_MAX) - 2u)
typedef char lumo_pmesh_rate_fit[LUMO_PMESH_RC_RATE_MAX == 7u ? 1 : -1];  /* lumo_pmesh_ctx_make */
#define LUMO_PMESH_RC_TOP       (1u << 24)

/* A context's probability of a 0 (1 ... 2^PROB_BITS - 1). */
static inline uint32_t lumo_pmesh_ctx_prob(uint32_t ctx)
{
    return ctx & 0xffffu;
}
/* A context of probability prob and count (at most COUNT_MAX); its rate
 * s = floor(log2(count + 2)) rides along in bits 24 ... 26, so that a
 * coded bit does not work it out again. */
static inline uint32_t lumo_pmesh_ctx_make(uint32_t prob, uint32_t count)
{
    uint32_t s = 1u + (count >= 2u) + (count >= 6u) + (count >= 14u) + (count >= 30u) +
                 (count >= 62u) + (count >= 126u);
    return s << 24 | count << 16 | prob;
}
/* The context after coding `bit`: the probability moves by 1/2^s of its
 * distance to 0 or 1 and stays in 1 ... 2^PROB_BITS - 1; the count grows,
 * and s with it whenever count + 2 reaches a power of two. */
static inline uint32_t lumo_pmesh_ctx_update(uint32_t ctx, uint32_t bit)
{
    uint32_t p = ctx & 0xffffu, n = ctx >> 16 & 0xffu, s = ctx >> 24;
    p = bit ? p - (p >> s) : p + (((1u << LUMO_PMESH_RC_PROB_BITS) - p) >> s);
    if (n < LUMO_PMESH_RC_COUNT_MAX) {
        n++;
        s += ((n + 2u) & (n + 1u)) == 0;
    }
    return s << 24 | n << 16 | p;
}
/* The adaptive contexts (LUMO_PMESH_CONTEXTS of them, lumo/pmesh.h), by
 * first index: whether a parent continues the round; whether an eligible
 * vertex is the parent, by its valence (PARENT_CTXS); whether the split
 * is a fan split, by the previous split's kind (2); the fan rank's class
 * in unary, by the parent's corner count (RANK_CTXS) and place
 * (RANK_CLASSES); the first two bits under the rank's leading one, by
 * class (2 RANK_CLASSES); a mask bit (1). They carry over from record to
 * record. */
#define LUMO_PMESH_PARENT_CTXS  7u
#define LUMO_PMESH_RANK_CTXS    5u
#define LUMO_PMESH_RANK_CLASSES 9u
#define LUMO_PMESH_CTX_ROUND    0u
#define LUMO_PMESH_CTX_PARENT   1u
#define LUMO_PMESH_CTX_KIND     (LUMO_PMESH_CTX_PARENT + LUMO_PMESH_PARENT_CTXS)
#define LUMO_PMESH_CTX_RANK     (LUMO_PMESH_CTX_KIND + 2u)
#define LUMO_PMESH_CTX_RANK_LOW (LUMO_PMESH_CTX_RANK + LUMO_PMESH_RANK_CTXS * LUMO_PMESH_RANK_CLASSES)
#define LUMO_PMESH_CTX_MASK     (LUMO_PMESH_CTX_RANK_LOW + 2u * LUMO_PMESH_RANK_CLASSES)
/* Positions coded in the block (LUMO_PMESH_POS_CODED, §2.3 step 5): each
 * residual's class (its bit length) in unary, by the ring's spread class
 * (SPREAD_CTXS) and place (RES_CLASSES, the last one shared by every later
 * place); the first two bits under its leading one, by class (RES_LOW_CTXS,
 * the last one shared by every larger class) and place. */
#define LUMO_PMESH_SPREAD_CTXS  12u
#define LUMO_PMESH_RES_CLASSES  12u
#define LUMO_PMESH_RES_LOW_CTXS 16u
#define LUMO_PMESH_CTX_RES      (LUMO_PMESH_CTX_MASK + 1u)
#define LUMO_PMESH_CTX_RES_LOW  (LUMO_PMESH_CTX_RES + LUMO_PMESH_SPREAD_CTXS * LUMO_PMESH_RES_CLASSES)
/* A residual's sign (§2.3 step 5): by its class (1 ... SIGN_CLASSES, the
 * last one shared by every larger class) and by the prediction's offset
 * from the parent on that axis (SIGN_DIRS: 0; positive or negative, each
 * below 2^c or not): the residual leans towards the parent, more so when
 * the offset is large against the residual. */
#define LUMO_PMESH_SIGN_CLASSES 6u
#define LUMO_PMESH_SIGN_DIRS    5u
#define LUMO_PMESH_CTX_SIGN     (LUMO_PMESH_CTX_RES_LOW + 2u * LUMO_PMESH_RES_LOW_CTXS)
/* A residual's first class bit ("class > 0", i.e. not zero) when the
 * prediction equals the parent's coordinate on that axis, by the spread
 * class: meshes extracted from voxels (the 871k dragon) put their
 * vertices on lattice lines, where a ring symmetric about the parent on an
 * axis often means k shares that coordinate too (the 871k dragon's
 * positions 12.37 -> 12.10 bits per vertex; one more context set for all
 * places, or one by the offset's size, gained < 0.1 bit more and cost the
 * bunny 0.1 … 0.2%). */
#define LUMO_PMESH_CTX_FLAT     (LUMO_PMESH_CTX_SIGN + LUMO_PMESH_SIGN_CLASSES * LUMO_PMESH_SIGN_DIRS)
/* LATTICE streams (§2.3 step 5): whether an axis's coordinate is copied
 * from the ring, by how many of the ring's vertices repeat a value on
 * that axis (COPY_CTXS, the last one shared by more); the copied value's
 * rank in unary, by place (COPY_RANK_CTXS, the last one shared by every
 * later place). */
#define LUMO_PMESH_COPY_CTXS      5u
#define LUMO_PMESH_COPY_RANK_CTXS 4u
#define LUMO_PMESH_CTX_COPY       (LUMO_PMESH_CTX_FLAT + LUMO_PMESH_SPREAD_CTXS)
#define LUMO_PMESH_CTX_COPY_RANK  (LUMO_PMESH_CTX_COPY + LUMO_PMESH_COPY_CTXS)
/* A new round's first parent p (§2.3 step 1): the class of p + 1 (its bit
 * length) in unary, by place (START_CTXS, the last one shared by every
 * later place). The first parent of a round is its lowest, so small: on
 * the bunny 0 ... 42 where truncated binary spent log2(k), 5 ... 11 bits. */
#define LUMO_PMESH_START_CTXS     16u
#define LUMO_PMESH_CTX_START      (LUMO_PMESH_CTX_COPY_RANK + LUMO_PMESH_COPY_RANK_CTXS)
/* CODED streams with albedo (§2.3 step 6): whether a split vertex's
 * albedo is its parent's, by whether the previous split's was (2); else
 * per channel the residual's class (its bit length, 0 ... 8) in unary by
 * channel and place (3 x ALB_CLASSES), and its sign by channel (3). */
#define LUMO_PMESH_ALB_CLASSES    8u
#define LUMO_PMESH_CTX_ALB_SAME   (LUMO_PMESH_CTX_START + LUMO_PMESH_START_CTXS)
#define LUMO_PMESH_CTX_ALB_CLASS  (LUMO_PMESH_CTX_ALB_SAME + 2u)
#define LUMO_PMESH_CTX_ALB_SIGN   (LUMO_PMESH_CTX_ALB_CLASS + 3u * LUMO_PMESH_ALB_CLASSES)
#define LUMO_PMESH_CTX_END        (LUMO_PMESH_CTX_ALB_SIGN + 3u)
/* An albedo code 0 ... 255 as Q1.14 ((v * 2^14 + 127) / 255) and back
 * (exact for every code: the client keeps only the Q1.14 values). */
static inline uint32_t lumo_pmesh_albedo_q14(uint32_t v)
{
    return (v * 16384u + 127u) / 255u;
}
static inline uint32_t lumo_pmesh_albedo_code(uint32_t q14)
{
    return (q14 * 255u + 8191u) / 16384u;
}
static inline uint32_t lumo_pmesh_start_ctx(uint32_t j)
{
    return LUMO_PMESH_CTX_START + (j < LUMO_PMESH_START_CTXS ? j : LUMO_PMESH_START_CTXS - 1u);
}
typedef char lumo_pmesh_ctx_fit[LUMO_PMESH_CTX_END == LUMO_PMESH_CONTEXTS ? 1 : -1];
/* The contexts at the start of a stream (every record after the base
 * carries them on): a context with a prior starts at its chance of a 0,
 * lumo_pmesh_prior[i] in 1/64 (PRIOR_UNIT in PROB_BITS), and count
 * PRIOR_COUNT (the prior is worth that many bits, so it moves at rate 4);
 * one without (0 in the table) at PROB_INIT (1/2), count 0. The table
 * (pmesh_priors.c) is fitted on training meshes' streams by
 * tools/pm-priors/pm_priors.py: a short stream then does not pay for the
 * code's learning (version 8: about 25 bytes on meshes outside the
 * training set). */
#define LUMO_PMESH_PRIOR_UNIT  512u
#define LUMO_PMESH_PRIOR_COUNT 16u
extern const uint8_t lumo_pmesh_prior[LUMO_PMESH_CONTEXTS];
void lumo_pmesh_init_contexts(uint32_t *ctx);

/* Context of the residual's class bit j ("class > j") under spread class
 * sc, the prediction `offset` grid steps from the parent on that axis, and
 * of bit j (0 or 1) under the leading one of a class-c residual. */
static inline uint32_t lumo_pmesh_res_ctx(uint32_t sc, uint32_t j, int32_t offset)
{
    if (j == 0 && offset == 0)
        return LUMO_PMESH_CTX_FLAT + sc;
    return LUMO_PMESH_CTX_RES + sc * LUMO_PMESH_RES_CLASSES +
           (j < LUMO_PMESH_RES_CLASSES ? j : LUMO_PMESH_RES_CLASSES - 1u);
}
static inline uint32_t lumo_pmesh_res_low_ctx(uint32_t c, uint32_t j)
{
    return LUMO_PMESH_CTX_RES_LOW + 2u * (c < LUMO_PMESH_RES_LOW_CTXS ? c : LUMO_PMESH_RES_LOW_CTXS - 1u) + j;
}
/* Context of the sign of a class-c residual (c >= 1) whose prediction
 * lies `offset` grid steps from the parent on its axis. */
static inline uint32_t lumo_pmesh_sign_ctx(uint32_t c, int32_t offset)
{
    uint32_t mag = (uint32_t)(offset < 0 ? -(int64_t)offset : offset);
    uint32_t dir = offset > 0 ? 1u : offset < 0 ? 2u : 0u;
    uint32_t b = c < LUMO_PMESH_SIGN_CLASSES ? c - 1u : LUMO_PMESH_SIGN_CLASSES - 1u;
    if (dir && (mag >> c) != 0)  /* c < 32 */
        dir += 2u;
    return LUMO_PMESH_CTX_SIGN + LUMO_PMESH_SIGN_DIRS * b + dir;
}

/* Context of the rank's class bit c for a parent with n corners. */
static inline uint32_t lumo_pmesh_rank_ctx(uint32_t n, uint32_t c)
{
    uint32_t b = n < 6u ? 0u : n > 10u ? 4u : n - 6u;
    return LUMO_PMESH_CTX_RANK + b * LUMO_PMESH_RANK_CLASSES + c;
}

/* Parent scan (§2.3 step 1): vertex v may be the parent of a split that
 * continues the round that began with vertex round_first when it has a
 * face and no neighbour that is an end of a split of this round: a vertex
 * at or above round_first, or a parent u of the round (round_parent[u] ==
 * round_first). The server's collapses of one round are independent,
 * their ends two edges apart. Returns the context of its flag
 * (CTX_PARENT + its valence bucket), or -1 when it is not eligible. Work:
 * v's corners. Shared by the writer and the decoder. */
int lumo_pmesh_parent_ctx(const uint32_t *tris, const uint32_t *head, const uint32_t *next,
                          const uint32_t *round_parent, uint32_t v, uint32_t round_first);

/* Fan splits whose parent has at most ARC_MAX_CORNERS corners name their
 * fan (first wing and length) by its rank among p's fans ordered by a
 * geometric score, coded by its class in adaptive bits (§2.3 step 3). */
#define LUMO_PMESH_ARC_MAX_CORNERS 16u
/* The fan score sees grid integers of at most ARC_BITS bits (q >> (bits -
 * ARC_BITS) on finer grids), so a score and the candidate's id fit one
 * int64 key. */
#define LUMO_PMESH_ARC_BITS 14u
/* The candidate fans of a fan split whose parent p has n corners (1 ...
 * ARC_MAX_CORNERS), ranked by geometry (docs/progressive-mesh.md §2.3
 * step 3; sdk/src/pmesh_predict.c). The stream writer and the decoder share
 * it so that both order the candidates identically. nx[i] / pv[i]: the
 * vertices after / before p in the face of corner i of L(p), in list
 * order; q: grid integers, 3 per vertex. */
#define LUMO_PMESH_FAN_NONE 0xffu
typedef struct lumo_pmesh_fan {
    uint32_t n;
    uint32_t nx[LUMO_PMESH_ARC_MAX_CORNERS];
    uint8_t  succ[LUMO_PMESH_ARC_MAX_CORNERS];   /* corner after i in the fan, or FAN_NONE */
    uint8_t  first[LUMO_PMESH_ARC_MAX_CORNERS];  /* first corner with the same nx */
    int64_t  w[LUMO_PMESH_ARC_MAX_CORNERS], ring;
} lumo_pmesh_fan;
void lumo_pmesh_fan_init(lumo_pmesh_fan *g, const int32_t *q, unsigned quant_bits, uint32_t p,
                         const uint32_t *nx, const uint32_t *pv, uint32_t n);
/* Every candidate's key into key[] (room for n^2), in enumeration order;
 * returns their count. A higher key ranks first; keys are distinct. */
uint32_t lumo_pmesh_fan_keys(const lumo_pmesh_fan *g, int64_t *key);
/* The candidate a key names: i << 8 | m (corner i of L(p), m corners). */
static inline uint32_t lumo_pmesh_fan_key_id(int64_t key)
{
    return 4095u - (uint32_t)((uint64_t)key & 4095u);
}

/* What a split vertex k's ring predicts right after its split, with
 * parent p (docs/progressive-mesh.md §2.3 step 5; sdk/src/pmesh_predict.c):
 * pred, a blend of p, the wings' mean and the inner ring's mean; sc[],
 * each axis's spread class (0 ... SPREAD_CTXS - 1), the bit length of 3
 * times the extent (max - min) of the ring and p on that axis, which
 * scales with the residual on that axis; vert[], when keep_ring (a
 * LATTICE stream, which copies coordinates from them), the ring's first
 * RING_MAX distinct vertices, p first, in walk order (else only p). L(k) is walked from head[k] through
 * next[] until LUMO_PMESH_NIL, corner c showing tris[c]; q holds 3 grid
 * integers per vertex. Shared by the stream writer and the decoder. */
#define LUMO_PMESH_NIL 0xffffffffu
#define LUMO_PMESH_RING_MAX 32u
typedef struct lumo_pmesh_ring {
    int32_t  pred[3];
    uint32_t sc[3];
    uint32_t n;                        /* vertices in vert[] (>= 1) */
    uint32_t vert[LUMO_PMESH_RING_MAX];
} lumo_pmesh_ring;
void lumo_pmesh_predict_position(const int32_t *q, const uint32_t *tris, const uint32_t *head,
                                 const uint32_t *next, uint32_t k, uint32_t p, int keep_ring,
                                 lumo_pmesh_ring *ring);
/* The distinct values on axis d of the ring's vertices into cand[] (room
 * for RING_MAX), nearest the prediction first (ties: the smaller value);
 * returns their count m and sets *copy_ctx, the context of the copy flag
 * (CTX_COPY + min(n - m, COPY_CTXS - 1): how many vertices repeat a
 * value). Work: RING_MAX^2 at most. */
uint32_t lumo_pmesh_lattice_values(const int32_t *q, const lumo_pmesh_ring *ring, unsigned d,
                                   int32_t *cand, uint32_t *copy_ctx);
static inline uint32_t lumo_pmesh_copy_rank_ctx(uint32_t j)
{
    return LUMO_PMESH_CTX_COPY_RANK + (j < LUMO_PMESH_COPY_RANK_CTXS ? j : LUMO_PMESH_COPY_RANK_CTXS - 1u);
}

/* w(c) of docs/progressive-mesh.md: the bit width of a value in [0, count),
 * the smallest n with 2^n >= count (0 for count <= 1). The stream writer
 * and the batch decoder size every packed field with it. */
static inline unsigned lumo_pmesh_field_bits(uint32_t count)
{
    unsigned n = 0;
    while (n < 32 && ((uint64_t)1 << n) < count)
        n++;
    return n;
}

#endif /* LUMO_SHARED_PMESH_SHARED_H */
