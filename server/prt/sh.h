/*
 * prt/sh.h — real spherical harmonics in double precision, the server side
 * of PRT (seed 003 §3.1.1; Sloan, Kautz & Snyder 2002 §3): basis
 * evaluation, projection of a spherical function, and the rotation matrix
 * of a band-limited function by quadrature (the double reference the
 * client's fixed-point rotation is tested against).
 *
 * Convention (the client's lumo/prt.h uses the same): order N holds bands
 * l = 0..N-1, N*N coefficients, index i = l*(l+1) + m, m = -l..l;
 *   y_l^0  = K_l^0 P_l^0(z)
 *   y_l^m  = sqrt(2) K_l^m P_l^m(z) cos(m phi)     m > 0
 *   y_l^-m = sqrt(2) K_l^m P_l^m(z) sin(m phi)     m > 0
 * K_l^m = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!), P_l^m without the
 * Condon-Shortley phase, phi measured from +x towards +y, z the polar axis.
 */
#ifndef SRV_SH_H
#define SRV_SH_H

#define SRV_SH_MAX_ORDER 6
#define SRV_SH_MAX_COEFFS (SRV_SH_MAX_ORDER * SRV_SH_MAX_ORDER)

/* y_i(d) for i < order*order; d need not be unit (it is normalised; a zero
 * vector gives the +z value). order in 1..SRV_SH_MAX_ORDER. */
void srv_sh_eval(int order, const double d[3], double *out);

/* The projection of f over the sphere, int f(s) y_i(s) ds, by Gauss-Legendre
 * in z (n_theta nodes) times n_phi uniform steps in phi: exact for a
 * band-limited f of degree < min(2*n_theta, n_phi) after the product with
 * y_i. out: order*order. */
typedef double (*srv_sh_fn)(void *ctx, const double d[3]);
void srv_sh_project(int order, srv_sh_fn f, void *ctx, int n_theta, int n_phi, double *out);

/* The clamped cosine max(z, 0) projected on band l (zonal, m = 0), exact:
 * 2 pi K_l^0 int_0^1 P_l(z) z dz. */
double srv_sh_clamped_cosine_zonal(int l);

/* The (order^2 x order^2, row-major) matrix R_sh with
 * coeffs(f o rot^-1) = R_sh coeffs(f), for the 3x3 row-major rotation rot
 * (a function turned by rot); block diagonal per band. */
void srv_sh_rotation(int order, const double rot[9], double *out);

/* Nodes and weights of n-point Gauss-Legendre on [-1, 1] (n <= 64). */
void srv_gauss_legendre(int n, double *x, double *w);

#endif
