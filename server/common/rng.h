/* rng.h — a small deterministic generator (PCG32 seeded by SplitMix64), so a
 * bake's output depends only on --seed and the work item, never on threads. */
#ifndef SRV_RNG_H
#define SRV_RNG_H

#include <stdint.h>

typedef struct { uint64_t state, inc; } srv_rng;

static inline uint64_t srv_splitmix64(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/* The SplitMix64 generator (Steele, Lea, Flood 2014; Vigna's reference
 * splitmix64.c): advance the state by the golden gamma, return its mix.
 * The IVG streaming order draws with it (docs/package-format.md "IVGS"). */
static inline uint64_t srv_splitmix64_next(uint64_t *state)
{
    uint64_t z = srv_splitmix64(*state);
    *state += 0x9E3779B97F4A7C15ull;
    return z;
}

static inline uint32_t srv_rng_u32(srv_rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    uint32_t x = (uint32_t)(((old >> 18) ^ old) >> 27), rot = (uint32_t)(old >> 59);
    return (x >> rot) | (x << ((32 - rot) & 31));
}

/* One independent stream per (seed, item). */
static inline void srv_rng_seed(srv_rng *r, uint64_t seed, uint64_t item)
{
    r->state = srv_splitmix64(seed ^ srv_splitmix64(item));
    r->inc = (srv_splitmix64(item + 0x5851F42D4C957F2Dull) << 1) | 1u;
    srv_rng_u32(r);
}

/* Uniform in [0, 1). */
static inline float srv_rng_float(srv_rng *r)
{
    return (float)(srv_rng_u32(r) >> 8) * (1.0f / 16777216.0f);
}

#endif
