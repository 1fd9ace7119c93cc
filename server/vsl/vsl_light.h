/*
 * vsl_light.h — light from the VSLs (seed 004 §0.4.1): a VSL s of reflected
 * flux Phi_s is a diffuse surface element of area dS' (radiance
 * Phi_s / (pi dS') towards its front), so a surface point x receives
 *   E(x) = sum_s Phi_s cos(theta) cos(theta') / (pi r^2 + dS')
 * (the paper's L = sum Phi_s rho/pi cos cos' / (pi r^2) is rho/pi E), and a
 * grid vertex p gathers, per hemisphere delta (seed 000 §3.1),
 *   I_delta(p) = sum_{s: w.delta > 0} Phi_s cos(theta') w / (pi r^2 + dS').
 * dS' in the denominator is the on-axis irradiance of a disc of area dS'
 * (B dS' / (pi r^2 + dS')): the element stays finite at r -> 0, where a
 * point light would blow up into the spots §0.4.1 set out to remove.
 * No VSL visibility (§0.6: "we have decided not to take VSLs shadows into
 * account"). Contributions below the cut-off are dropped (§0.7.3):
 * Phi_max / (pi r^2) < eps, the radius of the paper's VSL spheres.
 */
#ifndef SRV_VSL_LIGHT_H
#define SRV_VSL_LIGHT_H

#include <stddef.h>
#include "vsl/vsl.h"
#include "vsl/vsl_photon.h"

#define SRV_VSL_EPSILON 1e-6f   /* §0.7.3 */

/* A VSL as it lights: world pose and watts. */
typedef struct srv_vsl_lit {
    vec3  pos, normal;   /* world */
    vec3  flux;          /* reflected flux, W per channel */
    float area;          /* dS', m^2 */
} srv_vsl_lit;

/* The set's VSLs posed by rt's object poses, with their pool flux. */
void srv_vsl_lit_fill(const srv_vsl_set *set, const srv_vsl_rt *rt, const srv_photon_tracer *t,
                      srv_vsl_lit *out);

/* Cut-off radius squared of a VSL: beyond, max Phi / (pi r^2) < eps. */
float srv_vsl_cutoff2(const srv_vsl_lit *v, float eps);

/* Indirect irradiance (W/m^2 per channel) at x, unit normal n. */
vec3 srv_vsl_irradiance(const srv_vsl_lit *v, size_t n, vec3 x, vec3 nrm, float eps);

/* 1 when p lies inside v's cut-off sphere (r^2 <= srv_vsl_cutoff2). */
int srv_vsl_reaches(const srv_vsl_lit *v, vec3 p, float eps);

/* Add scale * (one VSL's I_delta) at p into I (54 values: 6 hemispheres x
 * 3 channels x 3 components, the srv_bake_result order), no cut-off (the
 * caller picks the vertices); scale -1 takes a contribution back out
 * (vsl_ivg.h). */
void srv_vsl_ivg_add(const srv_vsl_lit *v, double scale, vec3 p, double *I);

#endif
