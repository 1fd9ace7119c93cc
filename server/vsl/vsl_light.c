/* vsl_light.c — VSLs as diffuse surface elements (seed 004 §0.4.1,
 * §0.7.3; vsl_light.h). */
#include <math.h>
#include "vsl/vsl_light.h"

void srv_vsl_lit_fill(const srv_vsl_set *set, const srv_vsl_rt *rt, const srv_photon_tracer *t,
                      srv_vsl_lit *out)
{
    for (size_t i = 0; i < set->n; i++) {
        const srv_vsl *v = &set->v[i];
        const srv_pose *p = srv_vsl_rt_pose(rt, v->object);
        float f[3];
        srv_photon_vsl_flux(t, (uint32_t)i, f);
        out[i].pos = srv_pose_point(p, v->pos);
        out[i].normal = srv_pose_dir(p, v->normal);
        out[i].flux = v3(f[0], f[1], f[2]);
        out[i].area = v->area;
    }
}

float srv_vsl_cutoff2(const srv_vsl_lit *v, float eps)
{
    return v3_maxc(v3(fabsf(v->flux.x), fabsf(v->flux.y), fabsf(v->flux.z))) / ((float)M_PI * eps);
}

/* Phi cos' / (pi r^2 + dS') towards x, and the unit w from x to the VSL;
 * 0 behind the VSL or beyond its cut-off. */
static float element(const srv_vsl_lit *v, vec3 x, float eps, vec3 *w)
{
    vec3 d = v3_sub(v->pos, x);
    float r2 = v3_dot(d, d);
    if (!(r2 > 0.0f) || (eps > 0.0f && r2 > srv_vsl_cutoff2(v, eps)))
        return 0.0f;
    *w = v3_scale(d, 1.0f / sqrtf(r2));
    float cl = -v3_dot(v->normal, *w);
    return cl > 0.0f ? cl / ((float)M_PI * r2 + v->area) : 0.0f;
}

vec3 srv_vsl_irradiance(const srv_vsl_lit *v, size_t n, vec3 x, vec3 nrm, float eps)
{
    vec3 e = v3(0, 0, 0);
    for (size_t i = 0; i < n; i++) {
        vec3 w;
        float g = element(&v[i], x, eps, &w), c = g > 0.0f ? v3_dot(nrm, w) : 0.0f;
        if (c > 0.0f)
            e = v3_add(e, v3_scale(v[i].flux, g * c));
    }
    return e;
}

int srv_vsl_reaches(const srv_vsl_lit *v, vec3 p, float eps)
{
    vec3 d = v3_sub(v->pos, p);
    return v3_dot(d, d) <= srv_vsl_cutoff2(v, eps);
}

void srv_vsl_ivg_add(const srv_vsl_lit *v, double scale, vec3 p, double *I)
{
    vec3 w;
    double g = (double)element(v, p, 0.0f, &w) * scale;
    if (g == 0.0)
        return;
    for (int h = 0; h < 6; h++) {
        float along = v3_get(w, h / 2);
        if (h & 1 ? along >= 0.0f : along <= 0.0f)
            continue;
        for (int ch = 0; ch < 3; ch++) {
            double k = g * (double)v3_get(v->flux, ch);
            double *o = I + (h * 3 + ch) * 3;
            o[0] += k * w.x, o[1] += k * w.y, o[2] += k * w.z;
        }
    }
}
