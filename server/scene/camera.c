/* camera.c — parsing and primary rays of the shared camera convention
 * (docs/scene-format.md, "Camera"). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "scene/camera.h"
#include "scene/scene.h"

lumo_status srv_camera_parse(const char *text, srv_camera *out)
{
    char buf[256], *parts[4], *save = NULL;
    float v[4][3], fovy;
    int n = 0;

    if (!text)
        return LUMO_ERR_ARG;
    if (strlen(text) >= sizeof buf)
        return LUMO_ERR_LIMIT;
    strcpy(buf, text);
    for (char *p = strtok_r(buf, ":", &save); p; p = strtok_r(NULL, ":", &save)) {
        if (n == 4)
            return LUMO_ERR_ARG;
        parts[n++] = p;
    }
    if (n != 4)
        return LUMO_ERR_ARG;
    for (int i = 0; i < 3; i++)
        if (srv_parse_floats(parts[i], v[i], 3))
            return LUMO_ERR_ARG;
    if (srv_parse_floats(parts[3], &fovy, 1) || !(fovy > 0.0f && fovy < 180.0f))
        return LUMO_ERR_ARG;
    srv_camera c = {v3(v[0][0], v[0][1], v[0][2]), v3(v[1][0], v[1][1], v[1][2]),
                    v3(v[2][0], v[2][1], v[2][2]), fovy};
    vec3 f = v3_sub(c.target, c.eye);
    if (v3_len(f) <= 0.0f || v3_len(v3_cross(v3_norm(f), v3_norm(c.up))) < 1e-6f)
        return LUMO_ERR_ARG;
    *out = c;
    return LUMO_OK;
}

vec3 srv_camera_ray(const srv_camera *c, int w, int h, float px, float py)
{
    vec3 f = v3_norm(v3_sub(c->target, c->eye));
    vec3 r = v3_norm(v3_cross(f, c->up));
    vec3 u = v3_cross(r, f);
    float t = tanf(c->fovy_deg * (float)M_PI / 360.0f);
    float s = (2.0f * px / (float)w - 1.0f) * t * (float)w / (float)h;
    float q = (1.0f - 2.0f * py / (float)h) * t;
    return v3_norm(v3_add(f, v3_add(v3_scale(r, s), v3_scale(u, q))));
}

srv_camera srv_camera_default(void)
{
    srv_camera c = {{0, 1, 3.4f}, {0, 1, 0}, {0, 1, 0}, 40.0f};
    return c;
}
