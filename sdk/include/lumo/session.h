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
#include "lumo/prt.h"
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
/* Lighting updates of a dynamic scene (docs/dynamic.md): an IVGR run that
 * replaces vertices already held, as a DATA frame of the updates channel
 * carries it; not counted in lumo_session_lighting_progress. */
#define LUMO_MSG_IVGU  LUMO_PKG_FOURCC('I', 'V', 'G', 'U')
/* PRT (seed 003, docs/prt.md, docs/client-session.md "PRT"): the
 * clustered-PCA transfer of mesh `index` and an environment's lighting.
 * PRTV: the mesh's PRTV chunk, or a prefix of it of at least its 12-byte
 * header (the session then holds the whole chunk's size in the arena);
 * once per mesh. PRTS: a span of that chunk continuing it, u32 byte
 * offset (= the bytes held) then the bytes; as a DATA frame of the PRT
 * channel carries it (docs/protocol.md §10). PRTL: the PRTL chunk (u8
 * order, 3 zero bytes, 3 x N^2 int32 Q16.16); once. */
#define LUMO_MSG_PRTV  LUMO_PKG_FOURCC('P', 'R', 'T', 'V')
#define LUMO_MSG_PRTS  LUMO_PKG_FOURCC('P', 'R', 'T', 'S')
#define LUMO_MSG_PRTL  LUMO_PKG_FOURCC('P', 'R', 'T', 'L')
#define LUMO_MSG_PRTS_HEADER 4u   /* bytes of a PRTS message's head */

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
    uint8_t    *prt;        /* PRT: the mesh's PRTV chunk in the arena (its size from
                               the header), NULL before PRTV */
    uint32_t    prt_held;   /* its bytes held (checked), a prefix */
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
    lumo_q16_16    pose[LUMO_MAX_MESHES][4];   /* dynamic scenes: translation (m), yaw (deg) */
    const uint8_t *prtl;          /* PRTL: its checked copy in the arena (its length from
                                   * its order), NULL before */
} lumo_session;

/* An empty session taking its memory from `arena` (not owned; must outlive
 * the session). cfg NULL: full meshes, smoothing on. */
lumo_status lumo_session_init(lumo_session *s, const lumo_session_config *cfg, lumo_arena *arena);

/* Arena bytes the message (type, payload) will take when fed: the arrays of
 * a raw mesh, a progressive mesh's decoder (from its stream header), the
 * IVG grid, the copy of an IVGS or ORDR payload, a PRTV's whole chunk (from
 * its header), a PRTL's copy; 0 for the others. Errors
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
 * the level-of-detail target is accepted and ignored. IVGQ, IVGF, IVGR, IVGU and
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
 * mesh (its PMSH stream, else its MESH chunk), then each mesh's PRTV chunk
 * and the PRTL when present. Stops at the first error;
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
/* Dynamic scenes (docs/dynamic.md): a light moved to pos (RANGE past the
 * info's lights; STATE before INFO), and a mesh's pose — translation in
 * metres and rotation about +y in degrees, from where the package put it
 * (RANGE past the info's meshes). A session starts with every pose zero;
 * the caller's renderer applies them. */
lumo_status lumo_session_move_light(lumo_session *s, uint32_t i, const lumo_q16_16 pos[3]);
lumo_status lumo_session_set_mesh_pose(lumo_session *s, uint32_t i, const lumo_q16_16 t[3], lumo_q16_16 yaw_deg);
lumo_status lumo_session_mesh_pose(const lumo_session *s, uint32_t i, lumo_q16_16 t[3], lumo_q16_16 *yaw_deg);

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

/* The PRT of mesh `index` as held (lumo/prt.h: a view of the session's
 * copy; vertices_held grows as PRTS spans arrive — relight those, the
 * first ones of the progressive order, whatever the level of detail):
 * LUMO_OK; RANGE when no PRTV of that mesh arrived; TRUNCATED while its
 * clusters and pass table are not all held. */
lumo_status lumo_session_prt(const lumo_session *s, uint32_t index, lumo_prt *out);
/* Bytes of mesh `index`'s PRTV chunk held and its whole size (0, 0 before
 * its PRTV): the cursor of a PRT REQUEST (docs/protocol.md §10). */
void lumo_session_prt_progress(const lumo_session *s, uint32_t index, uint32_t *held, uint32_t *size);
/* The layout of mesh `index`'s PRTV chunk (from its header): the bytes
 * before its vertex records (header, clusters, pass table) and one vertex
 * record's. RANGE when no PRTV of that mesh arrived. */
lumo_status lumo_session_prt_layout(const lumo_session *s, uint32_t index, uint32_t *fixed, uint32_t *vertex_bytes);
/* The environment lighting of the PRTL message: RANGE when none arrived. */
lumo_status lumo_session_prt_light(const lumo_session *s, lumo_prt_light *out);

/* The stream header of progressive mesh `index` (batch sizes and counts, for
 * a client that sizes its requests); RANGE when no such stream arrived. */
lumo_status lumo_session_stream_header(const lumo_session *s, uint32_t index, lumo_pmesh_header *out);

#endif /* LUMO_SESSION_H */
