/*
 * serve/link.h — link emulation per connection (lumo-server --rate,
 * --latency, --loss; docs/server.md "Link emulation").
 *
 *  - rate: a token bucket on the bytes sent, refilled at the rate and
 *    holding at most SRV_LINK_BURST_MS worth of bytes (at least one
 *    Ethernet frame), so a link of R kbit/s never carries more than R kbit in
 *    any second after its first burst;
 *  - latency: a request read from the client is acted on no earlier than
 *    the latency after it was read, and its answer's frames leave no earlier
 *    than the latency after that (the two directions of a link), counted
 *    from the request's arrival, not from when its answer was started: an
 *    answer queued behind others is not held again;
 *  - loss (the serial listener only): each frame, with probability P, gets
 *    one byte flipped or one byte dropped, from a seeded random stream per
 *    connection (splitmix64 of seed and connection number): the same run
 *    gives the same damage.
 */
#ifndef SRV_SERVE_LINK_H
#define SRV_SERVE_LINK_H

#include <stddef.h>
#include <stdint.h>

#define SRV_LINK_BURST_MS 20

typedef struct srv_link_config {
    double   rate_bytes;   /* bytes per second; 0: unlimited */
    int64_t  latency_us;
    double   loss;         /* per frame, 0..1 (applied where the caller asks) */
    uint64_t seed;
} srv_link_config;

typedef struct srv_link {
    double   tokens;
    int64_t  refill_us;
    uint64_t rng;
} srv_link;

enum { SRV_DEFECT_NONE = 0, SRV_DEFECT_FLIP, SRV_DEFECT_DROP };

void srv_link_init(srv_link *l, const srv_link_config *cfg, uint64_t conn_id, int64_t now_us);
/* Bytes the link lets through now, at most want (want when unlimited).
 * When that is 0, *wake_us is when enough will have refilled. */
size_t srv_link_budget(srv_link *l, const srv_link_config *cfg, int64_t now_us, size_t want,
                       int64_t *wake_us);
void srv_link_spend(srv_link *l, const srv_link_config *cfg, size_t n);
/* The defect of the next frame (frame_len >= 1): SRV_DEFECT_NONE, or FLIP
 * with the byte offset and the replacement byte, or DROP with the offset. */
int srv_link_defect(srv_link *l, const srv_link_config *cfg, uint32_t frame_len, uint32_t *at,
                    uint8_t *flip_xor);
/* splitmix64 step (also the tests' generator). */
uint64_t srv_link_rand(uint64_t *state);

#endif
