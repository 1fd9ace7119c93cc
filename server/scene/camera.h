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

#endif
