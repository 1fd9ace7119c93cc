/*
 * ply-compare REF.ply LUMO.ply — checks lumo-draco-decode's dequantized PLY
 * against draco_decoder's (binary little-endian) PLY of the same stream:
 * same vertex and face counts, same face indices, positions within 1e-6 of
 * the bounding box, normals within 1e-6, integer properties exact.
 * Properties present in only one file (e.g. per-face tex coords) are
 * skipped. Exit status 0 when equal; prints the worst differences.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXP 32

typedef struct ply {
    int ascii;
    long nv, nf;
    int np;
    char name[MAXP][64];
    int size[MAXP];              /* 1 uchar, 4 float/int */
    int is_float[MAXP];
    int face_has_tex;            /* binary: list uchar float texcoord */
    double *v;                   /* nv * np */
    int *f;                      /* nf * 3 */
} ply;

static char *slurp(const char *path, long *len)
{
    FILE *fp = fopen(path, "rb");
    char *d;
    if (!fp)
        return NULL;
    fseek(fp, 0, SEEK_END);
    *len = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    d = malloc((size_t)*len + 1);
    if (!d || fread(d, 1, (size_t)*len, fp) != (size_t)*len)
        exit(2);
    d[*len] = 0;
    fclose(fp);
    return d;
}

static int load(const char *path, ply *p)
{
    long len, i, k;
    char *d = slurp(path, &len), *s, *body, line[256];
    int in_vertex = 0;
    if (!d || !(body = strstr(d, "end_header\n")))
        return -1;
    body += 11;
    memset(p, 0, sizeof *p);
    for (s = d; s < body;) {
        char *e = strchr(s, '\n');
        size_t n = (size_t)(e - s) < sizeof line - 1 ? (size_t)(e - s) : sizeof line - 1;
        char a[64], b[64], c[64];
        memcpy(line, s, n);
        line[n] = 0;
        s = e + 1;
        if (strstr(line, "format ascii"))
            p->ascii = 1;
        if (sscanf(line, "element %63s %63s", a, b) == 2) {
            in_vertex = !strcmp(a, "vertex");
            if (in_vertex)
                p->nv = atol(b);
            else
                p->nf = atol(b);
        } else if (in_vertex && sscanf(line, "property %63s %63s", a, b) == 2 && p->np < MAXP) {
            snprintf(p->name[p->np], sizeof p->name[0], "%s", b);
            p->is_float[p->np] = !strcmp(a, "float");
            p->size[p->np] = !strcmp(a, "uchar") ? 1 : 4;
            p->np++;
        } else if (!in_vertex && sscanf(line, "property list %63s %63s %63s", a, b, c) == 3 &&
                   !strcmp(c, "texcoord")) {
            p->face_has_tex = 1;
        }
    }
    p->v = malloc(sizeof(double) * (size_t)(p->nv * p->np + 1));
    p->f = malloc(sizeof(int) * (size_t)(p->nf * 3 + 1));
    if (p->ascii) {
        char *q = body;
        for (i = 0; i < p->nv * p->np; ++i)
            p->v[i] = strtod(q, &q);
        for (i = 0; i < p->nf; ++i) {
            if (strtol(q, &q, 10) != 3)
                return -1;
            for (k = 0; k < 3; ++k)
                p->f[3 * i + k] = (int)strtol(q, &q, 10);
        }
    } else {
        const unsigned char *q = (const unsigned char *)body;
        for (i = 0; i < p->nv; ++i)
            for (k = 0; k < p->np; ++k) {
                if (p->size[k] == 1) {
                    p->v[i * p->np + k] = *q;
                } else if (p->is_float[k]) {
                    float x;
                    memcpy(&x, q, 4);
                    p->v[i * p->np + k] = x;
                } else {
                    int x;
                    memcpy(&x, q, 4);
                    p->v[i * p->np + k] = x;
                }
                q += p->size[k];
            }
        for (i = 0; i < p->nf; ++i) {
            if (*q++ != 3)
                return -1;
            for (k = 0; k < 3; ++k, q += 4)
                memcpy(&p->f[3 * i + k], q, 4);
            if (p->face_has_tex) {
                int n = *q++;
                q += 4 * n;
            }
        }
    }
    return 0;
}

static int find(const ply *p, const char *name)
{
    int i;
    for (i = 0; i < p->np; ++i)
        if (!strcmp(p->name[i], name))
            return i;
    return -1;
}

int main(int argc, char **argv)
{
    ply r, l;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, ext = 0;
    double worst[MAXP] = {0};
    long i;
    int k, bad = 0;
    if (argc != 3 || load(argv[1], &r) || load(argv[2], &l)) {
        fprintf(stderr, "usage: ply-compare REF.ply LUMO.ply (unreadable input)\n");
        return 2;
    }
    if (r.nv != l.nv || r.nf != l.nf) {
        printf("counts differ: %ld/%ld vertices, %ld/%ld faces\n", r.nv, l.nv, r.nf, l.nf);
        return 1;
    }
    for (i = 0; i < 3 * r.nf; ++i)
        if (r.f[i] != l.f[i]) {
            printf("face index %ld differs\n", i / 3);
            return 1;
        }
    for (k = 0; k < 3; ++k) {
        int c = find(&r, k == 0 ? "x" : k == 1 ? "y" : "z");
        for (i = 0; c >= 0 && i < r.nv; ++i) {
            double v = r.v[i * r.np + c];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
        if (hi[k] - lo[k] > ext)
            ext = hi[k] - lo[k];
    }
    for (k = 0; k < r.np; ++k) {
        int c = find(&l, r.name[k]);
        double tol = r.is_float[k] ? (r.name[k][0] == 'n' ? 1e-6 : 1e-6 * ext) : 0;
        if (c < 0)
            continue;
        for (i = 0; i < r.nv; ++i) {
            double d = fabs(r.v[i * r.np + k] - l.v[i * l.np + c]);
            if (d > worst[k])
                worst[k] = d;
        }
        printf("%-6s max |diff| %.3g (tolerance %.3g)\n", r.name[k], worst[k], tol);
        if (worst[k] > tol)
            bad = 1;
    }
    return bad;
}
