/* camera.c — parsing and primary rays of the shared camera convention
 * (docs/scene-format.md, "Camera"). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "scene/camera.h"
#include "scene/scene.h"
#include "lumo/scene.h"

/* A refusal: the reason into why (when there is room), then st. */
static lumo_status refuse(lumo_status st, char *why, size_t whylen, const char *reason)
{
    if (whylen)
        snprintf(why, whylen, "%s", reason);
    return st;
}

lumo_status srv_camera_parse_why(const char *text, srv_camera *out, char *why, size_t whylen)
{
    static const char *const k_fields[3] = {"EYE is not x,y,z (finite numbers)",
                                            "TARGET is not x,y,z (finite numbers)",
                                            "UP is not x,y,z (finite numbers)"};
    char buf[256], *parts[4], *save = NULL;
    float v[4][3], fovy;
    int n = 0;

    if (!text)
        return refuse(LUMO_ERR_ARG, why, whylen, "no camera");
    if (strlen(text) >= sizeof buf)
        return refuse(LUMO_ERR_LIMIT, why, whylen, "longer than 255 characters");
    strcpy(buf, text);
    for (char *p = strtok_r(buf, ":", &save); p; p = strtok_r(NULL, ":", &save)) {
        if (n == 4)
            return refuse(LUMO_ERR_ARG, why, whylen, "more than 4 fields (EYE:TARGET:UP:FOVY)");
        parts[n++] = p;
    }
    if (n != 4)
        return refuse(LUMO_ERR_ARG, why, whylen, "not 4 fields EYE:TARGET:UP:FOVY");
    for (int i = 0; i < 3; i++)
        if (srv_parse_floats(parts[i], v[i], 3))
            return refuse(LUMO_ERR_ARG, why, whylen, k_fields[i]);
    if (srv_parse_floats(parts[3], &fovy, 1) || !(fovy > 0.0f && fovy < 180.0f))
        return refuse(LUMO_ERR_ARG, why, whylen, "FOVY must be a number of degrees above 0 and below 180");
    srv_camera c = {v3(v[0][0], v[0][1], v[0][2]), v3(v[1][0], v[1][1], v[1][2]),
                    v3(v[2][0], v[2][1], v[2][2]), fovy};
    vec3 f = v3_sub(c.target, c.eye);
    if (v3_len(f) <= 0.0f)
        return refuse(LUMO_ERR_ARG, why, whylen, "eye and target are the same point (no view direction)");
    if (v3_len(v3_cross(v3_norm(f), v3_norm(c.up))) < 1e-6f)
        return refuse(LUMO_ERR_ARG, why, whylen, "UP is zero or parallel to the view direction (eye to target)");
    *out = c;
    return LUMO_OK;
}

lumo_status srv_camera_parse(const char *text, srv_camera *out)
{
    return srv_camera_parse_why(text, out, NULL, 0);
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

/* Metres to Q16.16, refusing what the clients cannot hold. */
static int to_q16(float v, lumo_q16_16 *out)
{
    double q = nearbyint((double)v * 65536.0);
    if (!(q >= (double)INT32_MIN && q <= (double)INT32_MAX))
        return -1;
    *out = (lumo_q16_16)q;
    return 0;
}

static vec3 from_q16(const lumo_q16_16 v[3])
{
    return v3((float)v[0] / 65536.0f, (float)v[1] / 65536.0f, (float)v[2] / 65536.0f);
}

lumo_status srv_camera_fit(vec3 lo, vec3 hi, srv_camera *out)
{
    lumo_pkg_info info;
    lumo_status st;

    memset(&info, 0, sizeof info);
    for (int a = 0; a < 3; a++)
        if (to_q16(v3_get(lo, a), &info.bmin[a]) || to_q16(v3_get(hi, a), &info.bmax[a]))
            return LUMO_ERR_RANGE;
    if ((st = lumo_scene_camera_fit(&info, 1, 1)))
        return st;
    out->eye = from_q16(info.eye);
    out->target = from_q16(info.target);
    out->up = from_q16(info.up);
    out->fovy_deg = (float)info.fovy_deg / 65536.0f;
    return LUMO_OK;
}

void srv_camera_format(const srv_camera *c, char *buf, size_t len)
{
    snprintf(buf, len, "%g,%g,%g:%g,%g,%g:%g,%g,%g:%g", (double)c->eye.x, (double)c->eye.y,
             (double)c->eye.z, (double)c->target.x, (double)c->target.y, (double)c->target.z,
             (double)c->up.x, (double)c->up.y, (double)c->up.z, (double)c->fovy_deg);
}
