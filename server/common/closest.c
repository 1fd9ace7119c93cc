/* common/closest.c — closest point on a triangle by its Voronoi regions
 * (Ericson, Real-Time Collision Detection, §5.1.5). */
#include "common/closest.h"

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void sub(const double a[3], const double b[3], double r[3])
{
    r[0] = a[0] - b[0], r[1] = a[1] - b[1], r[2] = a[2] - b[2];
}

/* out = a + s (b - a) + t (c - a) */
static void blend(const double a[3], const double b[3], const double c[3], double s, double t, double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = a[i] + s * (b[i] - a[i]) + t * (c[i] - a[i]);
}

static void copy(const double a[3], double out[3]) { out[0] = a[0], out[1] = a[1], out[2] = a[2]; }

void srv_closest_on_triangle(const double p[3], const double a[3], const double b[3],
                             const double c[3], double out[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    sub(b, a, ab), sub(c, a, ac), sub(p, a, ap);
    double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return copy(a, out);
    sub(p, b, bp);
    double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return copy(b, out);
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return blend(a, b, c, d1 / (d1 - d3), 0, out);
    sub(p, c, cp);
    double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return copy(c, out);
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return blend(a, b, c, 0, d2 / (d2 - d6), out);
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        return blend(b, c, c, (d4 - d3) / ((d4 - d3) + (d5 - d6)), 0, out);
    double den = va + vb + vc;
    if (den <= 0)
        return copy(a, out);  /* degenerate: every region test failed only by rounding */
    blend(a, b, c, vb / den, vc / den, out);
}

double srv_triangle_dist2(const double p[3], const double a[3], const double b[3], const double c[3])
{
    double q[3], d[3];
    srv_closest_on_triangle(p, a, b, c, q);
    sub(p, q, d);
    return dot(d, d);
}
