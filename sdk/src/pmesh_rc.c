/* pmesh_rc.c — range decoder of the split records (pmesh_rc.h). A read
 * past the block's end yields zero bytes and sets `over`, which the batch
 * decoder turns into TRUNCATED; nothing here can fail otherwise. */
#include "pmesh_rc.h"
#include "lumo_shared/pmesh_shared.h"

int lumo_pmesh_rc_init(pmesh_rc *rc, const uint8_t *p, uint32_t n)
{
    rc->p = p, rc->n = n, rc->pos = 4, rc->over = 0;
    rc->range = 0xffffffffu;
    if (n < 4)
        return rc->over = 1, -1;
    rc->code = (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
    return 0;
}

static void normalize(pmesh_rc *rc)
{
    while (rc->range < LUMO_PMESH_RC_TOP) {
        uint32_t byte = 0;
        if (rc->pos < rc->n)
            byte = rc->p[rc->pos];
        else
            rc->over = 1;
        rc->pos++;
        rc->range <<= 8;
        rc->code = rc->code << 8 | byte;
    }
}

uint32_t lumo_pmesh_rc_bit(pmesh_rc *rc, uint32_t *ctx)
{
    uint32_t bound = (rc->range >> LUMO_PMESH_RC_PROB_BITS) * lumo_pmesh_ctx_prob(*ctx), bit;
    if (rc->code < bound) {
        rc->range = bound;
        bit = 0;
    } else {
        rc->code -= bound, rc->range -= bound;
        bit = 1;
    }
    *ctx = lumo_pmesh_ctx_update(*ctx, bit);
    normalize(rc);
    return bit;
}

uint32_t lumo_pmesh_rc_direct(pmesh_rc *rc, unsigned n)
{
    uint32_t v = 0;
    for (unsigned i = 0; i < n; i++) {
        rc->range >>= 1;
        if (rc->code >= rc->range)
            rc->code -= rc->range, v |= (uint32_t)1 << i;
        normalize(rc);
    }
    return v;
}

int lumo_pmesh_rc_done(const pmesh_rc *rc)
{
    return !rc->over && rc->pos == rc->n && rc->code == 0;
}
