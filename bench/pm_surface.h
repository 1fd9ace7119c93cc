/*
 * bench/pm_surface.h — distances between two triangle meshes for the
 * simplification benchmark (bench/pm_quality.c): closest-point queries
 * through Embree 3's BVH (rtcPointQuery), surface samples from a fixed seed.
 *
 * Units: the meshes' own (metres); the caller divides by the original's
 * bounding-box diagonal. Memory: pm_surface_open() copies nothing; the
 * positions and indices must outlive the surface.
 */
#ifndef LUMO_BENCH_PM_SURFACE_H
#define LUMO_BENCH_PM_SURFACE_H

#include <stddef.h>
#include <stdint.h>

typedef struct pm_surface pm_surface;

/* A BVH over nf triangles (3 indices each into xyz). NULL on failure. */
pm_surface *pm_surface_open(const float *xyz, const uint32_t *tris, uint32_t nf);
void        pm_surface_close(pm_surface *s);

/* Distance from point p to the surface. */
double pm_surface_distance(const pm_surface *s, const double p[3]);

/* One direction of the mesh distance: from `samples` points spread over
 * mesh A by area (xorshift from `seed`) plus every corner of A, to surface
 * B. *mean_sq: mean squared distance of the area samples; *max: the largest
 * distance of any sample or corner (the sampled one-sided Hausdorff). */
void pm_surface_one_sided(const float *xyz, const uint32_t *tris, uint32_t nf, const pm_surface *b,
                          uint32_t samples, uint64_t seed, double *mean_sq, double *max);

#endif
