/*
 * lumo/session.h — the client session: one scene as a thin client holds it
 * (seed 000 §4: progressive meshes plus the IVG, refined as bytes arrive).
 *
 * The session is fed messages — the payloads of docs/package-format.md
 * (scene info, raw meshes, progressive-mesh stream headers and batch
 * records, the IVG descriptor, bundles and runs of their records, the IVG
 * streaming order and the interleaving) — from wherever they come: a
 * package file, a socket, a UART, USB or a replay. It owns the
 * level-of-detail cursor of every mesh, the progressive-mesh decoders, the
 * IVG and its push-pull, and hands out what a renderer draws. Every board
 * and tool drives this one object; none re-implements it.
 *
 * Usage (a package in memory):
 *   lumo_package pkg;  lumo_package_open(&pkg, bytes, size);
 *   size_t need;       lumo_session_package_need(&pkg, &need);
 *   lumo_arena a;      lumo_arena_init(&a, buffer, need);
 *   lumo_session s;    lumo_session_init(&s, &cfg, &a);
 *   lumo_session_feed_package(&s, &pkg);     (or lumo_session_feed per message)
 *   lumo_session_update(&s);                  push-pull if lighting arrived
 *   lumo_session_mesh(&s, i, &view) ...       draw
 *
 * Memory: the session struct is the caller's (its size is fixed by
 * lumo/config.h: about 300 bytes per LUMO_MAX_MESHES and 88 per
 * LUMO_MAX_LIGHTS, 21 KB with the defaults: keep it static, not on a small
 * stack); every array comes from
 * the arena given to init, carved when a descriptor message (raw mesh,
 * stream header, IVG descriptor) arrives. lumo_session_message_need() tells
 * what a descriptor will take, so a client sizes its arena before the bulk
 * arrives. The arena must outlive the session.
 *
 * Hostile input: every message is validated by its decoder; a message that
 * fails changes nothing (the scene stays at its last good state and still
 * draws), and the error says why. Out of order or repeated messages give
 * LUMO_ERR_STATE.
 */
#ifndef LUMO_SESSION_H
#define LUMO_SESSION_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/arena.h"
#include "lumo/config.h"
#include "lumo/ivg.h"
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo/scene.h"
#include "lumo/status.h"

/* Message types: the package's chunk types (lumo/package.h), plus one for a
 * single batch record of a progressive stream and one for a run of IVG
 * records. A PMSH message holds a stream's header, optionally followed by
 * batch records (a whole stream as a package stores it). */
#define LUMO_MSG_INFO  LUMO_PKG_INFO    /* scene info and lights (index 0) */
#define LUMO_MSG_MESH  LUMO_PKG_MESH    /* raw mesh `index` */
#define LUMO_MSG_PMSH  LUMO_PKG_PMSH    /* progressive stream of mesh `index` */
#define LUMO_MSG_PMSB  LUMO_PKG_FOURCC('P', 'M', 'S', 'B')  /* one batch record of mesh `index` */
#define LUMO_MSG_IVGD  LUMO_PKG_IVGD    /* IVG grid descriptor */
#define LUMO_MSG_IVGQ  LUMO_PKG_IVGQ    /* IVG bundle, quantized form */
#define LUMO_MSG_IVGF  LUMO_PKG_IVGF    /* IVG bundle, binary32 form */
#define LUMO_MSG_IVGS  LUMO_PKG_IVGS    /* IVG streaming order (stored) */
#define LUMO_MSG_ORDR  LUMO_PKG_ORDR    /* recommended interleaving (stored) */
/* A run of IVG records without the bundle header, as a DATA frame of the
 * lighting channel carries them (docs/protocol.md): u8 form (0 binary32,
 * 1 quantized), 3 reserved bytes (written 0, ignored), u32 record count,
 * then the records (lumo_ivg_apply_records). */
#define LUMO_MSG_IVGR  LUMO_PKG_FOURCC('I', 'V', 'G', 'R')
#define LUMO_MSG_IVGR_HEADER 8u   /* bytes of an IVGR message's head */

/* Level of detail: how far each progressive mesh is refined. A batch past
 * the target is not applied; the batch that crosses it is applied and the
 * mesh stepped back to exactly the target (lumo_pmesh_rewind), after which
 * the mesh is final. Never below the base mesh (it arrives whole). */
typedef struct lumo_session_lod {
    uint32_t vertices;   /* > 0: at most this many vertices per mesh */
    uint32_t ppm;        /* else this fraction, in parts per million (0 to
                            LUMO_SESSION_LOD_ALL), of the vertices streamed
                            after the base mesh, rounded up */
} lumo_session_lod;
#define LUMO_SESSION_LOD_ALL 1000000u   /* lod.ppm for the full meshes */

/* How a session refines: lumo_session_init's cfg. */
typedef struct lumo_session_config {
    lumo_session_lod lod;   /* how far meshes are refined */
    unsigned ivg_flags;  /* flags of lumo_ivg_pushpull (LUMO_IVG_SMOOTH) */
} lumo_session_config;

/* One mesh slot. Fields are private: read them through lumo_session_mesh. */
typedef struct lumo_session_mesh_slot {
    uint32_t    kind;       /* 0 empty, 1 raw, 2 progressive */
    uint32_t    target;     /* progressive: the level's vertex count */
    lumo_pmesh  pm;         /* progressive */
    lumo_pmesh_view raw;    /* raw: the arrays in the arena */
} lumo_session_mesh_slot;

/* The session. Fields are private. */
typedef struct lumo_session {
    lumo_session_config cfg;
    lumo_arena    *arena;
    int            have_info;
    lumo_pkg_info  info;
    lumo_pkg_light lights[LUMO_MAX_LIGHTS];
    lumo_ivg      *ivg;           /* NULL until IVGD */
    uint32_t       ivg_received;  /* vertices received at the last update */
    int            ivg_dirty;     /* bundles applied since the last update */
    uint32_t       ivg_records;   /* records applied (bundles and IVGR runs) */
    int            have_ivg_order, have_order;
    lumo_ivg_order ivg_order;     /* IVGS, its table copied into the arena */
    lumo_scene_order order;       /* ORDR, its steps copied into the arena */
    lumo_session_mesh_slot mesh[LUMO_MAX_MESHES];
} lumo_session;

/* An empty session taking its memory from `arena` (not owned; must outlive
 * the session). cfg NULL: full meshes, smoothing on. */
lumo_status lumo_session_init(lumo_session *s, const lumo_session_config *cfg, lumo_arena *arena);

/* Arena bytes the message (type, payload) will take when fed: the arrays of
 * a raw mesh, a progressive mesh's decoder (from its stream header), the
 * IVG grid, the copy of an IVGS or ORDR payload; 0 for the others. Errors
 * as the payload's decoder. */
lumo_status lumo_session_message_need(uint32_t type, const uint8_t *payload, size_t len, size_t *bytes);

/* Arena bytes to feed the whole package (LUMO_ARENA_SLACK included).
 * Errors as its payloads' decoders; LUMO_ERR_LIMIT for more than
 * LUMO_MAX_MESHES meshes (what a session holds). */
lumo_status lumo_session_package_need(const lumo_package *pkg, size_t *bytes);

/* Feed one message. `index`: the mesh for MESH, PMSH and PMSB, else 0.
 * INFO must come first (STATE otherwise) and only once; a mesh index past
 * the info's mesh count is RANGE (an info naming more than LUMO_MAX_MESHES
 * is LIMIT); NOMEM when the arena is too small for a descriptor. A PMSB past
 * the level-of-detail target is accepted and ignored. IVGQ, IVGF, IVGR and
 * IVGS need the IVGD first (STATE); IVGS and ORDR come once (STATE) and are
 * checked against the grid and the mesh count. On any error nothing
 * changes — except that a PMSH message carrying records acts as its header
 * followed by one PMSB per record: the header and the records before a bad
 * one stay applied. */
lumo_status lumo_session_feed(lumo_session *s, uint32_t type, uint32_t index, const uint8_t *payload,
                              size_t len);

/* Feed a whole package in its stream order: INFO, the IVG (its descriptor,
 * its streaming order IVGS and the interleaving ORDR when present, then the
 * quantized bundle a client receives, else the binary32 one), then every
 * mesh (its PMSH stream, else its MESH chunk). Stops at the first error;
 * *where (may be NULL) then names the failing message's type and index. */
typedef struct lumo_session_where {
    uint32_t type, index;   /* the failing message's type (LUMO_MSG_*) and index */
    uint32_t batch;      /* PMSH: the batch record that failed */
} lumo_session_where;
/* Feed the whole package (above); *where names a failure. */
lumo_status lumo_session_feed_package(lumo_session *s, const lumo_package *pkg, lumo_session_where *where);

/* Change the push-pull flags for the next updates (LUMO_IVG_SMOOTH or 0):
 * a weak client drops smoothing when it costs more than it can spend
 * (seed 000 §5.2, Fig. 7). ARG for unknown flags. */
lumo_status lumo_session_set_ivg_flags(lumo_session *s, unsigned flags);

/* Bring derived state up to date: push-pull fills the IVG's missing
 * vertices when bundles arrived since the last update (never changing a
 * received one). Returns 1 when something changed. */
int lumo_session_update(lumo_session *s);

/* ---- what a renderer reads ------------------------------------------------ */

/* Scene info (counts, bounds, default camera); NULL before INFO. */
const lumo_pkg_info *lumo_session_info(const lumo_session *s);
/* The lights (light_count of the info) and their number. */
const lumo_pkg_light *lumo_session_lights(const lumo_session *s, uint32_t *count);
/* The IVG, or NULL when none has arrived. */
const lumo_ivg *lumo_session_ivg(const lumo_session *s);

/* The IVG streaming order (IVGS) and the interleaving (ORDR), or NULL when
 * they have not arrived. */
const lumo_ivg_order *lumo_session_ivg_order(const lumo_session *s);
const lumo_scene_order *lumo_session_order(const lumo_session *s);

/* Lighting progress: records applied (every bundle's and IVGR run's, in the
 * order they came), and — with the IVGS — the whole rounds of the streaming
 * order among them, the cursor of a lighting REQUEST (docs/protocol.md),
 * out of `rounds`. Rounds are counted as if the records came in the order's
 * sequence, as a server sends them. */
typedef struct lumo_session_lighting {
    uint32_t records;               /* IVG records applied */
    uint32_t rounds_held, rounds;   /* 0, 0 without IVGS */
} lumo_session_lighting;
/* The lighting progress (above) into *out. */
void lumo_session_lighting_progress(const lumo_session *s, lumo_session_lighting *out);

/* Mesh `index` at its current level; RANGE when no such mesh has arrived.
 * The arrays are the session's and change with every fed batch. */
lumo_status lumo_session_mesh(const lumo_session *s, uint32_t index, lumo_pmesh_view *out);

/* Progress of mesh `index`: vertices of the full mesh and whether it is
 * progressive (0: raw). RANGE when no such mesh has arrived. */
typedef struct lumo_session_progress {
    uint32_t progressive;   /* 1 for a progressive mesh, 0 for a raw one */
    uint32_t vertices, full_vertices;   /* vertices now; of the full mesh */
    uint32_t batches;     /* batch records applied */
} lumo_session_progress;
/* The progress of mesh `index` (above) into *out. */
lumo_status lumo_session_mesh_progress(const lumo_session *s, uint32_t index, lumo_session_progress *out);

/* The stream header of progressive mesh `index` (batch sizes and counts, for
 * a client that sizes its requests); RANGE when no such stream arrived. */
lumo_status lumo_session_stream_header(const lumo_session *s, uint32_t index, lumo_pmesh_header *out);

#endif /* LUMO_SESSION_H */
