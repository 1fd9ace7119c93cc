/*
 * gen_meshes — writes the generated conformance meshes into a directory:
 *
 *   sphere_uv.obj     UV sphere, positions + tex coords (seam at u = 0/1)
 *                     + smooth normals: tex-coord seams, normal prediction
 *   cube_seams.obj    cube with per-face normals and uvs: seams everywhere
 *   torus_color.ply   torus with normals and 8-bit RGB colours
 *   cornell.obj       open Cornell box (walls + two blocks), holes/boundaries
 *   nonmanifold.ply   fan of triangles around one edge + bowtie vertices
 *   small.obj         < 1000 faces with uvs and normals
 *   cloud.ply         points only (for point-cloud encoding)
 *   triangle.obj      one triangle; single.ply: one point (degenerate sizes)
 *   materials.obj     a sphere in three materials (+ materials.mtl): with
 *                     -metadata the encoder writes metadata and a material
 *                     attribute
 *
 *   gen-meshes OUTDIR
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static FILE *open_out(const char *dir, const char *name)
{
    char path[1024];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    f = fopen(path, "w");
    if (!f) {
        perror(path);
        exit(1);
    }
    return f;
}

/* UV sphere with `rings` x `segs`; the u = 1 column duplicates u = 0 in
 * texture space only, so positions stay shared and uvs split. */
static void sphere_obj(const char *dir, const char *name, int rings, int segs, double r)
{
    FILE *f = open_out(dir, name);
    int i, j;
    const double pi = 3.14159265358979323846;
    for (i = 0; i <= rings; ++i)
        for (j = 0; j < segs; ++j) {
            double th = pi * i / rings, ph = 2 * pi * j / segs;
            double x = sin(th) * cos(ph), y = cos(th), z = sin(th) * sin(ph);
            fprintf(f, "v %.6f %.6f %.6f\n", r * x, r * y + 0.1 * sin(3 * ph), r * z);
            fprintf(f, "vn %.6f %.6f %.6f\n", x, y, z);
        }
    for (i = 0; i <= rings; ++i)
        for (j = 0; j <= segs; ++j)
            fprintf(f, "vt %.6f %.6f\n", (double)j / segs, 1.0 - (double)i / rings);
    for (i = 0; i < rings; ++i)
        for (j = 0; j < segs; ++j) {
            int j1 = (j + 1) % segs;
            int a = i * segs + j + 1, b = i * segs + j1 + 1;
            int c = (i + 1) * segs + j + 1, d = (i + 1) * segs + j1 + 1;
            int ta = i * (segs + 1) + j + 1, tb = ta + 1;
            int tc = (i + 1) * (segs + 1) + j + 1, td = tc + 1;
            if (i != 0)
                fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", a, ta, a, b, tb, b, c, tc, c);
            if (i != rings - 1)
                fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", b, tb, b, d, td, d, c, tc, c);
        }
    fclose(f);
}

static void cube_obj(const char *dir)
{
    static const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                    {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    static const double n[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                                   {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    FILE *f = open_out(dir, "cube_seams.obj");
    int i, k, sub = 6;
    /* subdivided faces so every face has interior vertices */
    int base = 1, tbase = 1;
    for (i = 0; i < 6; ++i) {
        double p[4][3];
        for (k = 0; k < 4; ++k) {
            int v = faces[i][k];
            p[k][0] = (v >> 2) & 1;
            p[k][1] = (v >> 1) & 1;
            p[k][2] = v & 1;
        }
        for (k = 0; k <= sub; ++k) {
            int l;
            for (l = 0; l <= sub; ++l) {
                double s = (double)k / sub, t = (double)l / sub, q[3];
                int c;
                for (c = 0; c < 3; ++c)
                    q[c] = (1 - s) * (1 - t) * p[0][c] + s * (1 - t) * p[1][c] +
                           s * t * p[2][c] + (1 - s) * t * p[3][c];
                fprintf(f, "v %.6f %.6f %.6f\n", q[0], q[1], q[2]);
                fprintf(f, "vt %.6f %.6f\n", (i % 3) / 3.0 + s / 3.0, (i / 3) / 2.0 + t / 2.0);
            }
        }
        fprintf(f, "vn %.1f %.1f %.1f\n", n[i][0], n[i][1], n[i][2]);
        for (k = 0; k < sub; ++k) {
            int l;
            for (l = 0; l < sub; ++l) {
                int a = base + k * (sub + 1) + l, b = a + (sub + 1), c = b + 1, d = a + 1;
                int ta = tbase + k * (sub + 1) + l, tb = ta + (sub + 1), tc = tb + 1, td = ta + 1;
                fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", a, ta, i + 1, b, tb, i + 1, c, tc, i + 1);
                fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", a, ta, i + 1, c, tc, i + 1, d, td, i + 1);
            }
        }
        base += (sub + 1) * (sub + 1);
        tbase += (sub + 1) * (sub + 1);
    }
    fclose(f);
}

static void torus_ply(const char *dir, int nu, int nv)
{
    FILE *f = open_out(dir, "torus_color.ply");
    const double pi = 3.14159265358979323846, R = 1.0, r = 0.35;
    int i, j;
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex %d\n", nu * nv);
    fprintf(f, "property float x\nproperty float y\nproperty float z\n");
    fprintf(f, "property float nx\nproperty float ny\nproperty float nz\n");
    fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    fprintf(f, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", 2 * nu * nv);
    for (i = 0; i < nu; ++i)
        for (j = 0; j < nv; ++j) {
            double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
            double nx = cos(u) * cos(v), ny = sin(u) * cos(v), nz = sin(v);
            fprintf(f, "%.6f %.6f %.6f %.6f %.6f %.6f %d %d %d\n", (R + r * cos(v)) * cos(u),
                    (R + r * cos(v)) * sin(u), r * sin(v), nx, ny, nz,
                    (int)(127.5 + 127.5 * cos(3 * u)), (int)(127.5 + 127.5 * sin(2 * v)),
                    (i * 7 + j * 3) % 256);
        }
    for (i = 0; i < nu; ++i)
        for (j = 0; j < nv; ++j) {
            int a = i * nv + j, b = ((i + 1) % nu) * nv + j;
            int c = ((i + 1) % nu) * nv + (j + 1) % nv, d = i * nv + (j + 1) % nv;
            fprintf(f, "3 %d %d %d\n3 %d %d %d\n", a, b, c, a, c, d);
        }
    fclose(f);
}

static void quad(FILE *f, int *nv, const double p[4][3])
{
    int k;
    for (k = 0; k < 4; ++k)
        fprintf(f, "v %.6f %.6f %.6f\n", p[k][0], p[k][1], p[k][2]);
    fprintf(f, "f %d %d %d\nf %d %d %d\n", *nv + 1, *nv + 2, *nv + 3, *nv + 1, *nv + 3, *nv + 4);
    *nv += 4;
}

/* Cornell box: five walls (open front) and two boxes, each wall a grid. */
static void cornell_obj(const char *dir)
{
    FILE *f = open_out(dir, "cornell.obj");
    int nv = 0, w, i, j, n = 8;
    static const double walls[5][4][3] = {
        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},   /* floor */
        {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},   /* ceiling */
        {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},   /* back */
        {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},   /* left */
        {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};  /* right */
    for (w = 0; w < 5; ++w)
        for (i = 0; i < n; ++i)
            for (j = 0; j < n; ++j) {
                double q[4][3];
                int k, c;
                for (k = 0; k < 4; ++k) {
                    double s = (i + ((k == 1 || k == 2) ? 1 : 0)) / (double)n;
                    double t = (j + ((k >= 2) ? 1 : 0)) / (double)n;
                    for (c = 0; c < 3; ++c)
                        q[k][c] = (1 - s) * (1 - t) * walls[w][0][c] + s * (1 - t) * walls[w][1][c] +
                                  s * t * walls[w][2][c] + (1 - s) * t * walls[w][3][c];
                }
                quad(f, &nv, q);
            }
    for (w = 0; w < 2; ++w) {
        double x0 = w ? 0.55 : 0.15, z0 = w ? 0.5 : 0.2, s = 0.3, h = w ? 0.6 : 0.3;
        double q[4][3] = {{x0, h, z0}, {x0 + s, h, z0}, {x0 + s, h, z0 + s}, {x0, h, z0 + s}};
        quad(f, &nv, q);
        for (i = 0; i < 4; ++i) {
            double a[3] = {x0 + (i == 1 || i == 2) * s, 0, z0 + (i >= 2) * s};
            double b[3] = {x0 + (i == 0 || i == 1) * s, 0, z0 + (i == 1 || i == 2) * s};
            double side[4][3] = {{a[0], 0, a[2]}, {b[0], 0, b[2]}, {b[0], h, b[2]}, {a[0], h, a[2]}};
            quad(f, &nv, side);
        }
    }
    fclose(f);
}

/* Non-manifold: three triangles on one edge, two fans joined at one vertex,
 * plus a regular strip so the mesh is not trivial. */
static void nonmanifold_ply(const char *dir)
{
    FILE *f = open_out(dir, "nonmanifold.ply");
    int nvx = 40, i, nf = 0;
    char faces[65536];
    size_t len = 0;
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex %d\n", 6 + 2 * nvx);
    fprintf(f, "property float x\nproperty float y\nproperty float z\n");
    for (i = 0; i < nvx - 1; ++i) {
        int a = 6 + 2 * i, b = a + 1, c = a + 2, d = a + 3;
        len += (size_t)snprintf(faces + len, sizeof faces - len, "3 %d %d %d\n3 %d %d %d\n", a, c, b, b, c, d);
        nf += 2;
    }
    len += (size_t)snprintf(faces + len, sizeof faces - len,
                            "3 0 1 2\n3 1 0 3\n3 0 1 4\n3 0 4 5\n3 6 0 7\n3 0 2 %d\n", 6 + 2 * nvx - 1);
    nf += 6;
    fprintf(f, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", nf);
    fprintf(f, "0 0 0\n1 0 0\n0.5 1 0\n0.5 -1 0\n0.5 0 1\n-0.5 0.3 1.2\n");
    for (i = 0; i < nvx; ++i)
        fprintf(f, "%.4f %.4f %.4f\n%.4f %.4f %.4f\n", 2.0 + 0.1 * i, 0.0, 0.02 * i * i / nvx,
                2.0 + 0.1 * i, 0.5, 0.3 * sin(i * 0.4));
    fputs(faces, f);
    fclose(f);
}

static void cloud_ply(const char *dir, int n)
{
    FILE *f = open_out(dir, "cloud.ply");
    int i;
    unsigned s = 12345u;
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex %d\n", n);
    fprintf(f, "property float x\nproperty float y\nproperty float z\n");
    fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n");
    for (i = 0; i < n; ++i) {
        double p[3];
        int c;
        for (c = 0; c < 3; ++c) {
            s = s * 1103515245u + 12345u;
            p[c] = (s >> 8) / 16777216.0;
        }
        fprintf(f, "%.6f %.6f %.6f %d %d %d\n", p[0], p[1] * 2, p[2] - 0.5, (int)(p[0] * 255),
                (int)(p[1] * 255), i % 256);
    }
    fclose(f);
}

/* The UV sphere again, its faces split over three materials. */
static void materials_obj(const char *dir)
{
    FILE *m = open_out(dir, "materials.mtl"), *f, *src;
    char path[1024], line[256];
    int face = 0;
    fprintf(m, "newmtl red\nKd 1 0 0\nnewmtl green\nKd 0 1 0\nnewmtl blue\nKd 0 0 1\n");
    fclose(m);
    sphere_obj(dir, "materials_src.obj", 16, 24, 1.0);
    snprintf(path, sizeof path, "%s/materials_src.obj", dir);
    src = fopen(path, "r");
    f = open_out(dir, "materials.obj");
    if (!src)
        exit(1);
    fprintf(f, "mtllib materials.mtl\n");
    while (fgets(line, sizeof line, src)) {
        if (line[0] == 'f') {
            static const char *names[3] = {"red", "green", "blue"};
            if (face % 200 == 0)
                fprintf(f, "usemtl %s\n", names[(face / 200) % 3]);
            ++face;
        }
        fputs(line, f);
    }
    fclose(src);
    fclose(f);
    remove(path);
}

static void degenerate(const char *dir)
{
    FILE *f = open_out(dir, "triangle.obj");
    fprintf(f, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    fclose(f);
    f = open_out(dir, "single.ply");
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
               "property float z\nend_header\n0.5 0.25 -1\n");
    fclose(f);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: gen-meshes OUTDIR\n");
        return 2;
    }
    sphere_obj(argv[1], "sphere_uv.obj", 48, 64, 1.0);
    sphere_obj(argv[1], "small.obj", 14, 20, 0.5);
    cube_obj(argv[1]);
    torus_ply(argv[1], 60, 40);
    cornell_obj(argv[1]);
    nonmanifold_ply(argv[1]);
    cloud_ply(argv[1], 3000);
    materials_obj(argv[1]);
    degenerate(argv[1]);
    return 0;
}
