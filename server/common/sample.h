/* sample.h — direction sampling shared by the path tracer (bake/) and the
 * photon tracer (vsl/): an orthonormal basis about a unit axis, cosine-
 * weighted and uniform-cone directions. */
#ifndef SRV_SAMPLE_H
#define SRV_SAMPLE_H

#include <math.h>
#include "common/rng.h"
#include "common/vec3.h"

/* Two unit vectors completing the unit n to a right-handed basis. */
static inline void srv_basis(vec3 n, vec3 *b1, vec3 *b2)
{
    vec3 a = fabsf(n.x) > 0.5f ? v3(0, 1, 0) : v3(1, 0, 0);
    *b1 = v3_norm(v3_cross(a, n));
    *b2 = v3_cross(n, *b1);
}

/* Direction about n at polar cosine ct and azimuth phi. */
static inline vec3 srv_dir_about(vec3 n, float ct, float phi)
{
    vec3 b1, b2;
    float st = sqrtf(fmaxf(0.0f, 1.0f - ct * ct));
    srv_basis(n, &b1, &b2);
    return v3_norm(v3_add(v3_add(v3_scale(b1, st * cosf(phi)), v3_scale(b2, st * sinf(phi))),
                          v3_scale(n, ct)));
}

/* Cosine-weighted direction about the unit normal n (pdf cos / pi). The
 * arithmetic is the bake's since its first release: packages stay the same
 * bytes. */
static inline vec3 srv_cosine_dir(vec3 n, srv_rng *r)
{
    float u1 = srv_rng_float(r), u2 = srv_rng_float(r);
    float rad = sqrtf(u1), phi = 2.0f * (float)M_PI * u2;
    vec3 b1, b2;
    srv_basis(n, &b1, &b2);
    return v3_norm(v3_add(v3_add(v3_scale(b1, rad * cosf(phi)), v3_scale(b2, rad * sinf(phi))),
                          v3_scale(n, sqrtf(fmaxf(0.0f, 1.0f - u1)))));
}

/* Uniform direction in the cone of half-angle cosine cos_max about n
 * (cos_max = -1: the whole sphere). */
static inline vec3 srv_cone_dir(vec3 n, float cos_max, srv_rng *r)
{
    float u1 = srv_rng_float(r), u2 = srv_rng_float(r);
    return srv_dir_about(n, 1.0f - u1 * (1.0f - cos_max), 2.0f * (float)M_PI * u2);
}

#endif
