/* sh.c — real spherical harmonics (prt/sh.h): evaluation by the associated
 * Legendre recurrence, projection by Gauss-Legendre x uniform-phi quadrature,
 * rotation matrices by projecting the rotated basis (seed 003 §3.2 rotates
 * the lighting vector; this is the reference the client is tested against). */
#include <math.h>
#include <string.h>
#include "prt/sh.h"

/* K_l^m = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!). */
static double sh_k(int l, int m)
{
    double r = (2.0 * l + 1.0) / (4.0 * M_PI);
    for (int k = l - m + 1; k <= l + m; k++)
        r /= k;
    return sqrt(r);
}

/* q[l][m] = P_l^m(z) / sin^m(theta), no Condon-Shortley phase. */
static void legendre_q(int order, double z, double q[SRV_SH_MAX_ORDER][SRV_SH_MAX_ORDER])
{
    double qmm = 1.0;
    for (int m = 0; m < order; m++) {
        if (m > 0)
            qmm *= 2.0 * m - 1.0;
        q[m][m] = qmm;
        if (m + 1 < order)
            q[m + 1][m] = z * (2.0 * m + 1.0) * qmm;
        for (int l = m + 2; l < order; l++)
            q[l][m] = ((2.0 * l - 1.0) * z * q[l - 1][m] - (l + m - 1.0) * q[l - 2][m]) / (l - m);
    }
}

void srv_sh_eval(int order, const double d[3], double *out)
{
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double x = len > 0 ? d[0] / len : 0, y = len > 0 ? d[1] / len : 0, z = len > 0 ? d[2] / len : 1;
    double q[SRV_SH_MAX_ORDER][SRV_SH_MAX_ORDER];
    double re = 1.0, im = 0.0;   /* (x + iy)^m = sin^m(theta) e^{i m phi} */
    legendre_q(order, z, q);
    for (int m = 0; m < order; m++) {
        for (int l = m; l < order; l++) {
            double k = sh_k(l, m) * q[l][m];
            if (m == 0) {
                out[l * (l + 1)] = k;
                continue;
            }
            out[l * (l + 1) + m] = M_SQRT2 * k * re;
            out[l * (l + 1) - m] = M_SQRT2 * k * im;
        }
        double nre = re * x - im * y;
        im = re * y + im * x;
        re = nre;
    }
}

void srv_gauss_legendre(int n, double *x, double *w)
{
    for (int i = 0; i < n; i++) {
        double t = cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1.0, p1 = t;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
                p0 = p1, p1 = p2;
            }
            if (n == 1)
                p1 = t, p0 = 1.0;
            dp = n * (t * p1 - p0) / (t * t - 1.0);
            double dt = p1 / dp;
            t -= dt;
            if (fabs(dt) < 1e-16)
                break;
        }
        x[i] = t;
        w[i] = 2.0 / ((1.0 - t * t) * dp * dp);
    }
}

void srv_sh_project(int order, srv_sh_fn f, void *ctx, int n_theta, int n_phi, double *out)
{
    double gx[64], gw[64], y[SRV_SH_MAX_COEFFS];
    int nc = order * order;
    if (n_theta > 64)
        n_theta = 64;
    srv_gauss_legendre(n_theta, gx, gw);
    memset(out, 0, (size_t)nc * sizeof *out);
    for (int i = 0; i < n_theta; i++) {
        double z = gx[i], r = sqrt(fmax(0.0, 1.0 - z * z));
        for (int j = 0; j < n_phi; j++) {
            double phi = 2.0 * M_PI * (j + 0.5) / n_phi;
            double d[3] = {r * cos(phi), r * sin(phi), z};
            double v = f(ctx, d) * gw[i] * (2.0 * M_PI / n_phi);
            srv_sh_eval(order, d, y);
            for (int c = 0; c < nc; c++)
                out[c] += v * y[c];
        }
    }
}

double srv_sh_clamped_cosine_zonal(int l)
{
    /* int_0^1 P_l(z) z dz by 32-point Gauss-Legendre on [0, 1]: P_l(z) z is
     * a polynomial of degree l + 1 <= 63, so the rule is exact. */
    double gx[32], gw[32], s = 0.0;
    srv_gauss_legendre(32, gx, gw);
    for (int i = 0; i < 32; i++) {
        double z = 0.5 * (gx[i] + 1.0), p0 = 1.0, p1 = z;
        for (int k = 2; k <= l; k++) {
            double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
            p0 = p1, p1 = p2;
        }
        s += 0.5 * gw[i] * (l == 0 ? 1.0 : p1) * z;
    }
    return 2.0 * M_PI * sh_k(l, 0) * s;
}

typedef struct { const double *rot; int order, j; } rot_ctx;

void srv_sh_rotation(int order, const double rot[9], double *out)
{
    enum { NT = 12, NP = 24 };   /* exact for the degree <= 2 (order - 1) <= 10 products */
    double gx[NT], gw[NT], yi[SRV_SH_MAX_COEFFS], yj[SRV_SH_MAX_COEFFS];
    int nc = order * order;
    srv_gauss_legendre(NT, gx, gw);
    memset(out, 0, (size_t)nc * (size_t)nc * sizeof *out);
    for (int i = 0; i < NT; i++) {
        double z = gx[i], r = sqrt(fmax(0.0, 1.0 - z * z));
        for (int k = 0; k < NP; k++) {
            double phi = 2.0 * M_PI * (k + 0.5) / NP, w = gw[i] * 2.0 * M_PI / NP;
            double s[3] = {r * cos(phi), r * sin(phi), z}, b[3];
            for (int a = 0; a < 3; a++)   /* rot^T s: where s came from */
                b[a] = rot[a] * s[0] + rot[3 + a] * s[1] + rot[6 + a] * s[2];
            srv_sh_eval(order, s, yi);
            srv_sh_eval(order, b, yj);
            for (int p = 0; p < nc; p++)
                for (int q = 0; q < nc; q++)
                    out[p * nc + q] += w * yi[p] * yj[q];
        }
    }
}
