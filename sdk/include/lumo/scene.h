/*
 * lumo/scene.h — the scene payloads of docs/package-format.md: scene info
 * (counts, bounds, default camera) with its lights, raw meshes, the IVG
 * grid descriptor, and the recommended streaming order (ORDR). They arrive as package chunks (lumo/package.h) or as
 * network messages; these decoders take the payload bytes either way.
 *
 * Every byte is hostile: each decoder bounds-checks what it reads, converts
 * the binary32 fields to lumo fixed point with integer code only
 * (lumo_f32bits_to_fixed), and writes its outputs only on success.
 */
#ifndef LUMO_SCENE_H
#define LUMO_SCENE_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/config.h"
#include "lumo/fixed.h"
#include "lumo/ivg.h"
#include "lumo/status.h"

/* Light kinds, as in docs/scene-format.md: the one enum of every layer (the
 * server's scene model, the package, the session, the rasterizer). */
typedef enum lumo_light_kind {
    LUMO_LIGHT_POINT = 0, LUMO_LIGHT_SPOT = 1,
    LUMO_LIGHT_DIRECTIONAL = 2, LUMO_LIGHT_AREA = 3
} lumo_light_kind;

/* One light in fixed point. power: W per channel (point/spot/area) or
 * irradiance W/m^2 (directional), UQ16.16. pos, u, v in metres (Q16.16);
 * dir unit (Q1.14): spot axis, direction of travel, or area normal u x v.
 * cos_half: cosine of the spot's half angle (Q1.14). */
typedef struct lumo_pkg_light {
    lumo_light_kind kind;        /* point, spot, directional or area */
    lumo_q16_16  pos[3], u[3], v[3];   /* metres: position; area: its edge vectors */
    lumo_q1_14   dir[3];         /* unit: spot axis, direction of travel, area normal */
    lumo_q1_14   cos_half;       /* spot: cosine of the half angle */
    lumo_q16_16  half_angle_deg; /* spot: half angle, degrees */
    lumo_uq16_16 power[3];       /* W per channel; directional: W/m^2 */
} lumo_pkg_light;

/* Scene info: counts, bounds (metres, Q16.16) and the default camera
 * (docs/scene-format.md "Camera"; fovy in degrees, Q16.16). */
typedef struct lumo_pkg_info {
    uint32_t    mesh_count, light_count, triangle_count;   /* the scene's counts */
    lumo_q16_16 bmin[3], bmax[3];   /* bounding box, metres */
    lumo_q16_16 eye[3], target[3], up[3], fovy_deg;   /* default camera: metres; fovy degrees */
} lumo_pkg_info;

/* ---- a camera that frames the scene (docs/scene-format.md) -------------- */

/* The fitted camera's vertical field of view: 40 degrees (Q16.16). */
#define LUMO_SCENE_FIT_FOVY LUMO_Q16_FROM_INT(40)

/* Replace info's camera (eye, target, up, fovy_deg) with one that sees the
 * whole box info->bmin..bmax in a width x height frame: it looks at the
 * box's centre from a three-quarter view above the front (+z, y up, 30
 * degrees to the right, 25 above), vertical field of view
 * LUMO_SCENE_FIT_FOVY, from the nearest distance at which all eight corners
 * are in the frame (plus 1/64). The server fits for a square frame (1, 1),
 * which frames every landscape frame too. Integer code; the same on every
 * board.
 * LUMO_ERR_ARG (NULL, zero size), LUMO_ERR_RANGE (bmin > bmax on an axis,
 * or the eye would leave the Q16.16 range); info is unchanged on error. */
lumo_status lumo_scene_camera_fit(lumo_pkg_info *info, uint32_t width, uint32_t height);

/* The counts and flags of a raw MESH chunk. */
typedef struct lumo_pkg_mesh_info {
    uint32_t nverts, ntris;  /* vertices, triangles */
    uint32_t flags;          /* LUMO_PKG_MESH_EMITTER */
} lumo_pkg_mesh_info;
#define LUMO_PKG_MESH_EMITTER 1u   /* the visible rectangle of an area light: not shaded */

/* The INFO payload: TRUNCATED, CORRUPT (size), LIMIT (more than
 * LUMO_MAX_LIGHTS lights), NONFINITE, RANGE (field of view outside
 * (0, 180) degrees; a camera with eye on target, or up zero or parallel
 * to the view direction). */
lumo_status lumo_scene_info_decode(const uint8_t *p, size_t len, lumo_pkg_info *out);

/* Light `index` of an INFO payload: errors as lumo_scene_info_decode, RANGE
 * for an index past the light count, UNSUPPORTED for an unknown kind. */
lumo_status lumo_scene_light_decode(const uint8_t *p, size_t len, uint32_t index, lumo_pkg_light *out);

/* The counts of a MESH payload (TRUNCATED, CORRUPT, UNSUPPORTED flags). */
lumo_status lumo_scene_mesh_info_decode(const uint8_t *p, size_t len, lumo_pkg_mesh_info *out);

/* A MESH payload into caller arrays sized from its counts: pos 3*nverts
 * (Q16.16 metres), nrm 3*nverts (Q1.14 unit, may be NULL), albedo 3*nverts
 * (Q1.14 in [0,1], may be NULL), tris 3*ntris (may be NULL). The whole
 * payload is validated (finite values, ranges, indices < nverts) before any
 * output is written. */
lumo_status lumo_scene_mesh_decode(const uint8_t *p, size_t len, lumo_q16_16 *pos, lumo_q1_14 *nrm,
                                   lumo_q1_14 *albedo, uint32_t *tris);

/* The IVGD payload: the grid's dims and bounds (Q16.16). */
lumo_status lumo_scene_ivg_desc_decode(const uint8_t *p, size_t len, lumo_ivg_desc *out);

/* ---- the recommended interleaving of geometry and lighting (ORDR) --------
 * Steps, 12 bytes each: u8 channel (LUMO_CHANNEL_*), 3 reserved bytes, u32
 * mesh (geometry; 0 for lighting), u32 amount (vertices for geometry, as a
 * REQUEST asks them; IVG rounds for lighting). The payload: u32 prefix step
 * count P, u32 cycle step count C, then the P + C steps. A client takes the
 * prefix once, then the cycle again and again until every channel has
 * ended, skipping steps of a channel (of a mesh) that has ended; a pass over
 * the cycle in which every step was skipped ends the order
 * (docs/package-format.md "ORDR"). */
#define LUMO_CHANNEL_GEOMETRY 0u   /* a step of progressive-mesh batches */
#define LUMO_CHANNEL_LIGHTING 1u   /* a step of IVG rounds */

/* One step of the order, decoded (lumo_scene_order_step). */
typedef struct lumo_scene_step {
    uint32_t channel, mesh, amount;   /* LUMO_CHANNEL_*; mesh; vertices or IVG rounds */
} lumo_scene_step;

/* A decoded ORDR payload. */
typedef struct lumo_scene_order {
    uint32_t       prefix, cycle;   /* step counts */
    const uint8_t *steps;           /* into the payload (not owned) */
} lumo_scene_order;

/* Decode and check an ORDR payload; *out keeps a pointer into p. TRUNCATED
 * / CORRUPT when the length is not that of P + C steps; UNSUPPORTED for a
 * channel other than 0 and 1; CORRUPT for an amount of 0 or a lighting step
 * naming a mesh; RANGE for a geometry step naming a mesh >= mesh_count. */
lumo_status lumo_scene_order_decode(const uint8_t *p, size_t len, uint32_t mesh_count, lumo_scene_order *out);

/* Step i (0 .. prefix + cycle - 1: the prefix's, then the cycle's);
 * RANGE past the last. */
lumo_status lumo_scene_order_step(const lumo_scene_order *o, uint32_t i, lumo_scene_step *out);

#endif /* LUMO_SCENE_H */
