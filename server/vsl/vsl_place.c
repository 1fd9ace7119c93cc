/* vsl_place.c — VSL distribution (seed 004 §0.4.2): random points on
 * triangles shrunk away from their edges, drawn by area with 10% extra
 * density, then the closest removed by Algorithm 1 until N_v remain. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "common/rng.h"
#include "vsl/vsl.h"

#define NONE UINT32_MAX

/* ---- Algorithm 1 ---------------------------------------------------------- */

typedef struct {
    float    d1, d2;   /* squared distances to V1, V2 (INFINITY when none) */
    uint32_t v1, v2;
} near2;

static float dist2(vec3 a, vec3 b)
{
    vec3 d = v3_sub(a, b);   /* a - b == -(b - a) exactly: symmetric */
    return v3_dot(d, d);
}

/* (d, j) before (e, k): nearest first, ties to the lower index. */
static int before(float d, uint32_t j, float e, uint32_t k)
{
    return d < e || (d == e && j < k);
}

static void find_two(const vec3 *p, const uint8_t *alive, size_t n, uint32_t i, near2 *q)
{
    q->d1 = q->d2 = INFINITY;
    q->v1 = q->v2 = NONE;
    for (uint32_t j = 0; j < n; j++) {
        if (j == i || !alive[j])
            continue;
        float d = dist2(p[i], p[j]);
        if (before(d, j, q->d1, q->v1)) {
            q->d2 = q->d1, q->v2 = q->v1;
            q->d1 = d, q->v1 = j;
        } else if (before(d, j, q->d2, q->v2)) {
            q->d2 = d, q->v2 = j;
        }
    }
}

/* The living point with the smallest (d_min1, d_min2) whose group keeps
 * another point; NONE when there is none. */
static uint32_t pick(const near2 *q, const uint8_t *alive, const uint32_t *group, const uint32_t *left,
                     size_t n)
{
    uint32_t best = NONE;
    for (uint32_t i = 0; i < n; i++) {
        if (!alive[i] || (group && left[group[i]] < 2))
            continue;
        if (best == NONE || q[i].d1 < q[best].d1 || (q[i].d1 == q[best].d1 && q[i].d2 < q[best].d2))
            best = i;
    }
    return best;
}

/* Points per group, indexed by group value (groups are < n here). */
static uint32_t *group_counts(const uint32_t *group, size_t n)
{
    uint32_t gmax = 0;
    for (size_t i = 0; group && i < n; i++)
        gmax = group[i] > gmax ? group[i] : gmax;
    uint32_t *left = calloc((size_t)gmax + 1, sizeof *left);
    for (size_t i = 0; left && group && i < n; i++)
        left[group[i]]++;
    return left;
}

/* The naive process Algorithm 1 is measured against (§0.4.2): every
 * removal recomputes every living removable point's two nearest distances
 * from scratch, O(n^2) each. The tests' oracle and the bench's peer. */
size_t srv_vsl_thin_naive(const vec3 *p, const uint32_t *group, size_t n, size_t keep, uint8_t *alive)
{
    size_t count = n;
    uint32_t *left = group_counts(group, n);
    if (!left)
        return (size_t)-1;
    memset(alive, 1, n);
    while (count > keep) {
        size_t best = n;
        float bd1 = INFINITY, bd2 = INFINITY;
        for (size_t i = 0; i < n; i++) {
            if (!alive[i] || (group && left[group[i]] < 2))
                continue;
            float d1 = INFINITY, d2 = INFINITY;
            for (size_t j = 0; j < n; j++) {
                if (j == i || !alive[j])
                    continue;
                vec3 d = v3_sub(p[i], p[j]);
                float e = v3_dot(d, d);
                if (e < d1)
                    d2 = d1, d1 = e;
                else if (e < d2)
                    d2 = e;
            }
            if (best == n || d1 < bd1 || (d1 == bd1 && d2 < bd2))
                best = i, bd1 = d1, bd2 = d2;
        }
        if (best == n)
            break;
        alive[best] = 0;
        count--;
        if (group)
            left[group[best]]--;
    }
    free(left);
    return count;
}

size_t srv_vsl_thin(const vec3 *p, const uint32_t *group, size_t n, size_t keep, uint8_t *alive)
{
    near2 *q = malloc((n ? n : 1) * sizeof *q);
    uint32_t *left = group_counts(group, n);
    if (!q || !left) {
        free(q);
        free(left);
        return (size_t)-1;
    }
    memset(alive, 1, n);
    for (uint32_t i = 0; i < n; i++)
        find_two(p, alive, n, i, &q[i]);
    size_t count = n;
    while (count > keep) {
        uint32_t k = pick(q, alive, group, left, n);
        if (k == NONE)
            break;
        alive[k] = 0;
        count--;
        if (group)
            left[group[k]]--;
        for (uint32_t i = 0; i < n; i++)   /* only those that had V_k as V1 or V2 */
            if (alive[i] && (q[i].v1 == k || q[i].v2 == k))
                find_two(p, alive, n, i, &q[i]);
    }
    free(q);
    free(left);
    return count;
}

/* ---- candidates ----------------------------------------------------------- */

static double tri_area(const srv_mesh *m, uint32_t t)
{
    vec3 a = m->pos[m->tris[3 * t]], b = m->pos[m->tris[3 * t + 1]], c = m->pos[m->tris[3 * t + 2]];
    return 0.5 * (double)v3_len(v3_cross(v3_sub(b, a), v3_sub(c, a)));
}

/* Cumulative triangle areas of m into cdf (ntris); returns the total. */
static double area_cdf(const srv_mesh *m, double *cdf)
{
    double sum = 0.0;
    for (uint32_t t = 0; t < m->ntris; t++)
        cdf[t] = sum += tri_area(m, t);
    return sum;
}

static uint32_t draw_tri(const double *cdf, uint32_t ntris, double u)
{
    uint32_t lo = 0, hi = ntris - 1;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (cdf[mid] > u)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* A uniform point on triangle t scaled by `shrink` about its centroid
 * (Figure 4.a), with the triangle's normal and interpolated albedo. */
static srv_vsl candidate(const srv_mesh *m, uint32_t t, float shrink, uint32_t object, srv_rng *r)
{
    const uint32_t *ix = &m->tris[3 * t];
    vec3 a = m->pos[ix[0]], b = m->pos[ix[1]], c = m->pos[ix[2]];
    float u = srv_rng_float(r), v = srv_rng_float(r);
    if (u + v > 1.0f)
        u = 1.0f - u, v = 1.0f - v;
    float w0 = 1.0f - u - v;
    vec3 ctr = v3_scale(v3_add(v3_add(a, b), c), 1.0f / 3.0f);
    vec3 x = v3_add(v3_add(v3_scale(a, w0), v3_scale(b, u)), v3_scale(c, v));
    srv_vsl s = {0};
    s.pos = v3_add(ctr, v3_scale(v3_sub(x, ctr), shrink));
    s.normal = v3_norm(v3_cross(v3_sub(b, a), v3_sub(c, a)));
    s.albedo = v3_add(v3_add(v3_scale(m->albedo[ix[0]], w0), v3_scale(m->albedo[ix[1]], u)),
                      v3_scale(m->albedo[ix[2]], v));
    s.object = object;
    return s;
}

static double lit_area(const srv_scene *s, size_t *nobj)
{
    double total = 0.0;
    *nobj = 0;
    for (size_t i = 0; i < s->nmeshes; i++) {
        if (s->meshes[i].emitter || !s->meshes[i].ntris)
            continue;
        for (uint32_t t = 0; t < s->meshes[i].ntris; t++)
            total += tri_area(&s->meshes[i], t);
        (*nobj)++;
    }
    return total;
}

/* Candidates of every object, by area, at least one each. */
static srv_vsl *draw_candidates(const srv_scene *s, const srv_vsl_place_opts *o, double total,
                                size_t *n, double *obj_area)
{
    size_t want = (size_t)ceil((double)o->nv * (1.0 + o->oversample)), cap = want + s->nmeshes, m = 0;
    srv_vsl *c = malloc(cap * sizeof *c);
    srv_rng r;
    srv_rng_seed(&r, o->seed, 0x56534Cu);
    for (size_t i = 0; c && i < s->nmeshes; i++) {
        const srv_mesh *mesh = &s->meshes[i];
        obj_area[i] = 0.0;
        if (mesh->emitter || !mesh->ntris)
            continue;
        double *cdf = malloc(mesh->ntris * sizeof *cdf);
        if (!cdf) {
            free(c);
            return NULL;
        }
        obj_area[i] = area_cdf(mesh, cdf);
        size_t k = (size_t)llround((double)want * obj_area[i] / total);
        for (k = k ? k : 1; k-- && m < cap;)
            c[m++] = candidate(mesh, draw_tri(cdf, mesh->ntris, srv_rng_float(&r) * obj_area[i]),
                               o->shrink, (uint32_t)i, &r);
        free(cdf);
    }
    *n = m;
    return c;
}

srv_vsl_place_opts srv_vsl_place_defaults(size_t nv, uint64_t seed)
{
    srv_vsl_place_opts o = {nv, 0.10f, 0.95f, seed};
    return o;
}

void srv_vsl_set_free(srv_vsl_set *set)
{
    free(set->v);
    free(set->first);
    free(set->count);
    memset(set, 0, sizeof *set);
}

/* Keep the survivors (already in object order), count them per object and
 * give each its surface element dS'. */
static lumo_status gather(const srv_vsl *c, const uint8_t *alive, size_t n, const double *obj_area,
                          size_t nobj, srv_vsl_set *out)
{
    out->nobjects = nobj;
    out->first = calloc(nobj ? nobj : 1, sizeof *out->first);
    out->count = calloc(nobj ? nobj : 1, sizeof *out->count);
    out->v = malloc((n ? n : 1) * sizeof *out->v);
    if (!out->first || !out->count || !out->v)
        return LUMO_ERR_NOMEM;
    for (size_t i = 0; i < n; i++)
        if (alive[i])
            out->v[out->n++] = c[i], out->count[c[i].object]++;
    for (size_t o = 1; o < nobj; o++)
        out->first[o] = out->first[o - 1] + out->count[o - 1];
    for (size_t i = 0; i < out->n; i++)
        out->v[i].area = (float)(obj_area[out->v[i].object] / out->count[out->v[i].object]);
    return LUMO_OK;
}

lumo_status srv_vsl_place(const srv_scene *s, const srv_vsl_place_opts *o, srv_vsl_set *out,
                          char *err, size_t errlen)
{
    size_t nobj, n = 0;
    memset(out, 0, sizeof *out);
    double total = lit_area(s, &nobj);
    if (!(total > 0.0) || o->nv < nobj) {
        snprintf(err, errlen, "cannot place %zu VSLs: %zu lit objects need one each, surface area %g m^2",
                 o->nv, nobj, total);
        return LUMO_ERR_ARG;
    }
    double *obj_area = calloc(s->nmeshes, sizeof *obj_area);
    srv_vsl *c = obj_area ? draw_candidates(s, o, total, &n, obj_area) : NULL;
    vec3 *p = c ? calloc(n + 1, sizeof *p) : NULL;
    uint32_t *g = p ? calloc(n + 1, sizeof *g) : NULL;
    uint8_t *alive = g ? malloc(n + 1) : NULL;
    lumo_status st = LUMO_ERR_NOMEM;
    if (alive) {
        for (size_t i = 0; i < n; i++)
            p[i] = c[i].pos, g[i] = c[i].object;
        if (srv_vsl_thin(p, g, n, o->nv, alive) != (size_t)-1)
            st = gather(c, alive, n, obj_area, s->nmeshes, out);
    }
    if (st) {
        srv_vsl_set_free(out);
        snprintf(err, errlen, "out of memory placing %zu VSLs", o->nv);
    }
    free(obj_area), free(c), free(p), free(g), free(alive);
    return st;
}
