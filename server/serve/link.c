/*
 * link.c — token bucket, latency and loss of an emulated link (serve/link.h).
 */
#include "serve/link.h"

uint64_t srv_link_rand(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double burst(const srv_link_config *cfg)
{
    double b = cfg->rate_bytes * SRV_LINK_BURST_MS / 1000.0;
    return b < 1500.0 ? 1500.0 : b;
}

void srv_link_init(srv_link *l, const srv_link_config *cfg, uint64_t conn_id, int64_t now_us)
{
    l->tokens = cfg->rate_bytes > 0 ? burst(cfg) : 0;
    l->refill_us = now_us;
    l->rng = cfg->seed ^ (conn_id * 0xd1b54a32d192ed03ull);
    srv_link_rand(&l->rng);
}

size_t srv_link_budget(srv_link *l, const srv_link_config *cfg, int64_t now_us, size_t want,
                       int64_t *wake_us)
{
    double b, need;

    if (cfg->rate_bytes <= 0)
        return want;
    b = burst(cfg);
    if (now_us > l->refill_us) {
        l->tokens += (double)(now_us - l->refill_us) * cfg->rate_bytes / 1e6;
        if (l->tokens > b)
            l->tokens = b;
        l->refill_us = now_us;
    }
    if (l->tokens >= 1.0)
        return l->tokens >= (double)want ? want : (size_t)l->tokens;
    /* Wait until a useful amount has refilled: the whole want, at most a
     * burst's worth and at most 512 bytes (small frames go out promptly on
     * slow links). */
    need = (double)want;
    if (need > b)
        need = b;
    if (need > 512.0)
        need = 512.0;
    *wake_us = now_us + 1 + (int64_t)((need - l->tokens) * 1e6 / cfg->rate_bytes);
    return 0;
}

void srv_link_spend(srv_link *l, const srv_link_config *cfg, size_t n)
{
    if (cfg->rate_bytes > 0)
        l->tokens -= (double)n;
}

int srv_link_defect(srv_link *l, const srv_link_config *cfg, uint32_t frame_len, uint32_t *at,
                    uint8_t *flip_xor)
{
    uint64_t r;

    if (cfg->loss <= 0 || frame_len == 0)
        return SRV_DEFECT_NONE;
    r = srv_link_rand(&l->rng);
    if ((double)(r >> 11) * (1.0 / 9007199254740992.0) >= cfg->loss)
        return SRV_DEFECT_NONE;
    r = srv_link_rand(&l->rng);
    *at = (uint32_t)((r >> 8) % frame_len);
    *flip_xor = (uint8_t)(1u << (r & 7));   /* one bit: a line error */
    return (r >> 3) & 1 ? SRV_DEFECT_DROP : SRV_DEFECT_FLIP;
}
