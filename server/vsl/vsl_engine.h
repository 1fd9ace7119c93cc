/*
 * vsl_engine.h — the live lighting engine (seed 004 §0.3, §0.7.2): VSLs
 * placed once, photons streamed continuously into the pool, objects and
 * lights moved by a motion script or live commands, and the IVG
 * re-evaluated from the VSLs where they changed (vsl_ivg.h). It runs in a
 * thread of its own beside serving (srv_vsl_engine_start), or step by step
 * for tests and offline runs (srv_vsl_engine_step).
 *
 * Latency (§0.5: "the entire photon pool is rapidly updated, producing a
 * slight latency when objects move"; §0.9.1 — named there, not measured):
 * a change is settled when the pool's oldest photon was emitted after it
 * (a full turnover: nothing of the old lighting is left) and the IVG has
 * been updated from that pool. The engine records, for every change, the
 * photon paths and the wall time from the change to its settling.
 *
 * Threads: srv_vsl_engine_move_* and srv_vsl_engine_snapshot may be called
 * from any thread while the engine runs; everything else from one thread,
 * with the engine stopped.
 */
#ifndef SRV_VSL_ENGINE_H
#define SRV_VSL_ENGINE_H

#include <stddef.h>
#include <stdint.h>
#include "vsl/vsl_ivg.h"
#include "vsl/vsl_motion.h"
#include "vsl/vsl_updates.h"

typedef struct srv_vsl_engine srv_vsl_engine;

typedef struct srv_vsl_engine_opts {
    size_t   nv;          /* N_v */
    size_t   pool;        /* photon pool, impacts */
    uint64_t batch;       /* photon paths per step (between IVG updates) */
    double   rate;        /* photon paths per second: scene time in steps; a cap when running (0: none) */
    float    tau, eps;    /* vsl_ivg.h */
    int      dims[3];     /* IVG grid over the scene's bounds ... */
    int      use_grid;    /* ... or this grid (a package's IVGD: the clients' grid) */
    srv_grid grid;
    uint64_t seed;
} srv_vsl_engine_opts;

/* Defaults: N_v 400, pool 200 000, batch 20 000, rate 0, tau 0.05, eps
 * 1e-6 (§0.7.3), 16^3 grid, seed 1. */
srv_vsl_engine_opts srv_vsl_engine_defaults(void);

typedef struct srv_vsl_latency {
    uint64_t changes, settled;          /* recorded, and settled of them */
    double   last_s, mean_s, max_s;     /* wall seconds, change to settled */
    uint64_t last_paths;                /* photon paths, change to settled */
} srv_vsl_latency;

/* s (and m, may be NULL) must outlive the engine. NULL with a reason. */
srv_vsl_engine *srv_vsl_engine_create(const srv_scene *s, const srv_motion *m,
                                      const srv_vsl_engine_opts *o, char *err, size_t errlen);
void srv_vsl_engine_free(srv_vsl_engine *e);

/* One step at scene time t (seconds): motion applied, queued moves
 * applied, a batch shot, the IVG updated. Returns the VSLs republished. */
size_t srv_vsl_engine_step(srv_vsl_engine *e, double t);

/* Run steps in a thread (scene time = wall time since start) until stop.
 * LUMO_OK or LUMO_ERR_NOMEM (no thread). */
lumo_status srv_vsl_engine_start(srv_vsl_engine *e);
void srv_vsl_engine_stop(srv_vsl_engine *e);

/* Live commands, applied at the next step: object o's pose, light i's
 * position; from then on the live command holds it (its motion track, if
 * any, no longer applies). LUMO_ERR_ARG when out of range (or an area or
 * directional light). */
lumo_status srv_vsl_engine_move_object(srv_vsl_engine *e, uint32_t o, const srv_pose *p);
lumo_status srv_vsl_engine_move_light(srv_vsl_engine *e, uint32_t i, vec3 pos);

/* Under the engine's lock: the grid (nverts x 54 doubles into I, may be
 * NULL), up to cap changed vertex indices taken into dirty, the update
 * count. Returns the number of dirty indices written. */
size_t srv_vsl_engine_snapshot(srv_vsl_engine *e, double *I, uint32_t *dirty, size_t cap,
                               uint64_t *version);

/* Publish every IVG update into u (vsl_updates.h: what the updates
 * channel serves) from now on; the dirty vertices then go to u, not to
 * srv_vsl_engine_snapshot. u must outlive the engine's running. */
void srv_vsl_engine_attach_updates(srv_vsl_engine *e, srv_vsl_updates *u);

/* Read-only views (engine stopped, or racing as §0.7.2 allows). */
const srv_vsl_ivg *srv_vsl_engine_ivg(const srv_vsl_engine *e);
const srv_vsl_lit *srv_vsl_engine_lit(const srv_vsl_engine *e, size_t *n);
const srv_photon_tracer *srv_vsl_engine_tracer(const srv_vsl_engine *e);
const srv_pose *srv_vsl_engine_pose(const srv_vsl_engine *e, uint32_t o);
srv_vsl_latency srv_vsl_engine_latency(const srv_vsl_engine *e);

/* Steps at scene time t until every change so far has settled, then one
 * more (the IVG from a pool without the old photons); at most max_steps.
 * Returns the steps run. Offline runs (dyn-error, lumo-vsl-render). */
int srv_vsl_engine_settle(srv_vsl_engine *e, double t, int max_steps);

/* A copy of s (the engine's scene) posed as the engine has it now: meshes
 * moved by their poses, lights at their current positions. out is
 * initialised here (free with srv_scene_free). LUMO_OK or LUMO_ERR_NOMEM. */
lumo_status srv_vsl_engine_posed_scene(const srv_vsl_engine *e, const srv_scene *s, srv_scene *out);

#endif
