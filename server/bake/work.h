/*
 * work.h — a sample-parallel stage (the IVG bake, the reference render) as
 * work that can be split: `items` independent items (grid vertices, image
 * rows), each giving `item_bytes` of output, computed in chunks of
 * consecutive items. Because every item draws from its own random stream
 * (bake.h, reference.h), the output bytes do not depend on who computed a
 * chunk, in which order, nor how many threads or MPI ranks took part
 * (cluster.h); so chunks may come from a checkpoint of an earlier run.
 *
 * The chunk table depends on the item count only (never on ranks or
 * threads), so a checkpoint can be resumed with any rank count.
 */
#ifndef SRV_WORK_H
#define SRV_WORK_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

struct srv_scene;

/* Compute items [first, first+count) into out (count * item_bytes bytes,
 * every byte written, padding included) with the stage's threads; add the
 * rays cast to *rays. LUMO_OK, or LUMO_ERR_NOMEM (threads cannot start). */
typedef lumo_status (*srv_work_fn)(void *ctx, size_t first, size_t count, uint8_t *out, uint64_t *rays);

typedef struct srv_work {
    const char *name;        /* "ivg", "reference": progress label, checkpoint file name */
    size_t      items;       /* >= 1 */
    size_t      item_bytes;  /* >= 1 */
    size_t      chunk_items; /* items per chunk (the last chunk may be shorter) */
    uint64_t    key;         /* digest of everything the output depends on (srv_key_*) */
    srv_work_fn run;
    void       *ctx;
    int         progress;    /* draw a progress bar on stderr */
} srv_work;

/* What a run did, for the summary and the scaling benchmark. */
#define SRV_WORK_MAX_RANKS 1024
typedef struct srv_work_report {
    size_t   chunks, resumed;     /* chunks in the table; taken from a checkpoint */
    uint64_t rays;                /* rays cast in this run, all ranks */
    double   seconds;             /* wall time of the run */
    int      ranks;
    size_t   rank_chunks[SRV_WORK_MAX_RANKS];  /* chunks computed by each rank */
    uint64_t rank_bytes[SRV_WORK_MAX_RANKS];   /* bytes each rank sent and received (rank 0: 0) */
} srv_work_report;

/* Items per chunk for n items: about 1024 chunks (a 64^3 grid gives 16
 * chunks to each of 64 ranks, so the last chunk out is a small tail: the
 * model in docs/benchmarks.md), at least 16 items (so a chunk's thread
 * barrier and message cost little), at most 4096. */
size_t srv_work_chunk_items(size_t items);
size_t srv_work_chunks(const srv_work *w);
/* Chunk c's first item and item count. */
void srv_work_chunk(const srv_work *w, size_t c, size_t *first, size_t *count);

/* Run every chunk in this process into out (items * item_bytes bytes).
 * ckpt_dir: NULL, or a directory whose checkpoint (checkpoint.h) is
 * resumed and extended chunk by chunk. LUMO_OK, or an error with err set. */
lumo_status srv_work_run_local(const srv_work *w, const char *ckpt_dir, uint8_t *out,
                               srv_work_report *rep, char *err, size_t errlen);

/* The key: a 64-bit FNV-1a digest. Start with SRV_KEY_INIT, feed every
 * input the output depends on. Floats are fed by their bits. */
#define SRV_KEY_INIT 0xcbf29ce484222325ull
uint64_t srv_key_bytes(uint64_t h, const void *p, size_t n);
uint64_t srv_key_u64(uint64_t h, uint64_t v);
uint64_t srv_key_float(uint64_t h, float f);
/* The scene's geometry, albedo, emitters and lights, field by field (no
 * struct padding). */
uint64_t srv_key_scene(uint64_t h, const struct srv_scene *s);

#endif
