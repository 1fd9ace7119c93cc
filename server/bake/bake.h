/*
 * bake.h — the IVG bake (seed 000 §3.1): for every grid vertex p and
 * hemisphere delta in {+x,-x,+y,-y,+z,-z}, a Monte Carlo estimate of
 * I_delta(p) = integral over Omega_delta of L(p<-w) w dw, with L the
 * indirect radiance only, per colour channel (the 3x3 matrix of §3.3).
 *
 * Sampling: spp paths per vertex over the full sphere (stratified jitter),
 * each path counting in the three hemispheres that contain its direction,
 * with the estimator 4*pi*L*w (pdf 1/(4 pi)); each hemisphere thus sees
 * about spp/2 paths. Uniform rather than cosine sampling because the
 * tangential components of w/cos would have infinite variance.
 *
 * Determinism: every vertex has its own random stream seeded from (seed,
 * vertex index) and is computed by one thread, so the result is identical
 * for any thread count, chunking, or MPI rank count (work.h, cluster.h).
 */
#ifndef SRV_BAKE_H
#define SRV_BAKE_H

#include <stddef.h>
#include <stdint.h>
#include "bake/trace.h"
#include "bake/work.h"
#include "lumo/status.h"

typedef struct srv_grid {
    int  dims[3];          /* vertices per axis, each in [2, 256] */
    vec3 bmin, bmax;       /* scene units; vertex (i,j,k) at bmin + (bmax-bmin)*(i,j,k)/(dims-1) */
} srv_grid;

typedef struct srv_bake_opts {
    int      spp;          /* paths per grid vertex (full sphere) */
    uint64_t seed;
    int      threads;      /* worker threads, >= 1 */
    int      progress;     /* draw a progress bar on stderr */
    float    solid_fraction; /* back-face share of first hits above which a vertex is solid */
} srv_bake_opts;

/* Offset in srv_bake_result.I of the 3-vector of vertex v (i + nx*(j + ny*k),
 * the lumo/ivg.h order), hemisphere h (lumo_ivg_axis order), channel ch. */
#define SRV_BAKE_I(v, h, ch) ((((size_t)(v) * 6 + (h)) * 3 + (ch)) * 3)

typedef struct srv_bake_result {
    srv_grid  grid;
    size_t    nverts;
    float    *I;       /* nverts x 6 hemispheres x 3 channels x 3 components (W/m^2) */
    float    *se;      /* nverts x 6 x 3: standard error of I.delta */
    uint8_t  *valid;   /* nverts: 0 when inside solid geometry */
    uint64_t  rays;
    double    seconds;
} srv_bake_result;

/* The grid over the scene bounds: dims given, box = bounds. */
srv_grid srv_grid_over(const srv_scene *s, const int dims[3]);
vec3 srv_grid_vertex(const srv_grid *g, int i, int j, int k);

/* Bake. LUMO_OK, or LUMO_ERR_NOMEM when the grid does not fit in memory
 * or threads cannot start (err set). */
lumo_status srv_bake(const srv_tracer *t, const srv_grid *g, const srv_bake_opts *o,
                     srv_bake_result *res, char *err, size_t errlen);
void srv_bake_result_free(srv_bake_result *res);

/* One grid vertex's output as the bake's srv_work item (work.h): the bytes
 * that travel between MPI ranks and into checkpoints. No implicit padding
 * (pad is zeroed), so the bytes are the same wherever they were computed. */
typedef struct srv_bake_record {
    float   I[6 * 9];     /* SRV_BAKE_I(0, h, ch) + c order */
    float   se[6 * 3];
    uint8_t valid;
    uint8_t pad[3];
} srv_bake_record;
_Static_assert(sizeof(srv_bake_record) == (6 * 9 + 6 * 3 + 1) * 4, "srv_bake_record has no padding");

/* The bake as work: srv_bake() is srv_bake_task_init, srv_work_run_local
 * over items * item_bytes of records, srv_bake_task_result; lumo-bake runs
 * the same work across MPI ranks instead (cluster.h). The task holds
 * copies of *g and *o and points at *t (which must outlive it). */
typedef struct srv_bake_task {
    srv_work             work;   /* key: the scene, grid, spp, seed, solid fraction */
    struct srv_bake_job *job;
} srv_bake_task;

/* LUMO_OK, or LUMO_ERR_NOMEM (the grid would not fit in memory; err set). */
lumo_status srv_bake_task_init(srv_bake_task *k, const srv_tracer *t, const srv_grid *g,
                               const srv_bake_opts *o, char *err, size_t errlen);
/* The result from the records of every vertex (res allocated here; rays
 * and seconds left 0 for the caller). LUMO_OK or LUMO_ERR_NOMEM. */
lumo_status srv_bake_task_result(const srv_bake_task *k, const uint8_t *records, srv_bake_result *res,
                                 char *err, size_t errlen);
void srv_bake_task_free(srv_bake_task *k);

#endif
