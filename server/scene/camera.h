/*
 * camera.h — the camera string EYE:TARGET:UP:FOVY shared by lumo-bake's
 * reference renderer and the desktop renderers (docs/scene-format.md,
 * "Camera": right-handed look-at, vertical field of view in degrees, pixel
 * rows from the top).
 */
#ifndef SRV_CAMERA_H
#define SRV_CAMERA_H

#include <stddef.h>
#include "common/vec3.h"
#include "lumo/status.h"

typedef struct srv_camera {
    vec3  eye, target, up;
    float fovy_deg;        /* vertical, in (0, 180) */
} srv_camera;

/* Parse "ex,ey,ez:tx,ty,tz:ux,uy,uz:fovy". LUMO_OK on success,
 * LUMO_ERR_ARG on a malformed, non-finite or degenerate camera (eye ==
 * target, up parallel to the view, fovy outside (0, 180)), LUMO_ERR_LIMIT
 * when the text is longer than 255 characters. */
lumo_status srv_camera_parse(const char *text, srv_camera *out);

/* The same, with the reason of a refusal in why (whylen bytes, may be 0):
 * which field is malformed, "eye and target are the same point", "up is
 * parallel to the view direction", the field of view's range. */
lumo_status srv_camera_parse_why(const char *text, srv_camera *out, char *why, size_t whylen);

/* Unit direction of the ray through image position (px, py) in pixels
 * (px in [0, w), py in [0, h), row 0 at the top; a pixel's centre is +0.5). */
vec3 srv_camera_ray(const srv_camera *c, int w, int h, float px, float py);

/* The default scene's camera: 0,1,3.4:0,1,0:0,1,0:40. */
srv_camera srv_camera_default(void);

/* A camera that frames the axis-aligned box lo..hi (metres) in any frame at
 * least as wide as it is tall: the client SDK's own fit
 * (lumo_scene_camera_fit, docs/scene-format.md "Fitted camera"), so a
 * client that refits gets the same camera. LUMO_ERR_RANGE for a box outside
 * the clients' Q16.16 range (|coordinate| < 32768 m) or lo > hi. */
lumo_status srv_camera_fit(vec3 lo, vec3 hi, srv_camera *out);

/* Render-friendly text of a camera, "ex,ey,ez:tx,ty,tz:ux,uy,uz:fovy"
 * (what --camera takes), into buf. */
void srv_camera_format(const srv_camera *c, char *buf, size_t len);

#endif
