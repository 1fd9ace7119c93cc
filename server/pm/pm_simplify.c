/* pm_simplify.c — half-edge collapse ordered by the quadric error metric
 * (Garland & Heckbert 1997), seed 000 §4.2: "we simply collapse the edge
 * onto one of its end vertices". A collapse u -> v removes u and the faces
 * on edge (u, v); u's other faces take v. Guards keep every level a valid
 * manifold-where-it-was mesh: the link condition, no face flip, no
 * duplicate face, no orphaned vertex; boundary vertices only slide along
 * the boundary, vertices on non-manifold edges never move.
 *
 * Collapses run in independent-set rounds (Pajarola & Rossignac's CPM,
 * Hoppe's independent splits): each round takes the cheapest valid
 * candidates whose neighbourhoods do not interact, so the splits of one
 * round commute and the stream may send them sorted by parent, which makes
 * the lookup-table entries an increasing, cheaply coded sequence. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "common/closest.h"
#include "pm/pm_internal.h"

typedef struct { uint32_t *f; uint32_t n, cap; } flist;

/* A candidate u -> v at its cost; su, sv the stamps it was priced at
 * (run_single); bad: it failed the guards, which read only the faces
 * around u and v, so it stays invalid until a round touches u or v; full:
 * the cost includes the surface term (surface_dev2, priced only when the
 * candidate is about to be taken); moved: that raised its cost, so it is
 * out of its place in the sorted round list. */
typedef struct { double cost; uint32_t u, v, su, sv; uint8_t bad, full, moved; } cand;

typedef struct {
    const float *xyz;
    uint32_t     nv, nf;
    const uint32_t *in_tri;  /* the input faces, never changed */
    uint32_t    *in_off, *in_face; /* the input faces around each input vertex: in_face[in_off[x] ..] */
    uint32_t    *in_seen, seen_stamp; /* surface_dev2's scratch: the input faces it listed */
    uint32_t    *near, near_cap; /* those faces */
    uint32_t    *tri;        /* current corners */
    uint8_t     *face_alive, *vert_alive;
    flist       *vf;         /* alive faces around each vertex */
    double      *q;          /* QN per vertex: symmetric 4x4 quadric, then its weight */
    uint32_t    *stamp;
    uint32_t    *core, *ring; /* round locks: u or v of a collapse, their neighbours */
    cand        *heap;
    size_t       hn, hcap;
    cand        *merge;      /* collect_round's scratch, hcap entries */
    uint32_t    *touched_list, touched_n; /* the vertices the last round locked, once each */
    uint32_t    *nb_u, *nb_v; /* neighbour scratch */
    uint32_t    *pt_head, *pt_next; /* the input vertices attached to each alive face (the
                                       nearest of the faces that replaced theirs): a list
                                       from pt_head[f] through pt_next */
    uint32_t    *moved, moved_cap;  /* apply_collapse's scratch: the points it re-attaches */
    uint32_t     nb_cap;
    const srv_pm_options *opt;
    double       limit;      /* largest cost a collapse may have (max_error) */
    double       flip_cos;   /* faces_ok's bound: opt->flip_cos, then (past
                                max_error, to the seed) SEED_FLIP_COS */
} simp;

/* ---- small vector helpers ------------------------------------------------ */
static void sub3(const float *a, const float *b, double r[3])
{
    r[0] = (double)a[0] - b[0], r[1] = (double)a[1] - b[1], r[2] = (double)a[2] - b[2];
}
static void cross3(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void normal_of(const float *a, const float *b, const float *c, double n[3])
{
    double e1[3], e2[3];
    sub3(b, a, e1);
    sub3(c, a, e2);
    cross3(e1, e2, n);
}

static int flist_push(flist *l, uint32_t f)
{
    if (l->n == l->cap) {
        uint32_t cap = l->cap ? 2 * l->cap : 8;
        uint32_t *p = realloc(l->f, sizeof *p * cap);
        if (!p)
            return -1;
        l->f = p, l->cap = cap;
    }
    l->f[l->n++] = f;
    return 0;
}

static void flist_remove(flist *l, uint32_t f)
{
    for (uint32_t i = 0; i < l->n; i++)
        if (l->f[i] == f) {
            l->f[i] = l->f[--l->n];
            return;
        }
}

static int has_vertex(const simp *s, uint32_t f, uint32_t v)
{
    const uint32_t *t = s->tri + 3 * (size_t)f;
    return t[0] == v || t[1] == v || t[2] == v;
}

/* ---- quadrics ----------------------------------------------------------- */
#define QN 11  /* 10 coefficients of the symmetric 4x4 matrix, then the weight sum */

/* Add w * (n.p + d)^2 for the plane through p0 with unit normal n. */
static void quadric_add(double *q, const double n[3], const float *p0, double w)
{
    double d = -(n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2]);
    double a = n[0], b = n[1], c = n[2];
    q[0] += w * a * a, q[1] += w * a * b, q[2] += w * a * c, q[3] += w * a * d;
    q[4] += w * b * b, q[5] += w * b * c, q[6] += w * b * d;
    q[7] += w * c * c, q[8] += w * c * d, q[9] += w * d * d;
    q[10] += w;
}

/* The quadric's weighted sum of squared plane distances at p. */
static double quadric_sum(const double *e, const float *p)
{
    double x = p[0], y = p[1], z = p[2];
    double r = e[0] * x * x + 2 * e[1] * x * y + 2 * e[2] * x * z + 2 * e[3] * x
             + e[4] * y * y + 2 * e[5] * y * z + 2 * e[6] * y + e[7] * z * z + 2 * e[8] * z + e[9];
    return r > 0 ? r : 0;  /* rounding */
}

/* The mean squared distance of p from the planes u gathered (u's quadric
 * over its weight): the quadric of the vertex that moves only, normalised
 * so that big and small triangles compare by distance, not by area times
 * distance (as meshoptimizer does; Garland & Heckbert's Q_u + Q_v counted
 * v's own accumulated error into every candidate of v, and area weighting
 * let small faces travel far: both cost worst-case error, bench-pm-quality). */
static double quadric_error(const double *q, const float *p)
{
    return q[10] > 0 ? quadric_sum(q, p) / q[10] : 0;
}

/* Faces alive around both u and v. */
#define MAX_EDGE_FACES 8  /* faces on one (non-manifold) edge a collapse may remove */

static uint32_t edge_faces(const simp *s, uint32_t u, uint32_t v, uint32_t out[MAX_EDGE_FACES])
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->vf[u].n; i++) {
        uint32_t f = s->vf[u].f[i];
        if (has_vertex(s, f, v)) {
            if (n < MAX_EDGE_FACES)
                out[n] = f;
            n++;
        }
    }
    return n;
}

/* Plane quadrics of every face (area weighted) plus, for boundary edges, a
 * perpendicular plane weighted by boundary_weight * |e|^2: boundaries are
 * penalised rather than frozen. */
static void init_quadrics(simp *s)
{
    for (uint32_t f = 0; f < s->nf; f++) {
        const uint32_t *t = s->tri + 3 * (size_t)f;
        const float *p[3] = {s->xyz + 3 * (size_t)t[0], s->xyz + 3 * (size_t)t[1], s->xyz + 3 * (size_t)t[2]};
        double n[3], len;
        normal_of(p[0], p[1], p[2], n);
        len = sqrt(dot3(n, n));
        if (len <= 0)
            continue;
        double un[3] = {n[0] / len, n[1] / len, n[2] / len};
        for (int c = 0; c < 3; c++)
            quadric_add(s->q + QN * (size_t)t[c], un, p[0], 0.5 * len);
        for (int c = 0; c < 3; c++) {
            uint32_t a = t[c], b = t[(c + 1) % 3], ef[MAX_EDGE_FACES];
            if (edge_faces(s, a, b, ef) != 1)
                continue;
            double e[3], bn[3];
            sub3(p[(c + 1) % 3], p[c], e);
            cross3(e, un, bn);
            double bl = sqrt(dot3(bn, bn));
            if (bl <= 0)
                continue;
            double ub[3] = {bn[0] / bl, bn[1] / bl, bn[2] / bl};
            quadric_add(s->q + QN * (size_t)a, ub, p[c], s->opt->boundary_weight * dot3(e, e));
            quadric_add(s->q + QN * (size_t)b, ub, p[c], s->opt->boundary_weight * dot3(e, e));
        }
    }
}

/* ---- neighbourhoods ------------------------------------------------------ */
static int grow_nb(simp *s, uint32_t need)
{
    if (need <= s->nb_cap)
        return 0;
    uint32_t cap = need * 2;
    uint32_t *a = realloc(s->nb_u, sizeof *a * cap);
    if (a)
        s->nb_u = a;
    uint32_t *b = realloc(s->nb_v, sizeof *b * cap);
    if (b)
        s->nb_v = b;
    if (!a || !b)
        return -1;
    s->nb_cap = cap;
    return 0;
}

/* Distinct neighbours of v, in first-seen order. */
static uint32_t neighbours(const simp *s, uint32_t v, uint32_t *out)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->vf[v].n; i++) {
        const uint32_t *t = s->tri + 3 * (size_t)s->vf[v].f[i];
        for (int c = 0; c < 3; c++) {
            uint32_t w = t[c], j = 0;
            if (w == v)
                continue;
            while (j < n && out[j] != w)
                j++;
            if (j == n)
                out[n++] = w;
        }
    }
    return n;
}

/* u's edges: how many have one face (border) and how many more than two
 * (non-manifold), and the last non-manifold neighbour. */
typedef struct { uint32_t border, nonmanifold, nm_neighbour; } edge_stats;

static edge_stats vertex_edges(const simp *s, uint32_t u, uint32_t *nb)
{
    edge_stats e = {0, 0, UINT32_MAX};
    uint32_t n = neighbours(s, u, nb), ef[MAX_EDGE_FACES];
    for (uint32_t i = 0; i < n; i++) {
        uint32_t k = edge_faces(s, u, nb[i], ef);
        e.border += k == 1;
        if (k > 2)
            e.nonmanifold++, e.nm_neighbour = nb[i];
    }
    return e;
}

/* ---- the guards ----------------------------------------------------------- */
static int in_list(const uint32_t *l, uint32_t n, uint32_t x)
{
    for (uint32_t i = 0; i < n; i++)
        if (l[i] == x)
            return 1;
    return 0;
}

static uint32_t opposite(const simp *s, uint32_t f, uint32_t u, uint32_t v)
{
    const uint32_t *t = s->tri + 3 * (size_t)f;
    for (int c = 0; c < 3; c++)
        if (t[c] != u && t[c] != v)
            return t[c];
    return UINT32_MAX;
}

/* Is c the third corner of a hole of three border edges u-v, v-c, c-u
 * (u -> v along the border edge closes it)? */
static int closes_hole(const simp *s, uint32_t u, uint32_t v, uint32_t c)
{
    uint32_t ef[MAX_EDGE_FACES];
    return edge_faces(s, u, c, ef) == 1 && edge_faces(s, v, c, ef) == 1;
}

/* Link condition: the common neighbours of u and v are exactly the
 * vertices opposite the edge, so the collapse keeps the surface's topology.
 * One exception: on a border edge, the third vertex of a hole of three
 * edges. The collapse then closes the hole (its two other edges become one
 * interior edge): the surface stays a manifold, one boundary loop fewer.
 * Without it each hole keeps three vertices for ever, and a mesh with a
 * hundred holes keeps hundreds (elephant-with-holes, bench-pm-quality). */
static int link_ok(simp *s, uint32_t u, uint32_t v, const uint32_t *ef, uint32_t ne)
{
    uint32_t nu = neighbours(s, u, s->nb_u), nv = neighbours(s, v, s->nb_v), common = 0, hole = 0;
    for (uint32_t i = 0; i < nu; i++) {
        uint32_t c = s->nb_u[i];
        if (!in_list(s->nb_v, nv, c))
            continue;
        common++;
        hole += ne == 1 && !has_vertex(s, ef[0], c) && closes_hole(s, u, v, c);
    }
    if (common != ne + hole || hole > 1)
        return 0;
    for (uint32_t i = 0; i < ne; i++) {
        uint32_t w = opposite(s, ef[i], u, v);
        if (!in_list(s->nb_v, nv, w) || s->vf[w].n <= 1)
            return 0;  /* w would lose its last face */
    }
    return 1;
}

/* u's surviving faces must not flip, degenerate, or duplicate a face of v. */
static int faces_ok(const simp *s, uint32_t u, uint32_t v)
{
    const float *pv = s->xyz + 3 * (size_t)v;
    for (uint32_t i = 0; i < s->vf[u].n; i++) {
        uint32_t f = s->vf[u].f[i];
        if (has_vertex(s, f, v))
            continue;
        const uint32_t *t = s->tri + 3 * (size_t)f;
        const float *p[3], *q[3];
        uint32_t other[2], no = 0;
        for (int c = 0; c < 3; c++) {
            p[c] = s->xyz + 3 * (size_t)t[c];
            q[c] = t[c] == u ? pv : p[c];
            if (t[c] != u)
                other[no++] = t[c];
        }
        double n0[3], n1[3];
        normal_of(p[0], p[1], p[2], n0);
        normal_of(q[0], q[1], q[2], n1);
        double l0 = sqrt(dot3(n0, n0)), l1 = sqrt(dot3(n1, n1));
        if (l1 <= 1e-12 * (l0 + 1e-30) || dot3(n0, n1) < s->flip_cos * l0 * l1)
            return 0;
        for (uint32_t j = 0; j < s->vf[v].n; j++) {
            uint32_t g = s->vf[v].f[j];
            if (has_vertex(s, g, other[0]) && has_vertex(s, g, other[1]))
                return 0;
        }
    }
    return 1;
}

/* Where u may go: a vertex on one non-manifold edge only along that edge
 * (all its faces vanish, which is how scans with fins and folds simplify);
 * a border vertex only along its border; a vertex with a tangled
 * neighbourhood (several non-manifold edges, or borders that are not one
 * simple fan) nowhere. */
static int direction_ok(simp *s, uint32_t u, uint32_t v, uint32_t ne)
{
    edge_stats e = vertex_edges(s, u, s->nb_u);
    if (e.nonmanifold > 1)
        return 0;
    if (e.nonmanifold == 1)
        return e.nm_neighbour == v && ne > 2;
    if (e.border != 0 && e.border != 2)
        return 0;
    return e.border == 0 || ne == 1;
}

static int collapse_ok(simp *s, uint32_t u, uint32_t v)
{
    uint32_t ef[MAX_EDGE_FACES];
    if (!s->vert_alive[u] || !s->vert_alive[v])
        return 0;
    uint32_t ne = edge_faces(s, u, v, ef);
    if (ne < 1 || ne > MAX_EDGE_FACES)
        return 0;
    if (grow_nb(s, 2 * (s->vf[u].n + s->vf[v].n) + 4))
        return 0;
    if (!direction_ok(s, u, v, ne))
        return 0;
    if (s->vf[u].n + s->vf[v].n <= 2 * ne)
        return 0;  /* v would be left without faces */
    return link_ok(s, u, v, ef, ne) && faces_ok(s, u, v);
}

/* ---- candidate heap (min on cost, then u, then v: deterministic) -------- */
static int cand_less(const cand *a, const cand *b)
{
    if (a->cost != b->cost)
        return a->cost < b->cost;
    if (a->u != b->u)
        return a->u < b->u;
    return a->v < b->v;
}

static int cand_cmp(const void *a, const void *b)
{
    return cand_less(a, b) ? -1 : cand_less(b, a);
}

/* Room for one more candidate; the candidate u -> v at today's cost. */
static int heap_room(simp *s)
{
    if (s->hn == s->hcap) {
        size_t cap = s->hcap ? 2 * s->hcap : 1024;
        cand *h = realloc(s->heap, sizeof *h * cap);
        if (h)
            s->heap = h;
        cand *m = realloc(s->merge, sizeof *m * cap);
        if (m)
            s->merge = m;
        if (!h || !m)
            return -1;
        s->hcap = cap;
    }
    return 0;
}

static void corner(const simp *s, uint32_t w, double out[3])
{
    const float *p = s->xyz + 3 * (size_t)w;
    out[0] = p[0], out[1] = p[1], out[2] = p[2];
}

/* Squared distance from input point x to the faces around v after u -> v,
 * or some value <= enough once one face is that near (the callers want
 * the largest of such distances: a point nearer than the largest so far
 * cannot change it). */
static double ring_dist2(const simp *s, uint32_t u, uint32_t v, const double x[3], double enough)
{
    double best = INFINITY;
    for (int side = 0; side < 2; side++) {
        uint32_t w = side ? v : u, other = side ? u : v;
        for (uint32_t i = 0; i < s->vf[w].n; i++) {
            uint32_t f = s->vf[w].f[i];
            if (has_vertex(s, f, other))
                continue;  /* on the edge: vanishes */
            const uint32_t *t = s->tri + 3 * (size_t)f;
            double c[3][3];
            for (int k = 0; k < 3; k++)
                corner(s, t[k] == u ? v : t[k], c[k]);
            double d = srv_triangle_dist2(x, c[0], c[1], c[2]);
            if (d <= enough)
                return d;
            best = d < best ? d : best;
        }
    }
    return best;
}

/* The worst-case error of u -> v: the largest distance from the faces
 * around v after the collapse of the input vertices attached to u's faces
 * (every one of which changes or vanishes): an upper bound of their
 * distance to the new surface. Points attached to faces the collapse does
 * not touch keep their distance; so the bound holds for every input vertex
 * at every level, not only for those that collapsed into u (which left the
 * points near u's neighbours unguarded when those neighbours moved:
 * bench-pm-quality's Hausdorff). */
static double worst_dist2(const simp *s, uint32_t u, uint32_t v)
{
    double worst = 0;
    for (uint32_t i = 0; i < s->vf[u].n; i++) {
        uint32_t f = s->vf[u].f[i];
        double c[3][3];
        int keeps = !has_vertex(s, f, v);
        for (int k = 0; keeps && k < 3; k++)
            corner(s, s->tri[3 * (size_t)f + k] == u ? v : s->tri[3 * (size_t)f + k], c[k]);
        for (uint32_t x = s->pt_head[f]; x != UINT32_MAX; x = s->pt_next[x]) {
            double p[3];
            corner(s, x, p);
            /* its own face first: usually the nearest, and then enough */
            double d = keeps ? srv_triangle_dist2(p, c[0], c[1], c[2]) : INFINITY;
            if (d > worst)
                d = fmin(d, ring_dist2(s, u, v, p, worst));
            worst = d > worst ? d : worst;
        }
    }
    return worst;
}

/* List the input faces around input vertex x in s->near (once each). */
static int near_add(simp *s, uint32_t x, uint32_t *n)
{
    for (uint32_t i = s->in_off[x]; i < s->in_off[x + 1]; i++) {
        uint32_t g = s->in_face[i];
        if (s->in_seen[g] == s->seen_stamp)
            continue;
        if (*n == s->near_cap) {
            uint32_t cap = s->near_cap ? 2 * s->near_cap : 256;
            uint32_t *a = realloc(s->near, sizeof *a * cap);
            if (!a)
                return -1;
            s->near = a, s->near_cap = cap;
        }
        s->in_seen[g] = s->seen_stamp;
        s->near[(*n)++] = g;
    }
    return 0;
}

/* The input surface under u's faces: the input faces around the points
 * attached to them and around the corners of u's ring. Its count, or -1. */
static int64_t near_faces(simp *s, uint32_t u)
{
    uint32_t n = 0;
    s->seen_stamp++;
    for (uint32_t i = 0; i < s->vf[u].n; i++) {
        uint32_t f = s->vf[u].f[i];
        const uint32_t *t = s->tri + 3 * (size_t)f;
        for (int k = 0; k < 3; k++)
            if (near_add(s, t[k], &n))
                return -1;
        for (uint32_t x = s->pt_head[f]; x != UINT32_MAX; x = s->pt_next[x])
            if (near_add(s, x, &n))
                return -1;
    }
    return n;
}

/* Squared distance from p to the listed input faces, or some value <=
 * enough (as ring_dist2). */
static double near_dist2(const simp *s, uint32_t n, const double p[3], double enough)
{
    double best = INFINITY;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t *t = s->in_tri + 3 * (size_t)s->near[i];
        double c[3][3];
        for (int k = 0; k < 3; k++)
            corner(s, t[k], c[k]);
        double d = srv_triangle_dist2(p, c[0], c[1], c[2]);
        if (d <= enough)
            return d;
        best = d < best ? d : best;
    }
    return best;
}

/* The surface term of u -> v: how far the faces u hands to v stray from
 * the input surface, the largest squared distance of their centroids and
 * edge midpoints from the input faces under them (near_faces). The other
 * direction of the Hausdorff distance: the quadric averages the planes'
 * distances and the worst-case term measures input points, so a face
 * bridging a concave fold or cutting off a ridge was seen by neither
 * (bench-pm-quality: the bunny's ears). Costly, so priced only for a
 * candidate about to be taken (run_rounds, run_single). */
static double surface_dev2(simp *s, uint32_t u, uint32_t v)
{
    int64_t n = near_faces(s, u);
    if (n <= 0)
        return n < 0 ? INFINITY : 0;  /* out of memory: the candidate is refused, not taken blind */
    double worst = 0;
    for (uint32_t i = 0; i < s->vf[u].n; i++) {
        uint32_t f = s->vf[u].f[i];
        if (has_vertex(s, f, v))
            continue;
        const uint32_t *t = s->tri + 3 * (size_t)f;
        double c[3][3], p[3];
        for (int k = 0; k < 3; k++)
            corner(s, t[k] == u ? v : t[k], c[k]);
        for (int k = 0; k < 4; k++) {  /* the centroid, then the edge midpoints */
            for (int a = 0; a < 3; a++)
                p[a] = k == 0 ? (c[0][a] + c[1][a] + c[2][a]) / 3 : 0.5 * (c[k - 1][a] + c[k % 3][a]);
            double d = near_dist2(s, (uint32_t)n, p, worst);
            worst = d > worst ? d : worst;
        }
    }
    return worst;
}

/* Complete c's cost with the surface term; 1 if that raised it. */
static int price_fully(simp *s, cand *c)
{
    c->full = 1;
    double d = surface_dev2(s, c->u, c->v);
    if (d <= c->cost)
        return 0;
    c->cost = d;
    return 1;
}

/* The third corner c of a hole u-v-c of three border edges, if u -> v
 * runs along one of them and would close it; else UINT32_MAX. */
static uint32_t hole_corner(const simp *s, uint32_t u, uint32_t v)
{
    uint32_t ef[MAX_EDGE_FACES];
    if (edge_faces(s, u, v, ef) != 1)
        return UINT32_MAX;
    for (uint32_t i = 0; i < s->vf[u].n; i++) {
        const uint32_t *t = s->tri + 3 * (size_t)s->vf[u].f[i];
        for (int k = 0; k < 3; k++)
            if (t[k] != u && t[k] != v && !has_vertex(s, ef[0], t[k]) && closes_hole(s, u, v, t[k]))
                return t[k];
    }
    return UINT32_MAX;
}

/* Closing a hole covers it: the new surface there is about the hole's
 * inradius from the nearest original surface (its rim), which neither the
 * quadric nor the input vertices see. The squared inradius 2A/P of the
 * hole's triangle. */
static double hole_cost(const simp *s, uint32_t u, uint32_t v)
{
    uint32_t c = hole_corner(s, u, v);
    if (c == UINT32_MAX)
        return 0;
    const float *a = s->xyz + 3 * (size_t)u, *b = s->xyz + 3 * (size_t)v, *p = s->xyz + 3 * (size_t)c;
    double n[3], e[3][3];
    normal_of(a, b, p, n);
    sub3(b, a, e[0]), sub3(p, b, e[1]), sub3(a, p, e[2]);
    double per = sqrt(dot3(e[0], e[0])) + sqrt(dot3(e[1], e[1])) + sqrt(dot3(e[2], e[2]));
    double r = per > 0 ? sqrt(dot3(n, n)) / per : 0;  /* |n| = 2A */
    return r * r;
}

/* The quadric's share of the cost: the cost is the largest of this times
 * the quadric's mean squared plane distance, the worst-case term and the
 * surface term (both largest squared distances, measured). The quadric
 * still orders where those agree (flat regions, creases); at full weight
 * it overruled them where a mean of accumulated planes says more than the
 * surface does. Measured on bench-pm-quality's seven meshes (levels worse
 * than meshoptimizer, RMS or Hausdorff, of 42): weight 1: 2, 0.5: 2, 0.4:
 * 1, 0.35: 0, 0.3: 1, 0.25: 1; the geometric mean of the ratios 0.57 at 1,
 * 0.48-0.51 below 0.5. It also lets max_error (which the cost is held to)
 * speak for distances rather than for the plane mean: bases 0-25% lower. */
#define QUADRIC_WEIGHT 0.35

static cand cand_make(const simp *s, uint32_t u, uint32_t v)
{
    double qe = QUADRIC_WEIGHT * quadric_error(s->q + QN * (size_t)u, s->xyz + 3 * (size_t)v);
    double h = fmax(worst_dist2(s, u, v), hole_cost(s, u, v));
    cand c = {qe > h ? qe : h, u, v, s->stamp[u], s->stamp[v], 0, 0, 0};
    return c;
}

/* A round's list: appended unordered, sorted once (collect_round). */
static int list_append(simp *s, uint32_t u, uint32_t v)
{
    if (heap_room(s))
        return -1;
    s->heap[s->hn++] = cand_make(s, u, v);
    return 0;
}

static int heap_insert(simp *s, cand c)
{
    if (heap_room(s))
        return -1;
    size_t i = s->hn++;
    while (i > 0 && cand_less(&c, &s->heap[(i - 1) / 2])) {
        s->heap[i] = s->heap[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    s->heap[i] = c;
    return 0;
}

static int heap_push(simp *s, uint32_t u, uint32_t v)
{
    return heap_insert(s, cand_make(s, u, v));
}

static cand heap_pop(simp *s)
{
    cand top = s->heap[0], last = s->heap[--s->hn];
    size_t i = 0;
    for (;;) {
        size_t l = 2 * i + 1, m = i;
        const cand *best = &last;
        if (l < s->hn && cand_less(&s->heap[l], best))
            m = l, best = &s->heap[l];
        if (l + 1 < s->hn && cand_less(&s->heap[l + 1], best))
            m = l + 1;
        if (m == i)
            break;
        s->heap[i] = s->heap[m];
        i = m;
    }
    if (s->hn)
        s->heap[i] = last;
    return top;
}

static int push_vertex_edges(simp *s, uint32_t v)
{
    if (grow_nb(s, 2 * s->vf[v].n + 2))
        return -1;
    uint32_t n = neighbours(s, v, s->nb_u);
    for (uint32_t i = 0; i < n; i++)
        if (heap_push(s, v, s->nb_u[i]) || heap_push(s, s->nb_u[i], v))
            return -1;
    return 0;
}

/* ---- the collapse --------------------------------------------------------- */
/* Detach the points of u's faces into s->moved; their count, or -1. */
static int64_t detach_points(simp *s, uint32_t u)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->vf[u].n; i++) {
        uint32_t f = s->vf[u].f[i];
        for (uint32_t x = s->pt_head[f]; x != UINT32_MAX; x = s->pt_next[x]) {
            if (n == s->moved_cap) {
                uint32_t cap = s->moved_cap ? 2 * s->moved_cap : 64;
                uint32_t *m = realloc(s->moved, sizeof *m * cap);
                if (!m)
                    return -1;
                s->moved = m, s->moved_cap = cap;
            }
            s->moved[n++] = x;
        }
        s->pt_head[f] = UINT32_MAX;
    }
    return n;
}

/* Attach each detached point to the nearest face around v. */
static void attach_points(simp *s, uint32_t v, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        uint32_t x = s->moved[i], best_f = s->vf[v].f[0];
        double p[3], best = INFINITY;
        corner(s, x, p);
        for (uint32_t j = 0; j < s->vf[v].n; j++) {
            const uint32_t *t = s->tri + 3 * (size_t)s->vf[v].f[j];
            double c[3][3];
            for (int k = 0; k < 3; k++)
                corner(s, t[k], c[k]);
            double d = srv_triangle_dist2(p, c[0], c[1], c[2]);
            if (d < best)
                best = d, best_f = s->vf[v].f[j];
        }
        s->pt_next[x] = s->pt_head[best_f];
        s->pt_head[best_f] = x;
    }
}

static int apply_collapse(simp *s, uint32_t u, uint32_t v, uint32_t step, srv_pm_collapses *out)
{
    int64_t moved = detach_points(s, u);
    if (moved < 0)
        return -1;
    for (uint32_t i = s->vf[u].n; i-- > 0;) {
        uint32_t f = s->vf[u].f[i];
        uint32_t *t = s->tri + 3 * (size_t)f;
        if (has_vertex(s, f, v)) {
            s->face_alive[f] = 0;
            out->face_die[f] = step;
            for (int c = 0; c < 3; c++)
                if (t[c] != u)
                    flist_remove(&s->vf[t[c]], f);
            continue;
        }
        for (int c = 0; c < 3; c++)
            if (t[c] == u)
                t[c] = v;
        if (flist_push(&s->vf[v], f))
            return -1;
    }
    s->vf[u].n = 0;
    s->vert_alive[u] = 0;
    attach_points(s, v, (uint32_t)moved);
    for (int i = 0; i < QN; i++)
        s->q[QN * (size_t)v + i] += s->q[QN * (size_t)u + i];
    s->stamp[v]++;
    out->removed[step] = u;
    out->target[step] = v;
    return 0;
}

static int push_all(simp *s)
{
    for (uint32_t v = 0; v < s->nv; v++)
        if (s->vert_alive[v] && push_vertex_edges(s, v))
            return -1;
    return 0;
}

/* One collapse at a time (round_fraction 0): pop candidates until none is
 * valid; a rejected candidate can become valid after its neighbourhood
 * changes, so the heap is refilled from every edge once it runs dry, until
 * a whole pass makes no progress. Every collapse is a round of its own. */
static int run_single(simp *s, srv_pm_collapses *out)
{
    uint32_t alive = s->nv - out->count, target = s->opt->min_vertices;
    for (int pass = 0; pass < 16 && alive > target; pass++) {
        uint32_t before = out->count;
        s->hn = 0;
        if (push_all(s))
            return -1;
        while (s->hn && alive > target) {
            cand c = heap_pop(s);
            if (c.cost > s->limit)
                break;  /* the cheapest left changes the shape */
            if (!s->vert_alive[c.u] || !s->vert_alive[c.v] || s->stamp[c.u] != c.su ||
                s->stamp[c.v] != c.sv || !collapse_ok(s, c.u, c.v))
                continue;
            if (!c.full && price_fully(s, &c)) {
                if (heap_insert(s, c))
                    return -1;
                continue;  /* back in its place */
            }
            if (apply_collapse(s, c.u, c.v, out->count, out) || push_vertex_edges(s, c.v))
                return -1;
            out->round[out->count] = out->count;
            out->count++;
            alive--;
        }
        if (out->count == before)
            break;
    }
    return 0;
}

/* May u -> v join round r? Neither end is a collapse end or a neighbour of
 * one already in the round, and no neighbour of u or v is a collapse end.
 * The round's collapses then touch disjoint faces, every guard of one reads
 * nothing another changes (a shared neighbour's faces only shrink, and
 * collapse_ok saw that in this order), so they commute: any order of any
 * subset is valid and gives the same faces. */
static int round_free(simp *s, uint32_t u, uint32_t v, uint32_t r)
{
    if (s->core[u] == r || s->core[v] == r || s->ring[u] == r || s->ring[v] == r)
        return 0;
    if (grow_nb(s, 2 * (s->vf[u].n + s->vf[v].n) + 4))
        return 0;
    uint32_t nu = neighbours(s, u, s->nb_u), nv = neighbours(s, v, s->nb_v);
    for (uint32_t i = 0; i < nu; i++)
        if (s->core[s->nb_u[i]] == r)
            return 0;
    for (uint32_t i = 0; i < nv; i++)
        if (s->core[s->nb_v[i]] == r)
            return 0;
    return 1;
}

/* Lock x for round r (ring or core), listing it once as touched. */
static void lock_one(simp *s, uint32_t *lock, uint32_t x, uint32_t r)
{
    if (s->core[x] != r && s->ring[x] != r)
        s->touched_list[s->touched_n++] = x;
    lock[x] = r;
}

static void round_lock(simp *s, uint32_t u, uint32_t v, uint32_t r)
{
    uint32_t nu = neighbours(s, u, s->nb_u), nv = neighbours(s, v, s->nb_v);
    for (uint32_t i = 0; i < nu; i++)
        lock_one(s, s->ring, s->nb_u[i], r);
    for (uint32_t i = 0; i < nv; i++)
        lock_one(s, s->ring, s->nb_v[i], r);
    lock_one(s, s->core, u, r);
    lock_one(s, s->core, v, r);
}

/* Did round r - 1 touch x (a collapse end or a neighbour of one)? Only
 * then can x's faces, quadric or input set have changed (round 1: all). */
static int touched(const simp *s, uint32_t x, uint32_t r)
{
    return r == 1 || s->core[x] == r - 1 || s->ring[x] == r - 1;
}

/* x's directed edges both ways, x touched by the last round; an edge to a
 * neighbour that was touched too is that neighbour's to list backwards. */
static int append_changed_edges(simp *s, uint32_t x, uint32_t r)
{
    if (grow_nb(s, 2 * s->vf[x].n + 2))
        return -1;
    uint32_t n = neighbours(s, x, s->nb_u);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t y = s->nb_u[i];
        if (list_append(s, x, y) || (!touched(s, y, r) && list_append(s, y, x)))
            return -1;
    }
    return 0;
}

/* Merge the sorted runs heap[0, kept) and heap[kept, hn). */
static void merge_runs(simp *s, size_t kept)
{
    size_t a = 0, b = kept, o = 0;
    while (a < kept && b < s->hn)
        s->merge[o++] = cand_less(&s->heap[b], &s->heap[a]) ? s->heap[b++] : s->heap[a++];
    while (a < kept)
        s->merge[o++] = s->heap[a++];
    while (b < s->hn)
        s->merge[o++] = s->heap[b++];
    cand *t = s->heap;
    s->heap = s->merge, s->merge = t;
}

/* The candidates of a round: every directed edge, cheapest first. An edge
 * neither of whose ends the last round touched keeps its cost and its
 * place (the worst-case term reads the input sets, so recomputing every
 * edge every round would cost the whole mesh per round); the edges of the
 * touched vertices are priced anew, sorted, and merged in: a round costs
 * the list's length plus what changed, so rounds may be small. */
static int collect_round(simp *s, uint32_t r)
{
    size_t kept = 0, nmoved = 0;
    for (size_t i = 0; r > 1 && i < s->hn; i++) {
        cand c = s->heap[i];
        if (!s->vert_alive[c.u] || !s->vert_alive[c.v] || touched(s, c.u, r) || touched(s, c.v, r))
            continue;
        if (c.moved)
            s->merge[nmoved++] = c;  /* re-sorted with the new ones */
        else
            s->heap[kept++] = c;
    }
    for (size_t i = 0; i < nmoved; i++)
        s->heap[kept + i] = s->merge[i], s->heap[kept + i].moved = 0;
    s->hn = kept + nmoved;
    uint32_t n = r == 1 ? s->nv : s->touched_n;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t x = r == 1 ? i : s->touched_list[i];
        if (s->vert_alive[x] && append_changed_edges(s, x, r))
            return -1;
    }
    s->touched_n = 0;
    qsort(s->heap + kept, s->hn - kept, sizeof *s->heap, cand_cmp);
    merge_runs(s, kept);
    return 0;
}

/* Independent-set rounds: each round walks the cheapest round_fraction of
 * the candidates (further only until one collapse is taken) and keeps
 * those that are valid and free of the round's locks. Ends when a whole
 * candidate list gives nothing. */
static int run_rounds(simp *s, srv_pm_collapses *out, uint32_t *round)
{
    uint32_t alive = s->nv - out->count, target = s->opt->min_vertices, r;
    for (r = *round + 1; alive > target; r++) {
        if (collect_round(s, r))
            return -1;
        size_t limit = (size_t)(s->opt->round_fraction * (double)s->hn), taken = 0;
        size_t last = limit < s->hn ? limit : s->hn - 1;  /* the walk's last candidate */
        for (size_t i = 0; i < s->hn && alive > target && (i < limit || !taken); i++) {
            uint32_t u = s->heap[i].u, v = s->heap[i].v;
            if (s->heap[i].cost > s->limit)
                break;  /* this one and all after it change the shape */
            if (s->heap[i].bad || !round_free(s, u, v, r))
                continue;
            if (!collapse_ok(s, u, v)) {
                s->heap[i].bad = 1;
                continue;
            }
            if (!s->heap[i].full && price_fully(s, &s->heap[i]) &&
                (s->heap[i].moved = 1, s->heap[i].cost > s->limit || s->heap[i].cost > s->heap[last].cost))
                continue;  /* beyond this round's walk: it waits for its place */
            round_lock(s, u, v, r);
            if (apply_collapse(s, u, v, out->count, out))
                return -1;
            out->round[out->count++] = r;
            alive--, taken++;
        }
        if (!taken)
            break;
    }
    *round = r;  /* the last round walked (it may have taken nothing) */
    return 0;
}

/* Past max_error no level is shown (the seed's levels only carry the base
 * mesh's vertices as splits), so a face may turn any way there; a
 * degenerate or duplicated face is still refused. Measured against
 * keeping flip_cos (0.2): bunny 4 853 -> 4 856 bytes, dragon 11k 17 124
 * -> 17 060, 48k 68 442 -> 68 397 (seeds of 4, 55 and 71 vertices instead
 * of 4, 72 and 81). */
#define SEED_FLIP_COS -1.0

/* The collapses within max_error, then (opt->seed) the rest, without the
 * limit, as far as the guards allow: the stream's base record carries the
 * mesh they leave (its seed) and their splits (docs/progressive-mesh.md
 * §2.3 "Base record"), so the base's vertices travel as splits (about 20
 * bits each) rather than as plain faces and coordinates, while the first
 * level shown is still the one within the bound. The extra collapses
 * start a new round; the bounded ones are exactly those without them. */
static int run(simp *s, srv_pm_collapses *out)
{
    uint32_t round = 0;
    for (int phase = 0; phase < 2; phase++) {
        if (phase && (!s->opt->seed || isinf(s->limit)))
            break;  /* no limit: every collapse was within it */
        if (phase) {
            s->limit = INFINITY;
            s->flip_cos = SEED_FLIP_COS;
        }
        if (s->opt->round_fraction > 0 ? run_rounds(s, out, &round) : run_single(s, out))
            return -1;
        if (!phase)
            out->bounded = out->count;
    }
    return 0;
}

static void simp_free(simp *s)
{
    if (s->vf)
        for (uint32_t v = 0; v < s->nv; v++)
            free(s->vf[v].f);
    free(s->vf);
    free(s->tri);
    free(s->face_alive);
    free(s->vert_alive);
    free(s->q);
    free(s->stamp);
    free(s->core);
    free(s->ring);
    free(s->heap);
    free(s->merge);
    free(s->touched_list);
    free(s->nb_u);
    free(s->nb_v);
    free(s->pt_head);
    free(s->pt_next);
    free(s->moved);
    free(s->in_off);
    free(s->in_face);
    free(s->in_seen);
    free(s->near);
}

/* The input faces around each input vertex (counting sort by vertex). */
static void index_inputs(simp *s)
{
    for (size_t i = 0; i < 3 * (size_t)s->nf; i++)
        s->in_off[s->in_tri[i] + 1]++;
    for (uint32_t x = 0; x < s->nv; x++)
        s->in_off[x + 1] += s->in_off[x];
    for (uint32_t f = 0; f < s->nf; f++)
        for (int k = 0; k < 3; k++) {
            uint32_t x = s->in_tri[3 * (size_t)f + k];
            s->in_face[s->in_off[x]++] = f;
        }
    for (uint32_t x = s->nv; x > 0; x--)  /* in_off[x] now ends x's run: shift back */
        s->in_off[x] = s->in_off[x - 1];
    s->in_off[0] = 0;
}

/* Every input vertex starts attached to its first face (distance 0). */
static void attach_inputs(simp *s)
{
    for (uint32_t x = 0; x < s->nv; x++) {
        uint32_t f = s->vf[x].f[0];  /* the cleaned mesh has no unused vertex */
        s->pt_next[x] = s->pt_head[f];
        s->pt_head[f] = x;
    }
}

/* max_error as a cost: the squared fraction of the bounding-box diagonal. */
static double error_limit(const srv_pm_clean_mesh *m, double max_error)
{
    if (max_error <= 0 || !m->nv)
        return INFINITY;
    double lo[3], hi[3], d2 = 0;
    for (int a = 0; a < 3; a++)
        lo[a] = hi[a] = m->xyz[a];
    for (uint32_t v = 1; v < m->nv; v++)
        for (int a = 0; a < 3; a++)
            lo[a] = fmin(lo[a], m->xyz[3 * (size_t)v + a]), hi[a] = fmax(hi[a], m->xyz[3 * (size_t)v + a]);
    for (int a = 0; a < 3; a++)
        d2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
    return max_error * max_error * d2;
}

lumo_status srv_pm_simplify(const srv_pm_clean_mesh *m, const srv_pm_options *opt,
                            srv_pm_collapses *out)
{
    simp s;
    memset(&s, 0, sizeof s);
    memset(out, 0, sizeof *out);
    size_t nv = m->nv ? m->nv : 1, nf = m->nf ? m->nf : 1;
    s.xyz = m->xyz, s.nv = m->nv, s.nf = m->nf, s.opt = opt;
    s.tri = malloc(sizeof *s.tri * 3 * nf);
    s.face_alive = malloc(nf);
    s.vert_alive = malloc(nv);
    s.vf = calloc(nv, sizeof *s.vf);
    s.q = calloc(QN * nv, sizeof *s.q);
    s.stamp = calloc(nv, sizeof *s.stamp);
    s.core = calloc(nv, sizeof *s.core);
    s.ring = calloc(nv, sizeof *s.ring);
    s.touched_list = malloc(sizeof *s.touched_list * nv);
    s.pt_head = malloc(sizeof *s.pt_head * nf);
    s.pt_next = malloc(sizeof *s.pt_next * nv);
    s.in_tri = m->tris;
    s.in_off = calloc(nv + 1, sizeof *s.in_off);
    s.in_face = malloc(sizeof *s.in_face * 3 * nf);
    s.in_seen = calloc(nf, sizeof *s.in_seen);
    out->round = malloc(sizeof *out->round * nv);
    out->removed = malloc(sizeof *out->removed * nv);
    out->target = malloc(sizeof *out->target * nv);
    out->face_die = malloc(sizeof *out->face_die * nf);
    lumo_status rc = LUMO_ERR_NOMEM;
    if (!s.tri || !s.face_alive || !s.vert_alive || !s.vf || !s.q || !s.stamp || !s.core || !s.ring || !s.touched_list || !s.pt_head || !s.pt_next || !s.in_off || !s.in_face || !s.in_seen ||
        !out->round || !out->removed || !out->target || !out->face_die)
        goto done;
    memcpy(s.tri, m->tris, sizeof *s.tri * 3 * (size_t)m->nf);
    memset(s.face_alive, 1, nf);
    memset(s.vert_alive, 1, nv);
    memset(s.pt_head, 0xff, sizeof *s.pt_head * nf);
    memset(out->face_die, 0xff, sizeof *out->face_die * nf);
    for (uint32_t f = 0; f < m->nf; f++)
        for (int c = 0; c < 3; c++)
            if (flist_push(&s.vf[s.tri[3 * (size_t)f + c]], f))
                goto done;
    attach_inputs(&s);
    index_inputs(&s);
    init_quadrics(&s);
    s.limit = error_limit(m, opt->max_error);
    s.flip_cos = opt->flip_cos;
    rc = run(&s, out) ? LUMO_ERR_NOMEM : LUMO_OK;   /* its helpers fail only to allocate */
done:
    simp_free(&s);
    if (rc)
        srv_pm_collapses_free(out);
    return rc;
}

void srv_pm_collapses_free(srv_pm_collapses *c)
{
    free(c->removed);
    free(c->target);
    free(c->round);
    free(c->face_die);
    memset(c, 0, sizeof *c);
}
