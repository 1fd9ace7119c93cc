/* pm/pm_rc.h — the range encoder of progressive-mesh split records
 * (docs/progressive-mesh.md §2.3 "Range code"): LZMA's binary range coder
 * with the probabilities and renormalisation of lumo_shared/pmesh_shared.h.
 * The client's inverse is sdk/src/pmesh_rc.c. Memory: the output grows in
 * a malloc'ed srv_buf (package/package_write.h), freed by the caller. */
#ifndef SRV_PM_RC_H
#define SRV_PM_RC_H

#include <stdint.h>
#include "package/package_write.h"

typedef struct srv_pm_rc {
    srv_buf  out;
    uint64_t low;
    uint32_t range;
    uint8_t  cache;
    uint64_t cache_size;
    int      started;   /* the first byte (always 0) was dropped */
    double   cost;      /* bits spent so far: -log2 of each coded bit's probability */
} srv_pm_rc;

void srv_pm_rc_init(srv_pm_rc *rc);
/* One bit with the adaptive context *ctx (probability of a 0 and count,
 * lumo_pmesh_ctx_update), which adapts as the decoder's does. */
void srv_pm_rc_bit(srv_pm_rc *rc, uint32_t *ctx, uint32_t bit);
/* The n low bits of v at probability 1/2, least significant first. */
void srv_pm_rc_direct(srv_pm_rc *rc, uint32_t v, unsigned n);
/* Write out the rest of the code, shortest (its last three bytes, zero, are
 * implied): out then holds the whole block. */
void srv_pm_rc_flush(srv_pm_rc *rc);

#endif
