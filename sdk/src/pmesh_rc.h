/* pmesh_rc.h — the range decoder of progressive-mesh split records
 * (docs/progressive-mesh.md §2.3 "Range code"; internal to sdk/src). An
 * adaptive binary range coder as LZMA's: 32-bit range and code, 15-bit
 * probabilities in counted contexts (lumo_shared/pmesh_shared.h),
 * integers only, so every board decodes the same bits.
 * The writer's inverse is server/pm/pm_rc.c. */
#ifndef LUMO_PMESH_RC_H
#define LUMO_PMESH_RC_H

#include <stdint.h>

typedef struct pmesh_rc {
    const uint8_t *p;
    uint32_t n, pos;      /* bytes of the block; next byte to read */
    uint32_t range, code;
    int      over;        /* a renormalisation wanted a byte past the end */
} pmesh_rc;

/* Bytes the writer's flush leaves implied: zeros after the block. */
#define LUMO_PMESH_RC_TAIL 3u

/* Start on a block of n bytes: the code is its first 4 bytes (with the
 * implied zeros), big-endian. Nonzero when the block is empty. */
int lumo_pmesh_rc_init(pmesh_rc *rc, const uint8_t *p, uint32_t n);
/* One bit with the adaptive context *ctx (its probability of a 0 and
 * count, lumo_pmesh_ctx_update), which adapts. */
uint32_t lumo_pmesh_rc_bit(pmesh_rc *rc, uint32_t *ctx);
/* n bits of probability 1/2 (n <= 32), the first one the least significant. */
uint32_t lumo_pmesh_rc_direct(pmesh_rc *rc, unsigned n);
/* Every byte and the implied zeros used, the code where the writer's flush
 * leaves it (below 2^24). */
int lumo_pmesh_rc_done(const pmesh_rc *rc);

#endif
