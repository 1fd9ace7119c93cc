/*
 * scene_convert.h — the server's scene model (server/scene/scene.h: srv_scene,
 * srv_light, srv_camera; floats, metres) into the fixed-point structures the
 * rasterizer draws (lumo/raster.h), and the camera and light strings of
 * docs/scene-format.md read by the server's own parsers (srv_camera_parse,
 * srv_light_parse). lumo-render and the rasterizer's unit tests meet scene
 * text and scene models only through here; package lights (lumo/scene.h)
 * take the same light rule (lumo_raster_light_from_pkg, lumo/raster.h).
 *
 * Desktop code: floats and heap. Fixed-point values are rounded to nearest
 * (host_q16, host_q14); powers saturate at the top of UQ16.16.
 */
#ifndef LUMO_HOST_SCENE_CONVERT_H
#define LUMO_HOST_SCENE_CONVERT_H

#include <stddef.h>
#include "lumo/raster.h"
#include "lumo/scene.h"
#include "lumo/status.h"
#include "mesh_build.h"
#include "scene/scene.h"

/* A server camera as the rasterizer's; znear is LUMO_RASTER_ZNEAR (0.01).
 * LUMO_ERR_RANGE when the field of view is outside the rasterizer's
 * [1, 179] degrees (the server accepts (0, 180)). */
lumo_status host_camera_from_srv(const srv_camera *c, lumo_raster_camera *out);

/* A server light as the rasterizer's: the fields a package would carry
 * (lumo_pkg_light), then lumo_raster_light_from_pkg. LUMO_OK, or
 * LUMO_ERR_NONFINITE (then *out is untouched). */
lumo_status host_light_from_srv(const srv_light *l, lumo_raster_light *out);

/* "EYE:TARGET:UP:FOVY" through srv_camera_parse, then host_camera_from_srv.
 * LUMO_OK; LUMO_ERR_ARG or LUMO_ERR_LIMIT from the parser (malformed,
 * degenerate, too long); LUMO_ERR_RANGE for a field of view outside
 * [1, 179]. *out is written only on success. */
lumo_status host_camera_from_string(const char *text, lumo_raster_camera *out);

/* "point:...", "spot:...", "directional:...", "area:..." through
 * srv_light_parse, then host_light_from_srv. LUMO_OK, or the parser's
 * status (LUMO_ERR_ARG, LUMO_ERR_LIMIT); *out is written only on success. */
lumo_status host_light_from_string(const char *text, lumo_raster_light *out);
/* The same with the parser's reason in err ("OPT 'TEXT': position needs 3
 * numbers, got 2", srv_light_parse_as); `opt` names the source ("--light"). */
lumo_status host_light_parse(const char *opt, const char *text, lumo_raster_light *out, char *err, size_t errlen);

/* A whole server scene into *out (initialised here; free it with
 * host_scene_free): every mesh appended in order, with area-weighted vertex
 * normals of its wound faces — vertices at one position share one normal,
 * so meshes an importer split into a vertex per corner (assimp's OBJ) shade
 * smooth — and vertices equal in position and albedo merged; every light;
 * the scene's camera. LUMO_OK, or with a one-line reason in err:
 * LUMO_ERR_LIMIT (more than LUMO_MAX_LIGHTS lights, or past UINT32_MAX / 3
 * vertices or triangles), LUMO_ERR_RANGE (a triangle indexes a missing
 * vertex; the camera's field of view), LUMO_ERR_NOMEM. */
lumo_status host_scene_from_srv(host_scene *out, const srv_scene *s, char *err, size_t errlen);

/* Aim s->camera for a width x height frame: the camera `view` (already
 * checked, e.g. by host_camera_from_string) when not NULL, else with `fit` one fitted to the
 * scene's bounds (lumo_scene_camera_fit), else the scene's own; then its
 * near plane from the bounds (lumo_raster_znear_for_box). LUMO_OK, or an
 * error with a one-line reason in err. */
lumo_status host_scene_aim(host_scene *s, const lumo_raster_camera *view, int fit, uint32_t width, uint32_t height,
                           char *err, size_t errlen);

#endif
