/* cluster_mpi.c — cluster.h over MPI (Open MPI from Debian): rank 0
 * coordinates and computes, the other ranks compute the chunks it hands
 * them. Linked into lumo-bake when the build finds Open MPI.
 *
 * Messages (all MPI_BYTE, little-endian; every rank runs the same build):
 *   HELLO  rank -> 0   key, items, item_bytes, chunk_items (4 x u64)
 *   ASSIGN 0 -> rank   u64 chunk index, or NO_CHUNK: nothing left, stop
 *   RESULT rank -> 0   u64 chunk, u64 rays, the chunk's bytes
 * A rank holds CREDIT chunks at a time (one computing, one queued), so it
 * never idles for a round trip; a RESULT returns one credit. Rank 0 checks
 * every message (size, chunk assigned to that rank, not yet done). */
#include <mpi.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "bake/checkpoint.h"
#include "bake/cluster.h"
#include "common/progress.h"
#include "lumo/wire.h"

enum { TAG_HELLO = 1, TAG_ASSIGN, TAG_RESULT };
#define NO_CHUNK UINT64_MAX
#define CREDIT 2
#define HELLO_BYTES 32
#define RESULT_HEAD 16

/* Open MPI's blocking calls spin a core; on a node whose cores all trace
 * that would slow the bake, so waits poll with a short sleep instead. */
static void nap(void)
{
    struct timespec ts = {0, 200 * 1000};
    nanosleep(&ts, NULL);
}

static int wait_polled(MPI_Request *r)
{
    for (int done = 0;;) {
        int rc = MPI_Test(r, &done, MPI_STATUS_IGNORE);
        if (rc != MPI_SUCCESS || done)
            return rc;
        nap();
    }
}

static int send_polled(const void *buf, size_t n, int dest, int tag)
{
    MPI_Request r;
    int rc = MPI_Isend(buf, (int)n, MPI_BYTE, dest, tag, MPI_COMM_WORLD, &r);
    return rc != MPI_SUCCESS ? rc : wait_polled(&r);
}

static int recv_polled(void *buf, size_t n, int src, int tag)
{
    MPI_Request r;
    int rc = MPI_Irecv(buf, (int)n, MPI_BYTE, src, tag, MPI_COMM_WORLD, &r);
    return rc != MPI_SUCCESS ? rc : wait_polled(&r);
}

/* mpirun stops the whole job with SIGTERM when a rank dies: rank 0 says
 * so in lumo-bake's words (the output is written only after every chunk
 * arrived, so nothing partial is left). */
static void on_term(int sig)
{
    static const char msg[] = "lumo-bake: error: the MPI job was stopped (a rank died or the job was "
                              "cancelled); no output written\n";
    ssize_t rc = write(2, msg, sizeof msg - 1);
    (void)rc;
    _exit(128 + sig);
}

lumo_status srv_cluster_init(srv_cluster *c, int *argc, char ***argv, char *err, size_t errlen)
{
    int provided = 0;
    *c = (srv_cluster){.rank = 0, .size = 1, .mpi = 0};
    if (!srv_cluster_launched())
        return LUMO_OK;   /* plain `lumo-bake`: no MPI at all, as before */
    if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS ||
        provided < MPI_THREAD_FUNNELED) {
        snprintf(err, errlen, "MPI failed to start (or without thread support)");
        return LUMO_ERR_UNSUPPORTED;
    }
    c->mpi = 1;
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &c->rank);
    MPI_Comm_size(MPI_COMM_WORLD, &c->size);
    if (c->size > SRV_WORK_MAX_RANKS) {
        snprintf(err, errlen, "%d ranks: at most %d", c->size, SRV_WORK_MAX_RANKS);
        return LUMO_ERR_LIMIT;
    }
    if (c->rank == 0 && c->size > 1)
        signal(SIGTERM, on_term);
    return LUMO_OK;
}

int srv_cluster_end(srv_cluster *c, int status)
{
    if (!c->mpi)
        return status;
    if (status && c->size > 1)
        MPI_Abort(MPI_COMM_WORLD, status);
    MPI_Request r;
    if (MPI_Ibarrier(MPI_COMM_WORLD, &r) == MPI_SUCCESS)
        wait_polled(&r);
    MPI_Finalize();
    return status;
}

/* ---- rank 0 --------------------------------------------------------------- */

typedef struct {
    const srv_work  *w;
    uint8_t         *out, *done;
    int             *owner;          /* rank holding each chunk, -1 none */
    size_t           nchunks, next, finished;
    srv_ckpt         ck;
    int              has_ck;
    srv_work_report *rep;
    pthread_mutex_t  lock;
    lumo_status      local_st;       /* the local thread's failure */
    char             local_err[256];
} coord;

static uint64_t take_chunk(coord *k, int rank)
{
    uint64_t c = NO_CHUNK;
    pthread_mutex_lock(&k->lock);
    while (k->next < k->nchunks && (k->done[k->next] || k->owner[k->next] >= 0))
        k->next++;
    if (k->next < k->nchunks) {
        c = k->next++;
        k->owner[c] = rank;
    }
    pthread_mutex_unlock(&k->lock);
    return c;
}

/* Chunk c is in out: count it, append it to the checkpoint. */
static lumo_status chunk_done(coord *k, size_t c, int rank, char *err, size_t errlen)
{
    size_t first, count;
    lumo_status st = LUMO_OK;
    srv_work_chunk(k->w, c, &first, &count);
    pthread_mutex_lock(&k->lock);
    k->done[c] = 1;
    k->finished++;
    k->rep->rank_chunks[rank]++;
    if (k->has_ck)
        st = srv_ckpt_append(&k->ck, k->w, c, k->out + first * k->w->item_bytes, err, errlen);
    pthread_mutex_unlock(&k->lock);
    return st;
}

static void *local_main(void *arg)
{
    coord *k = arg;
    for (uint64_t c; (c = take_chunk(k, 0)) != NO_CHUNK;) {
        size_t first, count;
        uint64_t rays = 0;
        srv_work_chunk(k->w, (size_t)c, &first, &count);
        lumo_status st = k->w->run(k->w->ctx, first, count, k->out + first * k->w->item_bytes, &rays);
        if (st)
            snprintf(k->local_err, sizeof k->local_err, "rank 0: cannot start worker threads");
        else
            st = chunk_done(k, (size_t)c, 0, k->local_err, sizeof k->local_err);
        pthread_mutex_lock(&k->lock);
        k->rep->rays += rays;
        k->local_st = st;
        pthread_mutex_unlock(&k->lock);
        if (st)
            break;
    }
    return NULL;
}

typedef struct {
    int outstanding;   /* chunks assigned, results not yet in */
    int stopped;       /* NO_CHUNK sent */
} rank_state;

static lumo_status mpi_fail(int rc, const char *what, char *err, size_t errlen)
{
    char text[MPI_MAX_ERROR_STRING];
    int len = 0;
    MPI_Error_string(rc, text, &len);
    snprintf(err, errlen, "MPI %s failed: %.*s", what, len, text);
    return LUMO_ERR_IO;
}

/* Give rank r a chunk, or tell it to stop once it holds none. */
static lumo_status assign(coord *k, rank_state *rs, int r, int *left, char *err, size_t errlen)
{
    uint8_t msg[8];
    uint64_t c = take_chunk(k, r);
    if (c == NO_CHUNK && (rs[r].outstanding > 0 || rs[r].stopped))
        return LUMO_OK;
    lumo_wire_put_le64(msg, c);
    int rc = MPI_Send(msg, 8, MPI_BYTE, r, TAG_ASSIGN, MPI_COMM_WORLD);
    if (rc != MPI_SUCCESS)
        return mpi_fail(rc, "send", err, errlen);
    k->rep->rank_bytes[r] += 8;
    if (c == NO_CHUNK) {
        rs[r].stopped = 1;
        --*left;
    } else {
        rs[r].outstanding++;
    }
    return LUMO_OK;
}

static lumo_status on_hello(coord *k, rank_state *rs, int r, int *left, char *err, size_t errlen)
{
    uint8_t got[HELLO_BYTES], want[HELLO_BYTES];
    const srv_work *w = k->w;
    int rc = MPI_Recv(got, HELLO_BYTES, MPI_BYTE, r, TAG_HELLO, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (rc != MPI_SUCCESS)
        return mpi_fail(rc, "receive", err, errlen);
    lumo_wire_put_le64(want, w->key);
    lumo_wire_put_le64(want + 8, w->items);
    lumo_wire_put_le64(want + 16, w->item_bytes);
    lumo_wire_put_le64(want + 24, w->chunk_items);
    k->rep->rank_bytes[r] += HELLO_BYTES;
    if (memcmp(got, want, HELLO_BYTES)) {
        snprintf(err, errlen, "rank %d has another %s work than rank 0 (a different scene file, build or "
                 "options on its node?)", r, w->name);
        return LUMO_ERR_STATE;
    }
    lumo_status st = LUMO_OK;
    for (int i = 0; i < CREDIT && !st; i++)
        st = assign(k, rs, r, left, err, errlen);
    return st;
}

static lumo_status on_result(coord *k, rank_state *rs, int r, size_t n, uint8_t *buf, int *left, char *err,
                             size_t errlen)
{
    size_t first, count;
    int rc = MPI_Recv(buf, (int)n, MPI_BYTE, r, TAG_RESULT, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (rc != MPI_SUCCESS)
        return mpi_fail(rc, "receive", err, errlen);
    k->rep->rank_bytes[r] += n;
    uint64_t c = n >= RESULT_HEAD ? lumo_wire_le64(buf) : NO_CHUNK;
    if (c >= k->nchunks || k->owner[c] != r || k->done[c]) {
        snprintf(err, errlen, "rank %d sent a result for chunk %llu, which it was not computing", r,
                 (unsigned long long)c);
        return LUMO_ERR_STATE;
    }
    srv_work_chunk(k->w, (size_t)c, &first, &count);
    if (n != RESULT_HEAD + count * k->w->item_bytes) {
        snprintf(err, errlen, "rank %d sent %zu bytes for chunk %llu", r, n, (unsigned long long)c);
        return LUMO_ERR_CORRUPT;
    }
    memcpy(k->out + first * k->w->item_bytes, buf + RESULT_HEAD, n - RESULT_HEAD);
    pthread_mutex_lock(&k->lock);
    k->rep->rays += lumo_wire_le64(buf + 8);
    pthread_mutex_unlock(&k->lock);
    rs[r].outstanding--;
    lumo_status st = chunk_done(k, (size_t)c, r, err, errlen);
    return st ? st : assign(k, rs, r, left, err, errlen);
}

/* One message, if one is waiting: 1 handled, 0 none, -1 failed. */
static int serve_one(coord *k, rank_state *rs, uint8_t *buf, size_t cap, int *left, char *err, size_t errlen)
{
    MPI_Status s;
    int flag = 0, n = 0, rc = MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &s);
    if (rc != MPI_SUCCESS)
        return mpi_fail(rc, "probe", err, errlen), -1;
    if (!flag)
        return 0;
    MPI_Get_count(&s, MPI_BYTE, &n);
    lumo_status st;
    if (s.MPI_TAG == TAG_HELLO && n == HELLO_BYTES)
        st = on_hello(k, rs, s.MPI_SOURCE, left, err, errlen);
    else if (s.MPI_TAG == TAG_RESULT && n >= RESULT_HEAD && (size_t)n <= cap)
        st = on_result(k, rs, s.MPI_SOURCE, (size_t)n, buf, left, err, errlen);
    else {
        snprintf(err, errlen, "rank %d sent an unexpected message (tag %d, %d bytes)", s.MPI_SOURCE, s.MPI_TAG, n);
        st = LUMO_ERR_CORRUPT;
    }
    return st ? -1 : 1;
}

static lumo_status coordinate(coord *k, int size, char *err, size_t errlen)
{
    size_t cap = RESULT_HEAD + k->w->chunk_items * k->w->item_bytes;
    rank_state *rs = calloc((size_t)size, sizeof *rs);
    uint8_t *buf = malloc(cap);
    lumo_status st = rs && buf ? LUMO_OK : LUMO_ERR_NOMEM;
    srv_progress bar;
    int left = size - 1;
    if (st)
        snprintf(err, errlen, "out of memory");
    srv_progress_begin(&bar, k->w->name, k->nchunks, k->w->progress);
    while (!st && left > 0) {
        int got = serve_one(k, rs, buf, cap, &left, err, errlen);
        if (got < 0)
            st = LUMO_ERR_STATE;
        pthread_mutex_lock(&k->lock);
        if (!st && k->local_st) {
            st = k->local_st;
            snprintf(err, errlen, "%s", k->local_err);
        }
        size_t finished = k->finished + k->rep->resumed;
        pthread_mutex_unlock(&k->lock);
        if (!got) {
            srv_progress_update(&bar, finished);
            nap();
        }
    }
    srv_progress_end(&bar);
    free(rs);
    free(buf);
    return st;
}

static lumo_status start_root(coord *k, const char *ckpt_dir, pthread_t *tid, char *err, size_t errlen)
{
    k->done = calloc(k->nchunks, 1);
    k->owner = malloc(k->nchunks * sizeof *k->owner);
    if (!k->done || !k->owner) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    for (size_t c = 0; c < k->nchunks; c++)
        k->owner[c] = -1;
    pthread_mutex_init(&k->lock, NULL);
    if (ckpt_dir) {
        lumo_status st = srv_ckpt_open(&k->ck, ckpt_dir, k->w, k->out, k->done, &k->rep->resumed, err, errlen);
        if (st)
            return st;
        k->has_ck = 1;
    }
    if (pthread_create(tid, NULL, local_main, k)) {
        snprintf(err, errlen, "rank 0: cannot start its compute thread");
        return LUMO_ERR_NOMEM;
    }
    return LUMO_OK;
}

/* On failure the coordinator state is left allocated: the local thread may
 * still be tracing into it until the caller's srv_cluster_end aborts. */
static lumo_status run_root(const srv_cluster *cl, const srv_work *w, const char *ckpt_dir, uint8_t *out,
                            srv_work_report *rep, char *err, size_t errlen)
{
    coord *k = calloc(1, sizeof *k);
    pthread_t tid;
    if (!k) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    *k = (coord){.w = w, .out = out, .rep = rep, .nchunks = srv_work_chunks(w)};
    lumo_status st = start_root(k, ckpt_dir, &tid, err, errlen);
    if (!st)
        st = coordinate(k, cl->size, err, errlen);
    if (st)
        return st;
    pthread_join(tid, NULL);
    if (k->local_st) {
        st = k->local_st;
        snprintf(err, errlen, "%s", k->local_err);
    } else if (k->finished + rep->resumed != k->nchunks) {
        snprintf(err, errlen, "only %zu of %zu chunks arrived", k->finished + rep->resumed, k->nchunks);
        st = LUMO_ERR_STATE;
    }
    if (k->has_ck)
        srv_ckpt_close(&k->ck);
    pthread_mutex_destroy(&k->lock);
    free(k->done);
    free(k->owner);
    free(k);
    return st;
}

/* ---- ranks 1.. -------------------------------------------------------------- */

static lumo_status run_worker(const srv_work *w, srv_work_report *rep, char *err, size_t errlen)
{
    uint8_t hello[HELLO_BYTES], msg[8];
    uint8_t *buf = malloc(RESULT_HEAD + w->chunk_items * w->item_bytes);
    if (!buf) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    lumo_wire_put_le64(hello, w->key);
    lumo_wire_put_le64(hello + 8, w->items);
    lumo_wire_put_le64(hello + 16, w->item_bytes);
    lumo_wire_put_le64(hello + 24, w->chunk_items);
    int rc = send_polled(hello, HELLO_BYTES, 0, TAG_HELLO);
    lumo_status st = rc != MPI_SUCCESS ? mpi_fail(rc, "send", err, errlen) : LUMO_OK;
    while (!st) {
        size_t first, count;
        uint64_t rays = 0;
        if ((rc = recv_polled(msg, 8, 0, TAG_ASSIGN)) != MPI_SUCCESS) {
            st = mpi_fail(rc, "receive", err, errlen);
            break;
        }
        uint64_t c = lumo_wire_le64(msg);
        if (c == NO_CHUNK)
            break;
        if (c >= srv_work_chunks(w)) {
            snprintf(err, errlen, "rank 0 assigned chunk %llu of %zu", (unsigned long long)c, srv_work_chunks(w));
            st = LUMO_ERR_RANGE;
            break;
        }
        srv_work_chunk(w, (size_t)c, &first, &count);
        if ((st = w->run(w->ctx, first, count, buf + RESULT_HEAD, &rays))) {
            snprintf(err, errlen, "cannot start worker threads");
            break;
        }
        lumo_wire_put_le64(buf, c);
        lumo_wire_put_le64(buf + 8, rays);
        rep->rays += rays;
        if ((rc = send_polled(buf, RESULT_HEAD + count * w->item_bytes, 0, TAG_RESULT)) != MPI_SUCCESS)
            st = mpi_fail(rc, "send", err, errlen);
    }
    free(buf);
    return st;
}

lumo_status srv_cluster_run(const srv_cluster *c, const srv_work *w, const char *ckpt_dir, uint8_t *out,
                            srv_work_report *rep, char *err, size_t errlen)
{
    if (c->size == 1)
        return srv_work_run_local(w, ckpt_dir, out, rep, err, errlen);
    double t0 = srv_now();
    memset(rep, 0, sizeof *rep);
    rep->ranks = c->size;
    rep->chunks = srv_work_chunks(w);
    lumo_status st = c->rank == 0 ? run_root(c, w, ckpt_dir, out, rep, err, errlen)
                                  : run_worker(w, rep, err, errlen);
    rep->seconds = srv_now() - t0;
    return st;
}
