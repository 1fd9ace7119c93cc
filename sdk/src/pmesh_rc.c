/* pmesh_rc.c — range decoder of the split records (pmesh_rc.h). The block
 * is followed by three implied zero bytes (the writer's short flush); a
 * read past those yields zeros and sets `over`, which the batch decoder
 * turns into TRUNCATED; nothing here can fail otherwise. */
#include "pmesh_rc.h"
#include "lumo_shared/pmesh_shared.h"

/* The next byte of the block, of its three implied zeros, or past them. */
static uint32_t next_byte(pmesh_rc *rc)
{
    uint32_t at = rc->pos++;
    if (at < rc->n)
        return rc->p[at];
    if (at - rc->n >= LUMO_PMESH_RC_TAIL)
        rc->over = 1;
    return 0;
}

int lumo_pmesh_rc_init(pmesh_rc *rc, const uint8_t *p, uint32_t n)
{
    rc->p = p, rc->n = n, rc->pos = 0, rc->over = 0;
    rc->range = 0xffffffffu, rc->code = 0;
    if (n < 1)
        return rc->over = 1, -1;
    for (int i = 0; i < 4; i++)
        rc->code = rc->code << 8 | next_byte(rc);
    return 0;
}

static void normalize(pmesh_rc *rc)
{
    while (rc->range < LUMO_PMESH_RC_TOP) {
        rc->range <<= 8;
        rc->code = rc->code << 8 | next_byte(rc);
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

/* The writer's flush leaves the code below 2^24 (its final value is the
 * smallest multiple of 2^24 in the interval) with exactly the three implied
 * zeros read: any other end is not a flush, or has bytes left over. */
int lumo_pmesh_rc_done(const pmesh_rc *rc)
{
    return !rc->over && rc->pos == rc->n + LUMO_PMESH_RC_TAIL && rc->code < LUMO_PMESH_RC_TOP;
}
