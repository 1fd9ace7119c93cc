/* parallel.h — run fn(ctx, item, worker) for item in [0, n) on `threads`
 * pthreads pulling items from a shared counter; the calling thread draws
 * the progress bar. Results must be written per item so that the output
 * does not depend on which worker ran what. */
#ifndef SRV_PARALLEL_H
#define SRV_PARALLEL_H

#include <stddef.h>
#include "lumo/status.h"

typedef void (*srv_item_fn)(void *ctx, size_t item, int worker);

/* LUMO_OK, or LUMO_ERR_NOMEM when threads could not be started (out of
 * resources). */
lumo_status srv_parallel_for(size_t n, int threads, srv_item_fn fn, void *ctx, const char *label,
                             int progress);

#endif
