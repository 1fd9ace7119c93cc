/*
 * lumo/raster.h — the backend-neutral rasterizer interface (seed 000, §3.2-3.3).
 *
 * One description of a frame — a camera, the scene's lights, an optional
 * indirect-light source (the IVG), a mesh and a target — drawn by three
 * backends: rasterizer/soft (this API's functions, client rules: C99, no heap,
 * no float, bit-exact), and the desktop GL backends (lumo/raster_gl.h) that
 * take the very same structures.
 *
 * Shading model (docs/rasterizer.md):
 *   L = rho/pi * (E_direct + E_indirect)         diffuse only, per channel
 *   E_direct: point light of intensity I = Phi/(4 pi) W/sr: I cos(theta)/r^2;
 *             spot: the same inside a hard cone, 0 outside;
 *             directional: E cos(theta). Each light may carry a shadow map
 *             (lumo_raster_shadow below): its direct light is then scaled
 *             by the visibility the map gives (2x2 PCF), 0 in full shadow.
 *   E_indirect = max(0, I_n . n) from the IVG (§3.2), or 0.
 *   Surfaces are two-sided: n is turned towards the eye before shading.
 *   pixel = sRGB(clamp(L * exposure, 0, 1)) to 8 bits (integer table), then
 *           XRGB8888, or RGB565 with a 4x4 ordered dither.
 * Lighting is evaluated per vertex (Gouraud: L interpolated) or per pixel
 * (position, normal and albedo interpolated, normal renormalised).
 *
 * Geometry: right-handed world, camera looks from eye to target; front faces
 * are counter-clockwise as seen by the camera (OpenGL's default). Depth is
 * near/w (1 at the near plane, towards 0 far away; no far plane), larger is
 * nearer; depth buffers are cleared to 0.
 *
 * Units: positions in scene units as Q16.16; normals and albedo Q1.14;
 * power, intensity, irradiance and radiance UQ16.16 (W, W/sr, W/m^2,
 * W/m^2/sr per channel).
 */
#ifndef LUMO_RASTER_H
#define LUMO_RASTER_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/config.h"
#include "lumo/fixed.h"
#include "lumo/scene.h"
#include "lumo/status.h"

/* Limits (lumo/config.h): frames up to LUMO_MAX_FRAME_DIM pixels per axis
 * (it bounds the edge-function ranges: docs/rasterizer.md, "ranges"), up to
 * LUMO_MAX_LIGHTS lights per frame. */

/* ---- camera ------------------------------------------------------------- */

/* A pinhole camera, scene units. */
typedef struct lumo_raster_camera {
    lumo_q16_16 eye[3];     /* where it is */
    lumo_q16_16 target[3];  /* where it looks */
    lumo_q16_16 up[3];      /* up direction (any length) */
    lumo_q16_16 fovy_deg;   /* vertical field of view in degrees, [1, 179] */
    lumo_q16_16 znear;      /* near plane distance (> 0), scene units */
} lumo_raster_camera;

/* ---- lights ------------------------------------------------------------- */

struct lumo_raster_shadow;

/* A light as the rasterizer shades with it (no area lights). */
typedef struct lumo_raster_light {
    lumo_light_kind kind;      /* point, spot or directional */
    lumo_q16_16  pos[3];       /* point, spot: position */
    lumo_q1_14   dir[3];       /* spot: cone axis; directional: the direction
                                * the light travels. Unit length (a component
                                * beyond +-1 is refused: LUMO_ERR_RANGE). */
    lumo_q1_14   cos_cutoff;   /* spot: cos of the cone's half angle */
    lumo_uq16_16 value[3];     /* point, spot: power Phi (W per channel);
                                * directional: irradiance E (W/m^2) on a
                                * surface facing it */
    const struct lumo_raster_shadow *shadow;  /* NULL: unshadowed; else this
                                * light's map (lumo_raster_shadow_init and
                                * _draw), the caller's, valid while drawn */
} lumo_raster_light;

/* ---- a package's camera and lights (lumo/scene.h) ------------------------ */

/* The near plane clients draw a package's camera with: 0.01 m (Q16.16,
 * rounded); docs/rasterizer.md, "16-bit depth", says what it costs. */
#define LUMO_RASTER_ZNEAR ((lumo_q16_16)655)
/* The smallest near plane a box gives (lumo_raster_znear_for_box): 1/4096 m,
 * so a millimetre-sized model seen from a few millimetres keeps its depth. */
#define LUMO_RASTER_ZNEAR_MIN ((lumo_q16_16)16)

/* The package's default camera (its scene info), its near plane from the
 * scene's bounds (lumo_raster_znear_for_box). */
void lumo_raster_camera_from_info(const lumo_pkg_info *info, lumo_raster_camera *out);

/* The near plane for cam looking at geometry inside the box bmin..bmax
 * (metres, Q16.16): half the smallest view depth of the box's corners, so
 * nothing inside is clipped; LUMO_RASTER_ZNEAR when that is below
 * LUMO_RASTER_ZNEAR_MIN (the eye inside or beside the box) or eye == target. A larger near plane gives 16-bit
 * depth finer steps (docs/rasterizer.md, "16-bit depth"). */
lumo_q16_16 lumo_raster_znear_for_box(const lumo_raster_camera *cam, const lumo_q16_16 bmin[3],
                                      const lumo_q16_16 bmax[3]);

/* A package light as a rasterizer light. The client has no area lights: an
 * area light becomes a spot at its centre facing its normal with a
 * 90-degree half angle and 2 Phi as its point-equivalent power (a uniform
 * hemisphere emitter, saturating; docs/rasterizer.md). */
void lumo_raster_light_from_pkg(const lumo_pkg_light *p, lumo_raster_light *out);

/* Indirect irradiance towards unit normal n at p (W/m^2, UQ16.16 per channel).
 * lumo_raster_ivg_irradiance() adapts lumo/ivg.h to it. */
typedef void (*lumo_raster_indirect_fn)(const void *ctx, const lumo_q16_16 p[3],
                                        const lumo_q1_14 n[3], lumo_uq16_16 out[3]);

/* Adapter: ctx is a const lumo_ivg *; calls lumo_ivg_irradiance. Lives in
 * its own object so programs without an IVG do not link the IVG code. */
void lumo_raster_ivg_irradiance(const void *ivg, const lumo_q16_16 p[3],
                                const lumo_q1_14 n[3], lumo_uq16_16 out[3]);

/* Adapter: ctx is a lumo_ivg_sampler * (lumo/ivg.h), taken as const void *
 * by the callback type but written: its memo of the last opened IVG cell.
 * Same values as lumo_raster_ivg_irradiance with the sampler's grid, and
 * cheaper per pixel (neighbouring pixels share a cell). One sampler per
 * drawing thread, initialised with lumo_ivg_sampler_init after the grid
 * last changed. */
void lumo_raster_ivg_sampler_irradiance(const void *sampler, const lumo_q16_16 p[3],
                                        const lumo_q1_14 n[3], lumo_uq16_16 out[3]);

/* Flags of a frame. */
#define LUMO_RASTER_PER_PIXEL 1u   /* per-pixel lighting (default: per vertex) */
#define LUMO_RASTER_CULL_BACK 2u   /* drop back faces (closed meshes) */
/* Per-pixel lighting, drawn into a band whose depth is clear: a depth-only
 * pass over the mesh first, then only each pixel's nearest fragment is
 * shaded, so a mesh that overdraws itself (a model inside a room) shades
 * every pixel once. The same bytes as without; it costs a second set-up of
 * every triangle, so it pays only where the mesh overdraws. Ignored per
 * vertex and when the band's depth holds anything (docs/rasterizer.md). */
#define LUMO_RASTER_DEPTH_FIRST 4u

/* What lights a frame. */
typedef struct lumo_raster_scene {
    const lumo_raster_light *lights;   /* light_count entries (may be NULL if 0) */
    uint32_t light_count;              /* <= LUMO_MAX_LIGHTS */
    lumo_raster_indirect_fn indirect;  /* NULL: no indirect light */
    const void *indirect_ctx;          /* handed to indirect */
    lumo_uq16_16 exposure;             /* multiplies radiance; 1.0 = LUMO_Q16_ONE */
    uint32_t flags;                    /* LUMO_RASTER_* */
} lumo_raster_scene;

/* ---- mesh ---------------------------------------------------------------- */

/* A mesh to draw; the arrays are the caller's. */
typedef struct lumo_raster_mesh {
    const lumo_q16_16 *pos;       /* 3 per vertex, scene units */
    const lumo_q1_14  *normal;    /* 3 per vertex, unit length */
    const lumo_q1_14  *albedo;    /* 3 per vertex in [0, 1], or NULL ... */
    lumo_q1_14 mesh_albedo[3];    /* ... then this one for the whole mesh */
    const uint32_t *tris;         /* 3 vertex indices per triangle */
    uint32_t vertex_count;        /* entries of pos, normal, albedo */
    uint32_t tri_count;           /* triangles at tris */
    const lumo_uq16_16 *lit;      /* optional, per-vertex lighting only: 6 per
                                   * vertex, the radiance of its front (n) and
                                   * back (-n) side from lumo_raster_light_vertices
                                   * for the scene drawn; NULL: lit per frame */
    const lumo_uq16_16 *indirect; /* optional, per-pixel lighting only: 6 per
                                   * vertex, the indirect irradiance towards n
                                   * and -n from lumo_raster_indirect_vertices;
                                   * interpolated across triangles instead of
                                   * sampled per pixel (docs/rasterizer.md,
                                   * "IVG per vertex"); NULL: sampled per pixel */
} lumo_raster_mesh;

/* Diffuse light does not depend on the view: a vertex's radiance (direct,
 * shadowed, and the IVG's indirect light) changes only with the lights, the
 * IVG or the mesh. lumo_raster_light_vertices fills `lit` (vertex_count * 6
 * entries, lumo_raster_lit_bytes) once; a mesh whose `lit` points at it is
 * then drawn per vertex without evaluating any light, with the very bytes
 * of a mesh without it (which side a vertex shows is still decided per
 * frame). Fill it again when a light, the IVG or the mesh changes. */
size_t lumo_raster_lit_bytes(uint32_t vertex_count);
lumo_status lumo_raster_light_vertices(const struct lumo_raster_scene *s, const lumo_raster_mesh *m,
                                       lumo_uq16_16 *lit);

/* The indirect term alone, for per-pixel lighting: the scene's indirect
 * irradiance (the IVG) towards n and -n at every vertex into `ind`
 * (vertex_count * 6 entries, lumo_raster_lit_bytes bytes). A mesh whose
 * `indirect` points at it is drawn per pixel with the direct light (and
 * shadows) per pixel and the indirect light interpolated from the vertices:
 * one IVG sample per vertex side instead of one per pixel. It depends on
 * the IVG and the mesh only (not on the lights nor the view). LUMO_ERR_ARG
 * without an indirect source. */
lumo_status lumo_raster_indirect_vertices(const struct lumo_raster_scene *s, const lumo_raster_mesh *m,
                                          lumo_uq16_16 *ind);

/* ---- target: a frame, or one band of K rows of it ------------------------ */

/* The colour buffer's pixels. */
typedef enum lumo_pixel_format {
    LUMO_PIXEL_XRGB8888 = 0,   /* uint32 0x00RRGGBB */
    LUMO_PIXEL_RGB565          /* uint16, ordered dither on absolute (x, y) */
} lumo_pixel_format;

/* Where a frame (or a band of it) is drawn; buffers are the caller's. */
typedef struct lumo_raster_target {
    uint16_t width, height;    /* the whole frame, <= LUMO_MAX_FRAME_DIM */
    uint16_t band_y;           /* first frame row held in the buffers */
    uint16_t band_rows;        /* rows held (K); band_y + K <= height */
    lumo_pixel_format format;  /* of color */
    void    *color;            /* band_rows rows of color_stride bytes */
    uint32_t color_stride;     /* bytes between rows, >= width * pixel size */
    void    *depth;            /* band_rows * width entries of depth_bits */
    uint8_t  depth_bits;       /* 16 or 32 */
} lumo_raster_target;

/* Bytes of colour plus depth buffer for a band of `rows` rows (tight rows),
 * 0 for invalid arguments. */
size_t lumo_raster_band_bytes(uint16_t width, uint16_t rows, lumo_pixel_format format,
                              uint8_t depth_bits);

/* Fill *t for rows [band_y, band_y + band_rows) of a width x height frame
 * with tight rows (color_stride = width * pixel size). `color` and `depth`
 * stay the caller's; they must hold band_rows rows each. Returns
 * lumo_raster_target_check(t). */
lumo_status lumo_raster_target_init(lumo_raster_target *t, uint16_t width, uint16_t height,
                                    uint16_t band_y, uint16_t band_rows,
                                    lumo_pixel_format format, void *color, void *depth,
                                    uint8_t depth_bits);

/* Validate a target (dimensions, band, stride, buffers, depth_bits). */
lumo_status lumo_raster_target_check(const lumo_raster_target *t);

/* Fill the band with `rgb` (0xRRGGBB, already display-encoded) and the
 * depth buffer with 0 (infinitely far). */
lumo_status lumo_raster_clear(lumo_raster_target *t, uint32_t rgb);

/* ---- the view: camera reduced to integer matrices ------------------------ */

/* A camera prepared for one frame size (lumo_raster_view_init). */
typedef struct lumo_raster_view {
    lumo_q16_16 eye[3];        /* the camera's position */
    lumo_q1_14  rot[3][3];     /* rows: right, up, forward (camera basis) */
    lumo_q16_16 cot_half;      /* cot(fovy / 2) */
    lumo_q16_16 znear;         /* near plane, scene units */
    uint16_t width, height;    /* the frame, pixels */
} lumo_raster_view;

/* Build the view for a frame of width x height. LUMO_ERR_RANGE when the
 * camera is degenerate (eye == target, up parallel to the view direction,
 * fovy outside [1, 179], znear <= 0) or the size is out of range. */
lumo_status lumo_raster_view_init(lumo_raster_view *v, const lumo_raster_camera *cam,
                                  uint16_t width, uint16_t height);

/* cot(deg / 2) for deg (Q16.16 degrees) in [1, 179], computed from an integer
 * sine table (no float); exposed for tests and the GL backends' agreement. */
lumo_q16_16 lumo_raster_cot_half_deg(lumo_q16_16 deg);

/* ---- shading (shared by the per-vertex and per-pixel paths) ------------- */

/* Irradiance (direct + indirect) at p with unit normal n, W/m^2 per channel. */
void lumo_raster_irradiance(const lumo_raster_scene *s, const lumo_q16_16 p[3],
                            const lumo_q1_14 n[3], lumo_uq16_16 out[3]);

/* rho/pi * E per channel. */
void lumo_raster_radiance(const lumo_uq16_16 e[3], const lumo_q1_14 albedo[3],
                          lumo_uq16_16 out[3]);

/* Tone map one channel: sRGB(clamp(L * exposure, 0, 1)) rounded to 8 bits. */
uint8_t lumo_raster_tonemap(lumo_uq16_16 radiance, lumo_uq16_16 exposure);

/* ---- transformed-vertex cache ------------------------------------------- */

/* Clip-space position and the varyings of one vertex (per-vertex mode: the
 * lit radiance; per-pixel mode: position, normal, albedo), and, for a vertex
 * inside every clip plane, its screen position: triangles of such vertices
 * skip projection, and each band rejects them from their rows alone. */
#define LUMO_RASTER_MAX_VARYINGS 12
/* One transformed vertex of the cache (above). */
typedef struct lumo_raster_vertex {
    int32_t  clip[3];          /* x, y, w in scene units, Q16.16 */
    int32_t  var[LUMO_RASTER_MAX_VARYINGS];   /* the varyings (above) */
    uint32_t outcode;          /* clip planes the vertex is outside of */
    int32_t  screen[2];        /* when outcode == 0: x, y in 1/16 pixel */
    uint32_t q;                /* when outcode == 0: znear / w, Q0.30 */
} lumo_raster_vertex;

/* Bytes a cache for n vertices needs (SIZE_MAX on overflow). */
size_t lumo_raster_cache_bytes(uint32_t vertex_count);

/* Transform (and, per vertex, light) every vertex of the mesh into `cache`
 * (vertex_count entries). Done once per frame, it saves the work each band
 * and each triangle would repeat. */
lumo_status lumo_raster_prepare(const lumo_raster_view *v, const lumo_raster_scene *s,
                                const lumo_raster_mesh *m, lumo_raster_vertex *cache);

/* ---- shadow maps (docs/rasterizer.md "Shadows") -------------------------- */

/* A depth-only map drawn by this rasterizer from the light: 16-bit znear/w
 * per texel (0 = nothing drawn), `size` x `size` texels per face.
 *   point light: a cube map, 6 faces of 90 degrees (+x, -x, +y, -y, +z, -z);
 *   spot: one face covering the cone (field of view 2 * ceil(half angle) +
 *         2 degrees), or a cube when the half angle exceeds 75 degrees;
 *   directional: one perspective face from 16 radii up-light of the bounding
 *         sphere given at init (rays within 3.6 degrees of parallel).
 * Lookup (per pixel, or per vertex in per-vertex mode): the point is moved
 * along its normal by 1.5 texel footprints (normal-offset bias), projected
 * into the face, compared with a depth bias of one texel footprint, and the
 * 4 nearest texels' results are weighted bilinearly (2x2 PCF, 1/16-texel
 * weights): visibility in [0, 256]. Memory: faces * size^2 * 2 bytes, the
 * caller's (e.g. 6 * 128^2 * 2 = 196 608 B; one 256^2 spot map 131 072 B).
 * The map is a function of the light and the geometry only: draw it again
 * when either changes, not per frame. */
#define LUMO_RASTER_SHADOW_MAX_FACES 6
#define LUMO_RASTER_SHADOW_MIN_SIZE 8
/* Default near plane of the light's views: 0.05 scene units (Q16.16).
 * Geometry nearer the light than this casts no shadow. */
#define LUMO_RASTER_SHADOW_ZNEAR ((lumo_q16_16)3277)

/* A light's shadow map: its views and the caller's depth texels. */
typedef struct lumo_raster_shadow {
    lumo_raster_view face[LUMO_RASTER_SHADOW_MAX_FACES];  /* the light's views */
    uint16_t *depth;           /* faces * size * size texels, face-major, rows top first */
    uint16_t size;             /* texels per face side */
    uint8_t faces;             /* 1 or 6 */
} lumo_raster_shadow;

/* Faces of the map a light needs (1 or 6), 0 for a bad light. */
unsigned lumo_raster_shadow_faces(const lumo_raster_light *l);

/* Bytes of depth a map of `size` texels per side needs for light l (0 for
 * a bad light or a size outside [LUMO_RASTER_SHADOW_MIN_SIZE,
 * LUMO_MAX_FRAME_DIM]). */
size_t lumo_raster_shadow_bytes(const lumo_raster_light *l, uint16_t size);

/* Set up the light's views and clear the map. `depth` (bytes >=
 * lumo_raster_shadow_bytes) stays the caller's. centre and radius bound the
 * shadow casters and receivers (used by directional lights only; may be
 * NULL / 0 otherwise); znear: the light views' near plane (0: the default
 * LUMO_RASTER_SHADOW_ZNEAR). LUMO_ERR_ARG / LUMO_ERR_RANGE on bad input. */
lumo_status lumo_raster_shadow_init(lumo_raster_shadow *sh, const lumo_raster_light *l,
                                    uint16_t size, uint16_t *depth, size_t bytes,
                                    const lumo_q16_16 centre[3], lumo_q16_16 radius,
                                    lumo_q16_16 znear);

/* The light's views only (sh->depth NULL, nothing to draw into): for a
 * renderer that keeps the depth itself (the GL backends draw their own maps
 * from these very views, lumo/raster_gl.h). Arguments and errors as
 * lumo_raster_shadow_init. */
lumo_status lumo_raster_shadow_views(lumo_raster_shadow *sh, const lumo_raster_light *l, uint16_t size,
                                     const lumo_q16_16 centre[3], lumo_q16_16 radius, lumo_q16_16 znear);

/* Add a mesh's triangles (both sides) to the map. Call for every mesh that
 * casts shadows after lumo_raster_shadow_init. Errors as lumo_raster_draw. */
lumo_status lumo_raster_shadow_draw(lumo_raster_shadow *sh, const lumo_raster_mesh *m);

/* Visibility of the light at p with unit normal n (turned towards the
 * light's side), 0 (shadow) .. 256 (lit). */
uint32_t lumo_raster_shadow_visibility(const lumo_raster_shadow *sh, const lumo_q16_16 p[3],
                                       const lumo_q1_14 n[3]);

/* ---- drawing ------------------------------------------------------------- */

/* Draw the mesh's triangles into the target's band. `cache` is the output of
 * lumo_raster_prepare for the same view, scene and mesh, or NULL (vertices are
 * then transformed per triangle: no memory, more work). The bytes drawn do
 * not depend on the band split nor on the cache.
 * Errors (nothing drawn): LUMO_ERR_ARG, LUMO_ERR_RANGE (a triangle index
 * >= vertex_count, a bad target, view size != target size). Uses about
 * 3.1 KB of stack on a Cortex-M3 (the clipped polygon's vertices of 76
 * bytes and the triangle, shading with the IVG; 3 160 bytes peak measured
 * on the board by tests/board/golden_raster.c) and no other memory. */
lumo_status lumo_raster_draw(const lumo_raster_view *v, const lumo_raster_scene *s,
                             const lumo_raster_mesh *m, const lumo_raster_vertex *cache,
                             lumo_raster_target *t);

/* Statistics of the last draw, for tests and benchmarks (optional). */
typedef struct lumo_raster_stats {
    uint32_t tris_in, tris_culled, tris_clipped, tris_drawn;   /* triangles: given, culled, clipped, drawn */
    uint32_t pixels_tested, pixels_written;   /* depth tests; pixels written */
} lumo_raster_stats;

lumo_status lumo_raster_draw_stats(const lumo_raster_view *v, const lumo_raster_scene *s,
                                   const lumo_raster_mesh *m, const lumo_raster_vertex *cache,
                                   lumo_raster_target *t, lumo_raster_stats *stats);

#endif /* LUMO_RASTER_H */
