/* parallel.c — a work-stealing-free pool: one atomic counter, items handed
 * out one at a time (items are grid vertices or image rows: coarse enough). */
#include <pthread.h>
#include <stdatomic.h>
#include <time.h>
#include "common/parallel.h"
#include "common/progress.h"

#define MAX_THREADS 256

typedef struct {
    size_t        n;
    atomic_size_t next, done;
    srv_item_fn   fn;
    void         *ctx;
} pool;

typedef struct { pool *p; int worker; } worker_arg;

static void *worker_main(void *arg)
{
    worker_arg *w = arg;
    pool *p = w->p;
    for (;;) {
        size_t i = atomic_fetch_add(&p->next, 1);
        if (i >= p->n)
            break;
        p->fn(p->ctx, i, w->worker);
        atomic_fetch_add(&p->done, 1);
    }
    return NULL;
}

lumo_status srv_parallel_for(size_t n, int threads, srv_item_fn fn, void *ctx, const char *label,
                             int progress)
{
    pthread_t tid[MAX_THREADS];
    worker_arg args[MAX_THREADS];
    pool p = {.n = n, .fn = fn, .ctx = ctx};
    srv_progress bar;
    int started = 0, rc = 0;
    atomic_init(&p.next, 0);
    atomic_init(&p.done, 0);
    threads = threads < 1 ? 1 : threads > MAX_THREADS ? MAX_THREADS : threads;
    srv_progress_begin(&bar, label, n, progress);
    for (; started < threads; started++) {
        args[started] = (worker_arg){&p, started};
        if (pthread_create(&tid[started], NULL, worker_main, &args[started])) {
            rc = -1;
            break;
        }
    }
    while (started > 0 && atomic_load(&p.done) < n && bar.enabled) {
        struct timespec ts = {0, 200 * 1000 * 1000};
        srv_progress_update(&bar, atomic_load(&p.done));
        nanosleep(&ts, NULL);
    }
    for (int i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
    srv_progress_end(&bar);
    /* If no thread started, nothing ran: report; partial starts still finish. */
    if (started == 0 || (rc && atomic_load(&p.done) < n))
        return LUMO_ERR_NOMEM;
    return LUMO_OK;
}
