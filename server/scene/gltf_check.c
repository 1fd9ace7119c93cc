/* gltf_check.c — lumo's check of a glTF 2.0 file (.gltf JSON or .glb
 * container) before assimp (model_check.h).
 *
 * assimp's glTF reader allocates what accessors declare (count × element
 * size) and copies an accessor again for every primitive and node that
 * uses it (aiProcess_PreTransformVertices). So before it sees the file,
 * with the JSON parsed by jansson:
 *   - GLB: magic, version 2, the declared length is the file's, the JSON
 *     and BIN chunks lie inside it;
 *   - every buffer is backed by bytes: the GLB's BIN chunk, a data: URI's
 *     decoded length, or a regular file beside the model at least
 *     byteLength long;
 *   - every bufferView lies inside its buffer, every accessor inside its
 *     bufferView (offset + (count − 1) × stride + element size); an
 *     accessor without a bufferView (all zeros, or Draco-compressed) and a
 *     sparse one are refused: nothing bounds what assimp makes of them;
 *   - the node hierarchy is a set of trees (no node with two parents, no
 *     cycle), and the bytes of geometry assimp expands — every accessor a
 *     mesh primitive uses, once per node that draws the mesh, plus
 *     animation, skin and image data — are at most SRV_GLTF_MAX_EXPANDED.
 * So assimp's memory is bounded by the file and its buffers, times a
 * small factor, and never by a count alone. */
#include <errno.h>
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "scene/model_check.h"
#include "scene/model_check_internal.h"

#define GLB_MAGIC      0x46546c67u   /* "glTF" */
#define GLB_JSON       0x4e4f534au
#define GLB_BIN        0x004e4942u
#define GLTF_MAX_ITEMS 1000000u      /* nodes, meshes, accessors, ... of one file */

typedef struct gltf {
    srv_mc       *c;
    json_t       *root;
    const uint8_t *bin;          /* the GLB's BIN chunk, or NULL */
    uint64_t      bin_len;
    uint64_t      expanded;      /* bytes assimp expands so far */
    uint64_t     *view_len;      /* per bufferView, its byteLength (checked) */
    uint64_t     *acc_bytes;     /* per accessor, count × element size */
} gltf;

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* ---- JSON fields ------------------------------------------------------------ */

/* The array `key` of the root (absent: empty); -1 with a message when it
 * is not an array or longer than GLTF_MAX_ITEMS. */
static int top_array(gltf *g, const char *key, json_t **out)
{
    json_t *a = json_object_get(g->root, key);
    *out = a;
    if (!a)
        return 0;
    if (!json_is_array(a))
        return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "'%s' is not an array", key), -1;
    if (json_array_size(a) > GLTF_MAX_ITEMS)
        return srv_mc_fail(g->c, LUMO_ERR_LIMIT, "%zu %s, at most %u are read", json_array_size(a), key,
                           GLTF_MAX_ITEMS), -1;
    return 0;
}

/* Integer member `key` of o in [lo, hi]; `def` when absent and def >= 0. */
static lumo_status get_int(gltf *g, json_t *o, const char *what, size_t i, const char *key, long long lo,
                           long long hi, long long def, long long *out)
{
    json_t *v = json_is_object(o) ? json_object_get(o, key) : NULL;
    if (!json_is_object(o))
        return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "%s %zu is not an object", what, i);
    if (!v && def >= 0)
        return *out = def, LUMO_OK;
    if (!v)
        return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "%s %zu has no %s", what, i, key);
    if (!json_is_integer(v) || json_integer_value(v) < lo || json_integer_value(v) > hi)
        return srv_mc_fail(g->c, LUMO_ERR_RANGE, "%s %zu: %s must be an integer in [%lld, %lld]", what, i, key, lo, hi);
    *out = json_integer_value(v);
    return LUMO_OK;
}

/* An index member: absent (-1 when optional) or in [0, n). */
static lumo_status get_ref(gltf *g, json_t *o, const char *what, size_t i, const char *key, size_t n, int optional,
                           long long *out)
{
    if (optional && json_is_object(o) && !json_object_get(o, key))
        return *out = -1, LUMO_OK;
    if (n == 0)
        return srv_mc_fail(g->c, LUMO_ERR_RANGE, "%s %zu: %s names an item of an empty list", what, i, key);
    return get_int(g, o, what, i, key, 0, (long long)n - 1, -1, out);
}

/* ---- GLB container ---------------------------------------------------------- */

/* The JSON chunk into [*json, +*len) and the BIN chunk into g. */
static lumo_status glb_chunks(gltf *g, const uint8_t **json, size_t *len)
{
    srv_mc *c = g->c;
    size_t size = (size_t)(c->end - c->base), at;
    uint32_t clen;
    if (size < 20 || le32(c->base) != GLB_MAGIC)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "no GLB header ('glTF' magic and 20 bytes)");
    if (le32(c->base + 4) != 2)
        return srv_mc_fail(c, LUMO_ERR_UNSUPPORTED, "GLB version %u: only version 2 (glTF 2.0) is read",
                           le32(c->base + 4));
    if (le32(c->base + 8) != size)
        return srv_mc_fail(c, le32(c->base + 8) > size ? LUMO_ERR_TRUNCATED : LUMO_ERR_CORRUPT,
                           "the GLB header declares %u bytes, the file holds %zu", le32(c->base + 8), size);
    clen = le32(c->base + 12);
    if (le32(c->base + 16) != GLB_JSON || clen == 0 || clen > size - 20)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "the first GLB chunk is not JSON of %u bytes inside the file's %zu",
                           clen, size);
    *json = c->base + 20;
    *len = clen;
    at = 20 + (size_t)clen;
    at += (4 - at % 4) % 4;
    if (at + 8 <= size && le32(c->base + at + 4) == GLB_BIN) {
        uint32_t blen = le32(c->base + at);
        if (blen > size - at - 8)
            return srv_mc_fail(c, LUMO_ERR_TRUNCATED, "the BIN chunk declares %u bytes, %zu follow it", blen,
                               size - at - 8);
        g->bin = c->base + at + 8;
        g->bin_len = blen;
    }
    return LUMO_OK;
}

/* ---- buffers ---------------------------------------------------------------- */

/* Bytes a base64 text of n characters decodes to (its padding aside). */
static uint64_t base64_bytes(const char *s, size_t n)
{
    while (n > 0 && s[n - 1] == '=')
        n--;
    return (uint64_t)n / 4 * 3 + (n % 4 ? n % 4 - 1 : 0);
}

/* What backs buffer i: its length in bytes, or a refusal. */
static lumo_status buffer_backing(gltf *g, size_t i, const char *uri, uint64_t *have)
{
    char dir[1024], path[2048];
    const char *slash = strrchr(g->c->name, '/'), *comma;
    struct stat st;
    if (!uri) {
        if (i != 0 || !g->bin)
            return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "buffer %zu has no uri and is not a GLB's BIN chunk", i);
        return *have = g->bin_len, LUMO_OK;
    }
    if (!strncmp(uri, "data:", 5)) {
        if (!(comma = strchr(uri, ',')) || !strstr(uri, ";base64,"))
            return srv_mc_fail(g->c, LUMO_ERR_UNSUPPORTED, "buffer %zu: a data: uri that is not base64", i);
        return *have = base64_bytes(comma + 1, strlen(comma + 1)), LUMO_OK;
    }
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - g->c->name) : 1, slash ? g->c->name : ".");
    snprintf(path, sizeof path, "%s/%s", dir, uri);
    if (stat(path, &st))
        return srv_mc_fail(g->c, LUMO_ERR_IO, "buffer %zu: '%.200s': %s", i, uri, strerror(errno));
    if (!S_ISREG(st.st_mode))
        return srv_mc_fail(g->c, LUMO_ERR_IO, "buffer %zu: '%.200s' is not a regular file", i, uri);
    *have = (uint64_t)st.st_size;
    return LUMO_OK;
}

/* Every buffer: byteLength within what backs it. lens gets each. */
static lumo_status check_buffers(gltf *g, json_t *buffers, uint64_t *lens)
{
    for (size_t i = 0; i < json_array_size(buffers); i++) {
        json_t *b = json_array_get(buffers, i), *uri = json_is_object(b) ? json_object_get(b, "uri") : NULL;
        long long len;
        uint64_t have = 0;
        lumo_status st = get_int(g, b, "buffer", i, "byteLength", 1, (long long)SRV_MODEL_MAX_BYTES, -1, &len);
        if (st)
            return st;
        if (uri && !json_is_string(uri))
            return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "buffer %zu: uri is not a string", i);
        if ((st = buffer_backing(g, i, uri ? json_string_value(uri) : NULL, &have)))
            return st;
        if ((uint64_t)len > have)
            return srv_mc_fail(g->c, LUMO_ERR_TRUNCATED, "buffer %zu declares %lld bytes, %s holds %llu", i, len,
                               uri ? "its uri" : "the BIN chunk", (unsigned long long)have);
        lens[i] = (uint64_t)len;
    }
    return LUMO_OK;
}

/* Every bufferView inside its buffer; a stride, when given, 4..252. */
static lumo_status check_views(gltf *g, json_t *views, const uint64_t *blen, size_t nbuf)
{
    for (size_t i = 0; i < json_array_size(views); i++) {
        json_t *v = json_array_get(views, i);
        long long b, off, len, stride;
        lumo_status st;
        if ((st = get_ref(g, v, "bufferView", i, "buffer", nbuf, 0, &b)) ||
            (st = get_int(g, v, "bufferView", i, "byteOffset", 0, (long long)SRV_MODEL_MAX_BYTES, 0, &off)) ||
            (st = get_int(g, v, "bufferView", i, "byteLength", 1, (long long)SRV_MODEL_MAX_BYTES, -1, &len)) ||
            (st = get_int(g, v, "bufferView", i, "byteStride", 4, 252, 0, &stride)))
            return st;
        if ((uint64_t)(off + len) > blen[b])
            return srv_mc_fail(g->c, LUMO_ERR_RANGE, "bufferView %zu: bytes %lld..%lld lie past buffer %lld's %llu",
                               i, off, off + len, b, (unsigned long long)blen[b]);
        g->view_len[i] = (uint64_t)len;
    }
    return LUMO_OK;
}

/* ---- accessors -------------------------------------------------------------- */

static unsigned component_size(long long type)
{
    switch (type) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
    }
}

static unsigned type_components(const char *t)
{
    static const char *const names[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    static const unsigned n[] = {1, 2, 3, 4, 4, 9, 16};
    for (size_t i = 0; t && i < sizeof n / sizeof n[0]; i++)
        if (!strcmp(t, names[i]))
            return n[i];
    return 0;
}

/* One accessor: a known type, inside its bufferView. */
static lumo_status check_accessor(gltf *g, json_t *a, size_t i, json_t *views)
{
    long long view, off, count, ctype, stride;
    unsigned csize, ncomp;
    uint64_t elem, last;
    lumo_status st;
    if ((st = get_int(g, a, "accessor", i, "componentType", 0, 99999, -1, &ctype)) ||
        (st = get_int(g, a, "accessor", i, "count", 1, (long long)SRV_MODEL_MAX_BYTES, -1, &count)) ||
        (st = get_int(g, a, "accessor", i, "byteOffset", 0, (long long)SRV_MODEL_MAX_BYTES, 0, &off)) ||
        (st = get_ref(g, a, "accessor", i, "bufferView", json_array_size(views), 1, &view)))
        return st;
    csize = component_size(ctype);
    ncomp = type_components(json_string_value(json_object_get(a, "type")));
    if (!csize || !ncomp)
        return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "accessor %zu: componentType %lld or its type is not glTF 2.0's",
                           i, ctype);
    if (json_object_get(a, "sparse"))
        return srv_mc_fail(g->c, LUMO_ERR_UNSUPPORTED, "accessor %zu is sparse: not read", i);
    if (view < 0)
        return srv_mc_fail(g->c, LUMO_ERR_UNSUPPORTED, "accessor %zu has no bufferView (zeros or Draco-compressed "
                           "data): not read", i);
    elem = (uint64_t)csize * ncomp;
    get_int(g, json_array_get(views, (size_t)view), "bufferView", (size_t)view, "byteStride", 4, 252, 0, &stride);
    last = (uint64_t)off + (uint64_t)(count - 1) * (stride ? (uint64_t)stride : elem) + elem;
    if (last > g->view_len[view])
        return srv_mc_fail(g->c, LUMO_ERR_RANGE, "accessor %zu: %lld items of %llu bytes from offset %lld need %llu "
                           "bytes, bufferView %lld holds %llu", i, count, (unsigned long long)elem, off,
                           (unsigned long long)last, view, (unsigned long long)g->view_len[view]);
    g->acc_bytes[i] = (uint64_t)count * elem;
    return LUMO_OK;
}

/* ---- what assimp expands ---------------------------------------------------- */

/* Add the bytes of accessor `ref` (a JSON index, checked) `times` times. */
static lumo_status expand(gltf *g, json_t *ref, uint64_t times, const char *where, size_t i)
{
    size_t nacc = json_array_size(json_object_get(g->root, "accessors"));
    if (!ref)
        return LUMO_OK;
    if (!json_is_integer(ref) || json_integer_value(ref) < 0 || (size_t)json_integer_value(ref) >= nacc)
        return srv_mc_fail(g->c, LUMO_ERR_RANGE, "%s %zu names accessor %lld, the file has %zu", where, i,
                           json_is_integer(ref) ? json_integer_value(ref) : -1LL, nacc);
    uint64_t bytes = g->acc_bytes[json_integer_value(ref)];
    if ((bytes && times > (SRV_GLTF_MAX_EXPANDED - g->expanded) / bytes) ||
        (g->expanded += bytes * times) > SRV_GLTF_MAX_EXPANDED)
        return srv_mc_fail(g->c, LUMO_ERR_LIMIT, "%s %zu: the geometry assimp would expand passes %llu MiB "
                           "(SRV_GLTF_MAX_EXPANDED: accessors counted once per primitive and node using them)",
                           where, i, (unsigned long long)(SRV_GLTF_MAX_EXPANDED >> 20));
    return LUMO_OK;
}

/* Every accessor of an object of accessor indices (attributes, a target). */
static lumo_status expand_map(gltf *g, json_t *map, uint64_t times, const char *where, size_t i)
{
    const char *key;
    json_t *v;
    lumo_status st = LUMO_OK;
    if (map && !json_is_object(map))
        return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "%s %zu: attributes are not an object", where, i);
    json_object_foreach(map, key, v)
        if ((st = expand(g, v, times, where, i)))
            return st;
    return st;
}

/* Mesh m drawn `times` times: its primitives' attributes, indices, targets. */
static lumo_status expand_mesh(gltf *g, json_t *mesh, size_t m, uint64_t times)
{
    json_t *prims = json_is_object(mesh) ? json_object_get(mesh, "primitives") : NULL;
    lumo_status st;
    if (!json_is_array(prims))
        return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "mesh %zu has no primitives array", m);
    for (size_t p = 0; p < json_array_size(prims); p++) {
        json_t *pr = json_array_get(prims, p), *targets = json_object_get(pr, "targets");
        if ((st = expand_map(g, json_object_get(pr, "attributes"), times, "mesh", m)) ||
            (st = expand(g, json_object_get(pr, "indices"), times, "mesh", m)))
            return st;
        for (size_t t = 0; t < json_array_size(targets); t++)
            if ((st = expand_map(g, json_array_get(targets, t), times, "mesh", m)))
                return st;
    }
    return LUMO_OK;
}

/* The nodes form trees: each node the child of at most one other and
 * never both a child and a root of a scene (else a few nodes draw a mesh
 * 2^n times). parent[i] gets 1 + the parent of node i (0: none), roots[i]
 * how often the scenes list node i. */
static lumo_status node_parents(gltf *g, json_t *nodes, uint32_t *parent, uint64_t *roots)
{
    json_t *scenes = json_object_get(g->root, "scenes");
    size_t n = json_array_size(nodes);
    for (size_t i = 0; i < n; i++) {
        json_t *nd = json_array_get(nodes, i), *kids = json_is_object(nd) ? json_object_get(nd, "children") : NULL;
        if (!json_is_object(nd))
            return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "node %zu is not an object", i);
        for (size_t k = 0; k < json_array_size(kids); k++) {
            json_t *kid = json_array_get(kids, k);
            long long c = json_is_integer(kid) ? json_integer_value(kid) : -1;
            if (c < 0 || (size_t)c >= n)
                return srv_mc_fail(g->c, LUMO_ERR_RANGE, "node %zu: child %lld is not one of the %zu nodes", i, c, n);
            if (parent[c])
                return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "node %lld is the child of nodes %u and %zu: the "
                                   "hierarchy must be trees", c, parent[c] - 1, i);
            parent[c] = (uint32_t)i + 1;
        }
    }
    for (size_t s = 0; s < json_array_size(scenes); s++) {
        json_t *list = json_object_get(json_array_get(scenes, s), "nodes");
        for (size_t k = 0; k < json_array_size(list); k++) {
            json_t *r = json_array_get(list, k);
            long long c = json_is_integer(r) ? json_integer_value(r) : -1;
            if (c < 0 || (size_t)c >= n)
                return srv_mc_fail(g->c, LUMO_ERR_RANGE, "scene %zu: node %lld is not one of the %zu nodes", s, c, n);
            if (parent[c])
                return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "scene %zu lists node %lld, a child of node %u: the "
                                   "hierarchy must be trees", s, c, parent[c] - 1);
            roots[c]++;
        }
    }
    return LUMO_OK;
}

/* How many times node i is drawn: its tree root's count in the scenes (at
 * least 1), memoised in inst (0: not yet known). A parent chain that
 * comes back to a node on it is a cycle. */
static lumo_status node_instances(gltf *g, size_t i, const uint32_t *parent, const uint64_t *roots, uint64_t *inst,
                                  uint8_t *on_path)
{
    size_t top = i;
    uint64_t v;
    while (parent[top] && !inst[top]) {
        if (on_path[top])
            return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "node %zu is its own ancestor: the hierarchy must be trees",
                               top);
        on_path[top] = 1;
        top = parent[top] - 1;
    }
    v = inst[top] ? inst[top] : roots[top] ? roots[top] : 1;
    for (size_t k = i;; k = parent[k] - 1) {
        on_path[k] = 0;
        inst[k] = v;
        if (k == top)
            return LUMO_OK;
    }
}

/* Node arrays for the hierarchy checks, freed together. */
typedef struct node_work {
    uint32_t *parent;
    uint64_t *roots, *inst, *uses;
    uint8_t  *on_path;
} node_work;

/* Every mesh expanded once per node instance that draws it. */
static lumo_status check_meshes(gltf *g, json_t *nodes, json_t *meshes, node_work *w)
{
    size_t n = json_array_size(nodes);
    lumo_status st = node_parents(g, nodes, w->parent, w->roots);
    for (size_t i = 0; !st && i < n; i++) {
        long long mesh;
        if (!(st = node_instances(g, i, w->parent, w->roots, w->inst, w->on_path)) &&
            !(st = get_ref(g, json_array_get(nodes, i), "node", i, "mesh", json_array_size(meshes), 1, &mesh)) &&
            mesh >= 0)
            w->uses[mesh] += w->inst[i];
    }
    for (size_t m = 0; !st && m < json_array_size(meshes); m++)
        st = expand_mesh(g, json_array_get(meshes, m), m, w->uses[m] ? w->uses[m] : 1);
    return st;
}

/* Animation samplers, skins and images: read once each by assimp. */
static lumo_status check_other_data(gltf *g)
{
    json_t *anims = json_object_get(g->root, "animations"), *skins = json_object_get(g->root, "skins");
    json_t *images = json_object_get(g->root, "images"), *a;
    size_t i, k;
    lumo_status st = LUMO_OK;
    json_array_foreach(anims, i, a) {
        json_t *samplers = json_object_get(a, "samplers"), *sm;
        json_array_foreach(samplers, k, sm)
            if ((st = expand(g, json_object_get(sm, "input"), 1, "animation", i)) ||
                (st = expand(g, json_object_get(sm, "output"), 1, "animation", i)))
                return st;
    }
    json_array_foreach(skins, i, a)
        if ((st = expand(g, json_object_get(a, "inverseBindMatrices"), 1, "skin", i)))
            return st;
    json_array_foreach(images, i, a) {
        json_t *v = json_object_get(a, "bufferView");
        size_t nv = json_array_size(json_object_get(g->root, "bufferViews"));
        if (!v)
            continue;
        if (!json_is_integer(v) || json_integer_value(v) < 0 || (size_t)json_integer_value(v) >= nv)
            return srv_mc_fail(g->c, LUMO_ERR_RANGE, "image %zu names a bufferView the file does not have", i);
        if ((g->expanded += g->view_len[json_integer_value(v)]) > SRV_GLTF_MAX_EXPANDED)
            return srv_mc_fail(g->c, LUMO_ERR_LIMIT, "image %zu: the data assimp would copy passes %llu MiB "
                               "(SRV_GLTF_MAX_EXPANDED)", i, (unsigned long long)(SRV_GLTF_MAX_EXPANDED >> 20));
    }
    return st;
}

/* ---- the whole file --------------------------------------------------------- */

static lumo_status check_version(gltf *g)
{
    json_t *asset = json_object_get(g->root, "asset");
    const char *v = json_string_value(json_object_get(asset, "version"));
    if (!json_is_object(g->root))
        return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "the JSON is not an object");
    if (!v)
        return srv_mc_fail(g->c, LUMO_ERR_CORRUPT, "no asset.version: not a glTF file");
    if (strncmp(v, "2.", 2))
        return srv_mc_fail(g->c, LUMO_ERR_UNSUPPORTED, "glTF version '%.20s': only glTF 2.0 is read", v);
    return LUMO_OK;
}

/* Every list the checks index, each an array of bounded length. */
static lumo_status top_arrays(gltf *g, json_t **buffers, json_t **views, json_t **accessors, json_t **meshes,
                              json_t **nodes)
{
    json_t *other;
    if (top_array(g, "buffers", buffers) || top_array(g, "bufferViews", views) ||
        top_array(g, "accessors", accessors) || top_array(g, "meshes", meshes) || top_array(g, "nodes", nodes) ||
        top_array(g, "scenes", &other) || top_array(g, "animations", &other) || top_array(g, "skins", &other) ||
        top_array(g, "images", &other))
        return LUMO_ERR_CORRUPT;
    return LUMO_OK;
}

static lumo_status check_document(gltf *g)
{
    json_t *buffers, *views, *accessors, *meshes, *nodes;
    node_work w = {NULL, NULL, NULL, NULL, NULL};
    uint64_t *blen = NULL;
    size_t nn;
    lumo_status st = check_version(g);
    if (st || (st = top_arrays(g, &buffers, &views, &accessors, &meshes, &nodes)))
        return st;
    nn = json_array_size(nodes);
    blen = calloc(json_array_size(buffers) + 1, sizeof *blen);
    g->view_len = calloc(json_array_size(views) + 1, sizeof *g->view_len);
    g->acc_bytes = calloc(json_array_size(accessors) + 1, sizeof *g->acc_bytes);
    w.parent = calloc(nn + 1, sizeof *w.parent);
    w.roots = calloc(nn + 1, sizeof *w.roots);
    w.inst = calloc(nn + 1, sizeof *w.inst);
    w.on_path = calloc(nn + 1, 1);
    w.uses = calloc(json_array_size(meshes) + 1, sizeof *w.uses);
    if (!blen || !g->view_len || !g->acc_bytes || !w.parent || !w.roots || !w.inst || !w.on_path || !w.uses)
        st = srv_mc_fail(g->c, LUMO_ERR_NOMEM, "no memory for the glTF checks");
    if (!st)
        st = check_buffers(g, buffers, blen);
    if (!st)
        st = check_views(g, views, blen, json_array_size(buffers));
    for (size_t i = 0; !st && i < json_array_size(accessors); i++)
        st = check_accessor(g, json_array_get(accessors, i), i, views);
    if (!st)
        st = check_meshes(g, nodes, meshes, &w);
    if (!st)
        st = check_other_data(g);
    free(blen), free(g->view_len), free(g->acc_bytes);
    free(w.parent), free(w.roots), free(w.inst), free(w.on_path), free(w.uses);
    return st;
}

lumo_status srv_mc_check_gltf(srv_mc *c, int glb)
{
    gltf g;
    json_error_t je;
    const uint8_t *json = c->base;
    size_t len = (size_t)(c->end - c->base);
    lumo_status st;
    memset(&g, 0, sizeof g);
    g.c = c;
    if (glb && (st = glb_chunks(&g, &json, &len)))
        return st;
    if (len > SRV_GLTF_MAX_JSON)
        return srv_mc_fail(c, LUMO_ERR_LIMIT, "%zu bytes of JSON, at most %llu MiB are read (SRV_GLTF_MAX_JSON)", len,
                           (unsigned long long)(SRV_GLTF_MAX_JSON >> 20));
    g.root = json_loadb((const char *)json, len, JSON_REJECT_DUPLICATES, &je);
    if (!g.root) {
        /* jansson quotes the file's bytes "near" the error: a control
         * character there would break the one-line reason */
        for (char *t = je.text; *t; t++)
            if ((unsigned char)*t < 0x20 || *t == 0x7f)
                *t = '?';
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "JSON line %d, column %d: %.120s", je.line, je.column, je.text);
    }
    st = check_document(&g);
    json_decref(g.root);
    return st;
}
