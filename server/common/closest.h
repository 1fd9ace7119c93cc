/*
 * common/closest.h — the point of a triangle closest to a point, in double
 * precision (the simplifier's worst-case error, the quality benchmark's
 * surface distances). Units: the caller's.
 */
#ifndef SRV_COMMON_CLOSEST_H
#define SRV_COMMON_CLOSEST_H

/* The point of triangle abc closest to p, into out; degenerate triangles
 * are handled (their closest edge or corner). */
void srv_closest_on_triangle(const double p[3], const double a[3], const double b[3],
                             const double c[3], double out[3]);

/* Squared distance from p to triangle abc. */
double srv_triangle_dist2(const double p[3], const double a[3], const double b[3], const double c[3]);

#endif
