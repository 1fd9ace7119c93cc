/*
 * draco_traverse.c — the order in which an attributes decoder visits
 * vertices (libdraco DepthFirstTraverser and MaxPredictionDegreeTraverser
 * driven by MeshTraversalSequencer): it fixes the order of the encoded
 * values and, through the points met, the value of every point.
 */
#include "draco_internal.h"

typedef struct ld_walk {
    const ld_ct *ct;
    uint8_t *face_seen;        /* a face is seen once walked: a byte per face,
                                  or per corner for the degree walk */
    uint32_t num_faces;
    uint32_t cap, max_depth;   /* DFS stack in free space */
    uint32_t max_values;       /* entries of o->value_to_corner */
    uint8_t overflow;          /* more vertices visited: a corrupt stream */
    ld_order *o;
} ld_walk;

/* Where a traversal finds the opposites: 32-bit ids, the packed table
 * (LUMO_DRACO_LEAN), or the lean decode's 24-bit table with the face flags
 * in its bit 23 and the border flags in the vertex map (ld_ct.o24). */
#define LD_STORE_PLAIN  0
#define LD_STORE_PACKED 1
#define LD_STORE_O24    2
#define LD_VMAP_BORDER  (-2)         /* LD_STORE_O24: unvisited, on a border */
#define LD_VMAP_TIPPED  (-3)         /* degree walk: unvisited, a tip before */

/* One opposite for a constant `store` (ld_dfs). */
static LD_FORCE_INLINE uint32_t ld_dfs_opp(const uint32_t *opp32, ld_pot_near opp,
                                           const uint8_t *o24, uint32_t c, int store)
{
    uint32_t o;
    if (store == LD_STORE_PLAIN)
        return opp32[c];
    if (store == LD_STORE_PACKED)
        return ld_pot_near_opp(opp, c);
    o = ld_o24(o24, c);
    return o == LD_O24_NONE ? LD_INV : o;
}

/* MeshAttributeIndicesEncodingObserver::OnNewVertexVisited */
static LD_FORCE_INLINE void ld_visit(ld_walk *w, uint32_t v, uint32_t corner)
{
    ld_order *o = w->o;
    if (o->num_values >= w->max_values) {
        w->overflow = 1;
        return;
    }
    if (w->ct->o24)  /* the entry keeps its corner's opposite (ld_ct.o24) */
        corner = ld_dfs_opp(NULL, ld_pot_near_of(&w->ct->opp), w->ct->o24, corner, LD_STORE_O24);
    o->value_to_corner[o->num_values] = corner;
    o->vertex_to_value[v] = (int32_t)o->num_values;
    o->num_values++;
}

static lumo_status ld_visit_edge(ld_walk *w, uint32_t corner)
{
    uint32_t n = ld_tvert(w->ct, ld_next_v(corner)), p = ld_tvert(w->ct, ld_prev_v(corner));
    if (n >= w->ct->num_vertices || p >= w->ct->num_vertices)
        return LUMO_ERR_CORRUPT;
    if (w->o->vertex_to_value[n] < 0)
        ld_visit(w, n, ld_next_v(corner));
    if (w->o->vertex_to_value[p] < 0)
        ld_visit(w, p, ld_prev_v(corner));
    return LUMO_OK;
}

/* DepthFirstTraverser::TraverseFromCorner on local copies of the tables
 * (the stores into the order arrays would otherwise force reloads);
 * `store`: a constant, one of LD_STORE_*; `seams`: a constant, 0 for the
 * mesh's own table (no seam test per opposite); `rep`: a constant, 1 when
 * the table's vertices and border flags are its points' rep words
 * (ld_ct.rep: every table of a mesh with seams). */
static LD_FORCE_INLINE lumo_status ld_dfs(ld_walk *w, uint32_t corner, uint32_t *stack,
                                          int store, int seams, int rep_words)
{
    const ld_ct *ct = w->ct;
    const uint32_t *c2v = ct->c2v, *lmc = ct->lmc, *opp32 = ct->opp32, nv = ct->num_vertices;
    const uint32_t vmask = ct->vmask, *rep = ct->rep;
    const ld_pot_near opp = ld_pot_near_of(&ct->opp);
    const uint8_t *seam = ct->seam, *border = ct->border;
    uint8_t *o24 = (uint8_t *)(uintptr_t)ct->o24;  /* face flags: LD_STORE_O24 */
    uint8_t *fseen = w->face_seen;
    uint32_t *v2c = w->o->value_to_corner;
    int32_t *vmap = w->o->vertex_to_value;
    uint32_t n = w->o->num_values, top = 0;
    lumo_status st;
#define LD_OPP(c) ((seams && ld_seam(seam, c)) ? LD_INV : ld_dfs_opp(opp32, opp, o24, c, store))
#define LD_FACE_SEEN(c) (store == LD_STORE_O24 ? ld_o24_seen(o24, c) : fseen[(c) / 3u])
#define LD_SEEN(c) ((c) == LD_INV || LD_FACE_SEEN(c))
    /* LD_STORE_O24: the entry keeps its corner's opposite (ld_ct.o24) */
#define LD_VISIT(v, c)                                                               \
    (v2c[n] = store == LD_STORE_O24 ? ld_dfs_opp(opp32, opp, o24, c, store) : (c), \
     vmap[v] = (int32_t)n, ++n)
    /* LD_STORE_O24: room for the mesh's points only (ld_traverse) */
#define LD_VISIT_ROOM() (store != LD_STORE_O24 || n < w->max_values)
    if (w->cap < 2)
        return LUMO_ERR_NOMEM;
    if ((st = ld_visit_edge(w, corner)))
        return st;
    n = w->o->num_values;
    stack[top++] = corner;
    while (top) {
        uint32_t c = stack[top - 1];
        if (LD_FACE_SEEN(c)) {  /* stacked corners are valid */
            --top;
            continue;
        }
        for (;;) {
            uint32_t v, r, l, m3, rw = 0;
            if (store == LD_STORE_O24)
                ld_o24_mark(o24, c - c % 3u);
            else
                fseen[c / 3u] = 1;
            v = store == LD_STORE_PACKED ? c2v[c] & vmask : c2v[c];
            if (v >= nv) {
                w->o->num_values = n;
                return LUMO_ERR_CORRUPT;
            }
            if (rep_words) {  /* the point's vertex (below nv) */
                rw = rep[v];
                v = rw & LD_REP_MASK;
            }
            m3 = c % 3u;
            if (vmap[v] < 0) {
                /* on the boundary: no left-most corner, or no swing left */
                int boundary;
                if (store == LD_STORE_O24) {
                    boundary = vmap[v] == LD_VMAP_BORDER;
                } else if (rep_words) {
                    boundary = (int)(rw >> 31);
                } else if (border) {
                    boundary = border[v];
                } else {
                    const uint32_t lc = lmc[v];
                    boundary = lc == LD_INV || LD_OPP(ld_next_v(lc)) == LD_INV;
                }
                if (!LD_VISIT_ROOM()) {
                    w->o->num_values = n;
                    return LUMO_ERR_CORRUPT;
                }
                LD_VISIT(v, c);
                if (!boundary) {
                    c = LD_OPP(m3 == 2u ? c - 2u : c + 1u);
                    if (LD_SEEN(c)) {
                        w->o->num_values = n;
                        return LUMO_ERR_CORRUPT;  /* libdraco reads out of bounds */
                    }
                    continue;
                }
            }
            r = LD_OPP(m3 == 2u ? c - 2u : c + 1u);
            l = LD_OPP(m3 == 0u ? c + 2u : c - 1u);
            if (LD_SEEN(r)) {
                if (LD_SEEN(l)) {
                    --top;
                    break;
                }
                c = l;
            } else if (LD_SEEN(l)) {
                c = r;
            } else {
                if (top >= w->cap) {
                    w->o->num_values = n;
                    return LUMO_ERR_NOMEM;
                }
                stack[top - 1] = l;
                stack[top++] = r;
                if (top > w->max_depth)
                    w->max_depth = top;
                break;
            }
        }
    }
#undef LD_OPP
#undef LD_FACE_SEEN
#undef LD_SEEN
#undef LD_VISIT
#undef LD_VISIT_ROOM
    w->o->num_values = n;
    return LUMO_OK;
}

/* The first start face from f on that no walk has reached (both
 * traversers skip seen ones, and most are): a byte scan by memchr
 * (vectorised), or a step over the 24-bit table's face flags. */
static LD_FORCE_INLINE uint32_t ld_next_start(const uint8_t *fseen, const uint8_t *o24, uint32_t f,
                                              uint32_t num_faces)
{
    const uint8_t *q;
    if (o24) {
        while (f < num_faces && ld_o24_seen(o24, 3u * f))
            ++f;
        return f;
    }
    if (f >= num_faces)
        return num_faces;
    q = memchr(fseen + f, 0, num_faces - f);
    return q ? (uint32_t)(q - fseen) : num_faces;
}

/* Every start face; one instance per opposite store, seams or none, rep
 * words or none. */
static LD_FORCE_INLINE lumo_status ld_dfs_starts(ld_walk *w, uint32_t *stack, int store, int seams,
                                                 int rep_words)
{
    const uint8_t *o24 = store == LD_STORE_O24 ? w->ct->o24 : NULL;
    uint32_t f = 0;
    lumo_status st = LUMO_OK;
    while (!st && (f = ld_next_start(w->face_seen, o24, f, w->num_faces)) < w->num_faces)
        st = ld_dfs(w, 3u * f++, stack, store, seams, rep_words);
    return st;
}

static lumo_status ld_dfs_all(ld_walk *w, uint32_t *stack)
{
    if (w->ct->o24)  /* a mesh without seams */
        return ld_dfs_starts(w, stack, LD_STORE_O24, 0, 0);
    if (!w->ct->rep)  /* a mesh without interior seams */
        return !ld_ct_packed(w->ct) ? ld_dfs_starts(w, stack, LD_STORE_PLAIN, 0, 0)
                                    : ld_dfs_starts(w, stack, LD_STORE_PACKED, 0, 0);
    if (!w->ct->seam)  /* the mesh's table of a mesh with seams */
        return !ld_ct_packed(w->ct) ? ld_dfs_starts(w, stack, LD_STORE_PLAIN, 0, 1)
                                    : ld_dfs_starts(w, stack, LD_STORE_PACKED, 0, 1);
    return !ld_ct_packed(w->ct) ? ld_dfs_starts(w, stack, LD_STORE_PLAIN, 1, 1)
                                : ld_dfs_starts(w, stack, LD_STORE_PACKED, 1, 1);
}

/* Prediction-degree traversal: three priority stacks sharing one node pool
 * (corner, next) with a free list. An unvisited vertex that was the tip of
 * a corner put on a stack is LD_VMAP_TIPPED in the vertex map (libdraco
 * counts these "prediction degrees" but reads only whether one is above
 * 1): no array of its own, and one load tells both. */
typedef struct ld_pq {
    uint32_t *corner, *next;
    uint32_t used, cap;
} ld_pq;

/* MaxPredictionDegreeTraverser::TraverseFromCorner for every start face,
 * all state in locals (stores into the uint32 arrays could otherwise alias
 * the structs' fields and force reloads); `packed`: a constant, one
 * instance per opposite store and per seams (an attribute's table) or none
 * (the mesh's: no seam test per opposite). */
static LD_FORCE_INLINE lumo_status ld_degree_walk(ld_walk *w, ld_pq *q, int packed, int seams,
                                                  int rep_words)
{
    const ld_ct *ct = w->ct;
    const uint32_t *c2v = ct->c2v, *opp32 = ct->opp32, nv = ct->num_vertices, vmask = ct->vmask;
    const uint32_t nfaces = w->num_faces, maxv = w->max_values, cap = q->cap, *rep = ct->rep;
    const ld_pot_near opp = ld_pot_near_of(&ct->opp);
    const uint8_t *seam = ct->seam;
    uint8_t *fseen = w->face_seen;
    uint32_t *v2c = w->o->value_to_corner, *qc = q->corner, *qn = q->next;
    int32_t *vmap = w->o->vertex_to_value;
    uint32_t n = w->o->num_values, used = 0, fre = LD_INV, head[3], f;
    lumo_status st = LUMO_OK;
    int best = 0;
#define LD_OPP(c) ((seams && ld_seam(seam, c)) ? LD_INV : packed ? ld_pot_near_opp(opp, c) : opp32[c])
    /* an attribute's table (seams): the point's attribute vertex (ld_ct.rep) */
#define LD_PT(c) (packed ? c2v[c] & vmask : c2v[c])
#define LD_VERT(c) (!rep_words ? LD_PT(c) : LD_PT(c) < nv ? rep[LD_PT(c)] & LD_REP_MASK : LD_INV)
#define LD_SEEN(c) ((c) == LD_INV || fseen[c])
    /* MeshAttributeIndicesEncodingObserver::OnNewVertexVisited */
#define LD_VISIT(v, c)                      \
    do {                                    \
        if (vmap[v] < 0) {                  \
            if (n >= maxv) {                \
                st = LUMO_ERR_CORRUPT;      \
                goto out;                   \
            }                               \
            v2c[n] = (c);                   \
            vmap[v] = (int32_t)n++;         \
        }                                   \
    } while (0)
#define LD_PUSH(c, pri)                                \
    do {                                               \
        uint32_t node_ = fre;                          \
        if (node_ != LD_INV) {                         \
            fre = qn[node_];                           \
        } else if (used < cap) {                       \
            node_ = used++;                            \
        } else {                                       \
            st = LUMO_ERR_NOMEM;                       \
            goto out;                                  \
        }                                              \
        qc[node_] = (c);                               \
        qn[node_] = head[pri];                         \
        head[pri] = node_;                             \
        if ((pri) < best)                              \
            best = (pri);                              \
    } while (0)
    head[0] = head[1] = head[2] = LD_INV;
    for (f = 0; nv > 0 && (f = ld_next_start(fseen, NULL, f, 3u * nfaces)) < 3u * nfaces;
         f += 3u) {
        uint32_t corner = f, a, b;
        /* the start face's three vertices: next, previous, then the tip */
        a = LD_VERT(corner + 1u);
        b = LD_VERT(corner + 2u);
        if (a >= nv || b >= nv) {
            st = LUMO_ERR_CORRUPT;
            goto out;
        }
        LD_VISIT(a, corner + 1u);
        LD_VISIT(b, corner + 2u);
        a = LD_VERT(corner);
        if (a >= nv) {
            st = LUMO_ERR_CORRUPT;
            goto out;
        }
        LD_VISIT(a, corner);
        LD_PUSH(corner, 0);
        best = 0;
        for (;;) {
            int pri;
            for (pri = best; pri < 3 && head[pri] == LD_INV; ++pri)
                ;
            if (pri == 3)
                break;
            {  /* pop */
                const uint32_t node = head[pri];
                head[pri] = qn[node];
                qn[node] = fre;
                fre = node;
                best = pri;
                corner = qc[node];
            }
            if (fseen[corner])
                continue;
            for (;;) {
                const uint32_t m3 = corner % 3u;
                uint32_t v, r, l;
                int rs, ls;
                int32_t x;
                memset(fseen + (corner - m3), 1, 3);
                v = LD_VERT(corner);
                if (v >= nv) {
                    st = LUMO_ERR_CORRUPT;
                    goto out;
                }
                LD_VISIT(v, corner);
                r = LD_OPP(m3 == 2u ? corner - 2u : corner + 1u);  /* right: opp(next) */
                l = LD_OPP(m3 == 0u ? corner + 2u : corner - 1u);  /* left: opp(prev) */
                rs = LD_SEEN(r);
                ls = LD_SEEN(l);
                if (!ls) {
                    const uint32_t tip = LD_VERT(l);
                    pri = 0;  /* priority 0 toward a visited tip, else 2 or 1 */
                    if (tip < nv && (x = vmap[tip]) < 0) {
                        pri = x == LD_VMAP_TIPPED ? 1 : 2;
                        vmap[tip] = LD_VMAP_TIPPED;
                    }
                    if (rs && pri <= best) {
                        corner = l;
                        continue;
                    }
                    LD_PUSH(l, pri);
                }
                if (!rs) {
                    const uint32_t tip = LD_VERT(r);
                    pri = 0;
                    if (tip < nv && (x = vmap[tip]) < 0) {
                        pri = x == LD_VMAP_TIPPED ? 1 : 2;
                        vmap[tip] = LD_VMAP_TIPPED;
                    }
                    if (pri <= best) {
                        corner = r;
                        continue;
                    }
                    LD_PUSH(r, pri);
                }
                break;
            }
        }
    }
out:
#undef LD_OPP
#undef LD_PT
#undef LD_VERT
#undef LD_SEEN
#undef LD_VISIT
#undef LD_PUSH
    w->o->num_values = n;
    q->used = used;
    return st;
}

static lumo_status ld_max_degree_all(ld_walk *w, ld_pq *q)
{
    if (!w->ct->rep)  /* the mesh's own table: no seam test per opposite */
        return !ld_ct_packed(w->ct) ? ld_degree_walk(w, q, 0, 0, 0) : ld_degree_walk(w, q, 1, 0, 0);
    if (!w->ct->seam)  /* ... of a mesh with seams: rep words */
        return !ld_ct_packed(w->ct) ? ld_degree_walk(w, q, 0, 0, 1) : ld_degree_walk(w, q, 1, 0, 1);
    return !ld_ct_packed(w->ct) ? ld_degree_walk(w, q, 0, 1, 1) : ld_degree_walk(w, q, 1, 1, 1);
}

lumo_status ld_traverse(ld_mem *m, const ld_ct *ct, uint32_t vmap_size, uint32_t max_values,
                        int prediction_degree, ld_order *o)
{
    ld_walk w;
    ld_pq q;
    uint32_t *stack = NULL, nv = ct->num_vertices, i, fbytes;
    lumo_status st = LUMO_OK;
    int32_t *vmap = o->vertex_to_value;  /* caller may provide the array */
    uint8_t *mark;
    memset(o, 0, sizeof *o);
    memset(&w, 0, sizeof w);
    memset(&q, 0, sizeof q);
    o->ct = ct;
    o->vertex_to_value = vmap ? vmap : ld_tmp(m, vmap_size, sizeof(int32_t));
    /* rep words: the vertex ids are points, the values at most max_values */
    w.max_values = ct->rep || max_values < nv ? max_values : nv;
    o->value_to_corner = ld_tmp(m, w.max_values, sizeof(uint32_t));
    mark = ld_tmp_mark(m);  /* the rest is released on return */
    w.ct = ct;
    w.o = o;
    w.num_faces = ct->num_corners / 3u;
    if (ct->o24 && (prediction_degree || !vmap))
        return LUMO_ERR_CORRUPT;  /* only the depth-first walk of a filled map */
    /* the degree walk tests a face from any of its corners: a flag per
     * corner spares a division by 3 per test; the depth-first walks keep
     * one per face (their arena is the tighter one) */
    fbytes = prediction_degree ? ct->num_corners : w.num_faces;
    if (!ct->o24)  /* else the flags are in the table and the map */
        w.face_seen = ld_tmp(m, fbytes, 1);
    if (!o->vertex_to_value || !o->value_to_corner || (!ct->o24 && !w.face_seen))
        return LUMO_ERR_NOMEM;
    if (!ct->o24) {
        for (i = 0; i < vmap_size; ++i)
            o->vertex_to_value[i] = -1;
        memset(w.face_seen, 0, fbytes);
    }
    if (prediction_degree) {
        size_t cap;
        /* node pool (corner, next) pairs in the free space */
        q.corner = ld_free_space(m, &cap);
        cap /= 2u;
        q.cap = cap > 0x7FFFFFFFu ? 0x7FFFFFFFu : (uint32_t)cap;
        q.next = q.corner + q.cap;
    } else {
        size_t cap;
        stack = ld_free_space(m, &cap);
        w.cap = cap > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)cap;
        w.max_depth = 2;  /* ld_dfs needs room for two entries */
    }
    if (prediction_degree)
        st = ld_max_degree_all(&w, &q);
    if (!prediction_degree)
        st = ld_dfs_all(&w, stack);
    if (!st && w.overflow)
        st = LUMO_ERR_CORRUPT;
    ld_free_used(m, prediction_degree ? (size_t)q.used * 8u : (size_t)w.max_depth * 4u);
    ld_tmp_release(m, mark);
    return st;
}
