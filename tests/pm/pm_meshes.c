/* pm_meshes.c — generated test meshes for the progressive-mesh checks:
 * closed sphere, open noisy grid (boundary), a Cornell-style box of
 * separate walls and a cube (several components), and a "scan" with every
 * defect of real scans (unwelded duplicates, holes, a non-manifold fin,
 * duplicate and degenerate faces, two components), and a sphere with many
 * small holes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "pm_meshes.h"

static void grow(pm_test_mesh *m, uint32_t nv, uint32_t nf)
{
    m->xyz = realloc(m->xyz, sizeof *m->xyz * 3 * (m->nv + nv + 1));
    m->tris = realloc(m->tris, sizeof *m->tris * 3 * (m->nf + nf + 1));
    if (!m->xyz || !m->tris)
        abort();
}

static uint8_t g_rgb[3] = {200, 200, 200};  /* albedo of new vertices */

static uint32_t vert(pm_test_mesh *m, double x, double y, double z)
{
    grow(m, 1, 0);
    if (m->rgb) {
        m->rgb = realloc(m->rgb, 3 * (size_t)(m->nv + 1));
        memcpy(m->rgb + 3 * (size_t)m->nv, g_rgb, 3);
    }
    m->xyz[3 * m->nv] = (float)x, m->xyz[3 * m->nv + 1] = (float)y, m->xyz[3 * m->nv + 2] = (float)z;
    return m->nv++;
}

static void tri(pm_test_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    grow(m, 0, 1);
    m->tris[3 * m->nf] = a, m->tris[3 * m->nf + 1] = b, m->tris[3 * m->nf + 2] = c;
    m->nf++;
}

static double noise(uint32_t i)
{
    i = (i ^ 61) ^ (i >> 16), i *= 9, i ^= i >> 4, i *= 0x27d4eb2d, i ^= i >> 15;
    return (double)(i % 1000) / 1000.0 - 0.5;
}

static void sphere(pm_test_mesh *m, int nu, int nv, double r, double cx)
{
    uint32_t top = vert(m, cx, 0, r), first = m->nv;
    for (int j = 1; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            double th = M_PI * j / nv, ph = 2 * M_PI * i / nu;
            double rr = r * (1 + 0.05 * noise((uint32_t)(j * nu + i)));
            vert(m, cx + rr * sin(th) * cos(ph), rr * sin(th) * sin(ph), rr * cos(th));
        }
    uint32_t bot = vert(m, cx, 0, -r);
    for (int i = 0; i < nu; i++) {
        uint32_t a = first + (uint32_t)i, b = first + (uint32_t)((i + 1) % nu);
        tri(m, top, a, b);
        uint32_t la = first + (uint32_t)((nv - 2) * nu + i), lb = first + (uint32_t)((nv - 2) * nu + (i + 1) % nu);
        tri(m, bot, lb, la);
    }
    for (int j = 0; j + 2 < nv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t a = first + (uint32_t)(j * nu + i), b = first + (uint32_t)(j * nu + (i + 1) % nu);
            uint32_t c = a + (uint32_t)nu, d = b + (uint32_t)nu;
            tri(m, a, c, d);
            tri(m, a, d, b);
        }
}

/* A subdivided quad: origin o, edge vectors u, v, n x n cells. */
static void quad(pm_test_mesh *m, const double o[3], const double u[3], const double v[3], int n,
                 double bump)
{
    uint32_t first = m->nv;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double s = (double)i / n, t = (double)j / n, h = bump * noise(first + (uint32_t)(j * (n + 1) + i));
            double nx = u[1] * v[2] - u[2] * v[1], ny = u[2] * v[0] - u[0] * v[2], nz = u[0] * v[1] - u[1] * v[0];
            vert(m, o[0] + s * u[0] + t * v[0] + h * nx, o[1] + s * u[1] + t * v[1] + h * ny,
                 o[2] + s * u[2] + t * v[2] + h * nz);
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t a = first + (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)(n + 1), d = c + 1;
            tri(m, a, b, d);
            tri(m, a, d, c);
        }
}

static void colour(uint8_t r, uint8_t g, uint8_t b)
{
    g_rgb[0] = r, g_rgb[1] = g, g_rgb[2] = b;
}

static void cornell(pm_test_mesh *m)
{
    m->rgb = malloc(3);
    const double O[3] = {0, 0, 0}, X[3] = {1, 0, 0}, Y[3] = {0, 1, 0}, Z[3] = {0, 0, 1};
    const double top[3] = {0, 1, 0}, back[3] = {0, 0, 1}, right[3] = {1, 0, 0};
    colour(190, 190, 190);
    quad(m, O, Z, X, 8, 0);         /* floor */
    quad(m, top, X, Z, 8, 0);       /* ceiling */
    quad(m, back, X, Y, 8, 0.01);   /* back wall */
    colour(160, 20, 20);
    quad(m, O, Y, Z, 8, 0);         /* left wall, red */
    colour(20, 150, 30);
    quad(m, right, Z, Y, 8, 0);     /* right wall, green */
    colour(230, 230, 230);
    /* A closed cube: six quads welded through shared positions. */
    const double c0[3] = {0.2, 0, 0.2}, c1[3] = {0.5, 0.3, 0.5};
    const double a[3] = {0.3, 0, 0}, b[3] = {0, 0.3, 0}, c[3] = {0, 0, 0.3};
    const double na[3] = {-0.3, 0, 0}, nb[3] = {0, -0.3, 0}, nc[3] = {0, 0, -0.3};
    quad(m, c0, b, a, 4, 0), quad(m, c0, a, c, 4, 0), quad(m, c0, c, b, 4, 0);
    quad(m, c1, na, nb, 4, 0), quad(m, c1, nc, na, 4, 0), quad(m, c1, nb, nc, 4, 0);
}

/* A closed box of six flat 4x4 quads welded through shared positions: its
 * base is its 8 corners and 12 triangles (issue 23: fewer changes the shape). */
static void box(pm_test_mesh *m)
{
    const double c0[3] = {0, 0, 0}, c1[3] = {1, 0.5, 0.25};
    const double a[3] = {1, 0, 0}, b[3] = {0, 0.5, 0}, c[3] = {0, 0, 0.25};
    const double na[3] = {-1, 0, 0}, nb[3] = {0, -0.5, 0}, nc[3] = {0, 0, -0.25};
    quad(m, c0, b, a, 4, 0), quad(m, c0, a, c, 4, 0), quad(m, c0, c, b, 4, 0);
    quad(m, c1, na, nb, 4, 0), quad(m, c1, nc, na, 4, 0), quad(m, c1, nb, nc, 4, 0);
}

/* A sphere with unwelded corners, holes, a fin on a non-manifold edge,
 * a duplicate and a degenerate face, plus a separate noisy patch. */
static void scan(pm_test_mesh *m)
{
    pm_test_mesh s = {0};
    sphere(&s, 24, 14, 1.0, 0);
    for (uint32_t f = 0; f < s.nf; f++) {
        if (f % 97 == 13)
            continue;  /* holes */
        uint32_t t[3];
        for (int c = 0; c < 3; c++) {
            const float *p = s.xyz + 3 * s.tris[3 * f + c];
            t[c] = vert(m, p[0], p[1], p[2]);  /* every corner its own vertex */
        }
        tri(m, t[0], t[1], t[2]);
    }
    const uint32_t *e = s.tris + 3 * 200;
    const float *p0 = s.xyz + 3 * e[0], *p1 = s.xyz + 3 * e[1];
    uint32_t a = vert(m, p0[0], p0[1], p0[2]), b = vert(m, p1[0], p1[1], p1[2]);
    uint32_t fin = vert(m, 1.5 * p0[0], 1.5 * p0[1], 1.5 * p0[2] + 0.1);
    tri(m, a, b, fin);                                   /* non-manifold fin */
    tri(m, m->tris[0], m->tris[1], m->tris[2]);          /* duplicate face */
    tri(m, m->tris[3], m->tris[3], m->tris[4]);          /* degenerate face */
    const double o[3] = {2, -1, -1}, u[3] = {1, 0, 0}, v[3] = {0, 1, 0};
    quad(m, o, u, v, 10, 0.05);
    free(s.xyz);
    free(s.tris);
}

/* Southern faces use copies of their vertices in another colour: the
 * equator becomes a colour seam the simplifier must keep. */
static void seam(pm_test_mesh *m)
{
    pm_test_mesh s = {0};
    sphere(&s, 24, 12, 1.0, 0);
    m->rgb = malloc(3);
    uint32_t *north = malloc(sizeof *north * s.nv), *south = malloc(sizeof *south * s.nv);
    for (uint32_t v = 0; v < s.nv; v++) {
        const float *p = s.xyz + 3 * v;
        colour(220, 180, 40), north[v] = vert(m, p[0], p[1], p[2]);
        colour(40, 90, 220), south[v] = vert(m, p[0], p[1], p[2]);
    }
    for (uint32_t f = 0; f < s.nf; f++) {
        const uint32_t *t = s.tris + 3 * f;
        double z = s.xyz[3 * t[0] + 2] + s.xyz[3 * t[1] + 2] + s.xyz[3 * t[2] + 2];
        const uint32_t *map = z < 0 ? south : north;
        tri(m, map[t[0]], map[t[1]], map[t[2]]);
    }
    free(north), free(south), free(s.xyz), free(s.tris);
}

/* A sphere with 40 holes: the fans of vertices spread over it (hexagonal
 * holes, the vertex itself dropped as unused) and single missing faces
 * (holes of three edges). Each hole that stayed open would keep three
 * vertices: the base is small only if holes close (issue 23). */
static void holes(pm_test_mesh *m)
{
    const int nu = 32, nv = 18;
    sphere(m, nu, nv, 1.0, 0);
    uint32_t kept = 0, first = 1;
    for (uint32_t f = 0; f < m->nf; f++) {
        int drop = f % 61 == 30;
        for (int c = 0; c < 3; c++) {
            uint32_t v = m->tris[3 * f + c];
            int j = v >= first ? (int)((v - first) / (uint32_t)nu) + 1 : 0, i = (int)((v - first) % (uint32_t)nu);
            drop |= v >= first && j < nv && j % 3 == 2 && i % 4 == (j % 2) * 2;
        }
        if (!drop)
            memmove(m->tris + 3 * kept++, m->tris + 3 * f, 3 * sizeof *m->tris);
    }
    m->nf = kept;
}

/* A sphere as marching cubes leaves one: every vertex on a line of a
 * lattice of step h, two of its coordinates on lattice planes (those of
 * the axes least along its normal), the third free. LATTICE streams copy
 * such coordinates from the ring (docs/progressive-mesh.md §2.3 step 5). */
static void voxel(pm_test_mesh *m)
{
    const double h = 2.0 / 28;
    sphere(m, 48, 26, 1.0, 0);
    for (uint32_t v = 0; v < m->nv; v++) {
        float *p = m->xyz + 3 * v;
        int free_axis = 0;
        for (int a = 1; a < 3; a++)
            free_axis = fabsf(p[a]) > fabsf(p[free_axis]) ? a : free_axis;
        for (int a = 0; a < 3; a++)
            if (a != free_axis)
                p[a] = (float)(h * floor(p[a] / h + 0.5));
    }
}

int pm_test_mesh_make(const char *name, pm_test_mesh *m)
{
    memset(m, 0, sizeof *m);
    if (!strcmp(name, "sphere"))
        sphere(m, 32, 18, 1.0, 0);
    else if (!strcmp(name, "grid")) {
        const double o[3] = {0, 0, 0}, u[3] = {1, 0, 0}, v[3] = {0, 1, 0};
        quad(m, o, u, v, 24, 0.03);
    } else if (!strcmp(name, "cornell"))
        cornell(m);
    else if (!strcmp(name, "seam"))
        seam(m);
    else if (!strcmp(name, "wall")) {
        const double o[3] = {0, 0, 0}, u[3] = {2, 0, 0}, v[3] = {0, 1, 0};
        quad(m, o, u, v, 8, 0);  /* flat, open: the base keeps its 4 corners */
    } else if (!strcmp(name, "box"))
        box(m);
    else if (!strcmp(name, "scan"))
        scan(m);
    else if (!strcmp(name, "holes"))
        holes(m);
    else if (!strcmp(name, "voxel"))
        voxel(m);
    else if (!strcmp(name, "tiny")) {
        sphere(m, 6, 4, 1.0, 0);
    } else
        return -1;
    return 0;
}

void pm_test_mesh_free(pm_test_mesh *m)
{
    free(m->xyz);
    free(m->rgb);
    free(m->tris);
    memset(m, 0, sizeof *m);
}
