/* pm_rc.c — range encoder of the split records (pm/pm_rc.h). LZMA's
 * encoder: a 64-bit low whose carries ripple into the delayed bytes; the
 * first output byte is always 0 and is not written, so the decoder starts
 * on the next four. The flush is short (docs/progressive-mesh.md §2.3):
 * one byte where LZMA writes four. */
#include <math.h>
#include "lumo_shared/pmesh_shared.h"
#include "pm/pm_rc.h"

void srv_pm_rc_init(srv_pm_rc *rc)
{
    *rc = (srv_pm_rc){{0}, 0, 0xffffffffu, 0, 1, 0, 0.0};
}

static void emit(srv_pm_rc *rc, uint8_t byte)
{
    if (rc->started)
        srv_buf_put(&rc->out, &byte, 1);
    rc->started = 1;
}

static void shift_low(srv_pm_rc *rc)
{
    if ((uint32_t)rc->low < 0xff000000u || (rc->low >> 32) != 0) {
        uint8_t carry = (uint8_t)(rc->low >> 32), temp = rc->cache;
        do {
            emit(rc, (uint8_t)(temp + carry));
            temp = 0xff;
        } while (--rc->cache_size != 0);
        rc->cache = (uint8_t)(rc->low >> 24);
    }
    rc->cache_size++;
    rc->low = (rc->low & 0x00ffffffu) << 8;
}

static void normalize(srv_pm_rc *rc)
{
    while (rc->range < LUMO_PMESH_RC_TOP) {
        rc->range <<= 8;
        shift_low(rc);
    }
}

void srv_pm_rc_bit(srv_pm_rc *rc, uint32_t *ctx, uint32_t bit)
{
    const double one = (double)(1u << LUMO_PMESH_RC_PROB_BITS);
    uint32_t prob = lumo_pmesh_ctx_prob(*ctx), bound = (rc->range >> LUMO_PMESH_RC_PROB_BITS) * prob;
    rc->cost -= log2(bit ? (one - prob) / one : prob / one);
    if (!bit)
        rc->range = bound;
    else
        rc->low += bound, rc->range -= bound;
    *ctx = lumo_pmesh_ctx_update(*ctx, bit);
    normalize(rc);
}

void srv_pm_rc_direct(srv_pm_rc *rc, uint32_t v, unsigned n)
{
    for (unsigned i = 0; i < n; i++) {
        rc->range >>= 1;
        if (v >> i & 1u)
            rc->low += rc->range;
        normalize(rc);
    }
    rc->cost += n;
}

/* The final code value is the smallest multiple of 2^24 in [low, low +
 * range) (there is one: range >= 2^24), so its three low bytes are zero and
 * are left to the decoder, which reads three zero bytes past the block: two
 * shifts write out the delayed bytes and the value's top byte. */
void srv_pm_rc_flush(srv_pm_rc *rc)
{
    rc->low = (rc->low + (LUMO_PMESH_RC_TOP - 1u)) & ~(uint64_t)(LUMO_PMESH_RC_TOP - 1u);
    shift_low(rc);
    shift_low(rc);
}
