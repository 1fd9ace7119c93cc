/* bench/raster_peers_mesh.h — the scene of the per-vertex comparison with tgx and
 * small3dlib (docs/benchmarks.md, "Round five"): dragon_48k.ply (ASCII)
 * fitted so its largest extent spans [-1, 1], area-weighted vertex normals
 * from the faces, one Lambert colour per vertex for one directional light.
 * Host-only harness code (floats allowed); the peers' harnesses, built
 * outside the repository, include this same file, so all draw one scene. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct hmesh {
    int nv, nt;
    float *p, *n, *col;   /* 3 per vertex; col in [0, 1] */
    unsigned *tri;
} hmesh;

#define H_W 640
#define H_H 480
#define H_FOVY 45.0
#define H_DIST 3.0
#define H_FRAMES 3
#define H_ALBEDO 0.8
/* the direction the light travels (normalised when used) */
static const double h_light[3] = {-0.4, -0.8, -0.45};

static void h_eye(int k, double e[3])
{
    double a = k * 120.0 * M_PI / 180.0;
    e[0] = H_DIST * sin(a);
    e[1] = 0;
    e[2] = H_DIST * cos(a);
}

static void h_load(const char *path, hmesh *m)
{
    FILE *f = fopen(path, "r");
    char line[256];
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30}, c[3], ext = 0, l[3], ll;
    int i, k;

    if (!f) { perror(path); exit(1); }
    m->nv = m->nt = 0;
    while (fgets(line, sizeof line, f)) {
        sscanf(line, "element vertex %d", &m->nv);
        sscanf(line, "element face %d", &m->nt);
        if (!strncmp(line, "end_header", 10)) break;
    }
    m->p = (float *)calloc(3 * m->nv, sizeof(float));
    m->n = (float *)calloc(3 * m->nv, sizeof(float));
    m->col = (float *)calloc(3 * m->nv, sizeof(float));
    m->tri = (unsigned *)calloc(3 * m->nt, sizeof(unsigned));
    for (i = 0; i < m->nv; i++) {
        if (fscanf(f, "%f %f %f", &m->p[3 * i], &m->p[3 * i + 1], &m->p[3 * i + 2]) != 3) exit(2);
        for (k = 0; k < 3; k++) {
            if (m->p[3 * i + k] < lo[k]) lo[k] = m->p[3 * i + k];
            if (m->p[3 * i + k] > hi[k]) hi[k] = m->p[3 * i + k];
        }
    }
    for (i = 0; i < m->nt; i++) {
        int cnt;
        if (fscanf(f, "%d %u %u %u", &cnt, &m->tri[3 * i], &m->tri[3 * i + 1], &m->tri[3 * i + 2]) != 4 || cnt != 3)
            exit(3);
    }
    fclose(f);
    for (k = 0; k < 3; k++) {
        c[k] = (lo[k] + hi[k]) / 2;
        if (hi[k] - lo[k] > ext) ext = hi[k] - lo[k];
    }
    for (i = 0; i < 3 * m->nv; i++)
        m->p[i] = (float)((m->p[i] - c[i % 3]) * 2 / ext);
    for (i = 0; i < m->nt; i++) {
        const float *a = &m->p[3 * m->tri[3 * i]], *b = &m->p[3 * m->tri[3 * i + 1]], *d = &m->p[3 * m->tri[3 * i + 2]];
        double u[3], v[3], x[3];
        for (k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = d[k] - a[k];
        x[0] = u[1] * v[2] - u[2] * v[1];
        x[1] = u[2] * v[0] - u[0] * v[2];
        x[2] = u[0] * v[1] - u[1] * v[0];
        for (k = 0; k < 9; k++)
            m->n[3 * m->tri[3 * i + k / 3] + k % 3] += (float)x[k % 3];
    }
    ll = sqrt(h_light[0] * h_light[0] + h_light[1] * h_light[1] + h_light[2] * h_light[2]);
    for (k = 0; k < 3; k++) l[k] = -h_light[k] / ll;
    for (i = 0; i < m->nv; i++) {
        float *n = &m->n[3 * i];
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]), d;
        if (len == 0) { n[0] = 0; n[1] = 1; n[2] = 0; len = 1; }
        for (k = 0; k < 3; k++) n[k] = (float)(n[k] / len);
        d = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        for (k = 0; k < 3; k++) m->col[3 * i + k] = (float)(H_ALBEDO * (d > 0 ? d : 0));
    }
}
