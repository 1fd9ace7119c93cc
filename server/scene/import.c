/* import.c — meshes, materials and lights from files through assimp's C API. */
#include <assimp/cimport.h>
#include <assimp/light.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "scene/import.h"
#include "scene/import_io.h"
#include "scene/model_check.h"

#define DEFAULT_ALBEDO 0.8f
#define MAX_ALBEDO 0.98f   /* reflection must never create light */

srv_xform srv_xform_identity(void)
{
    srv_xform x = {{1, 1, 1}, {0, 1, 0}, 0.0f, {0, 0, 0}};
    return x;
}

/* Rodrigues' rotation of p about the unit axis k. */
static vec3 rotate(vec3 p, vec3 k, float deg)
{
    float a = deg * (float)M_PI / 180.0f, c = cosf(a), s = sinf(a);
    return v3_add(v3_add(v3_scale(p, c), v3_scale(v3_cross(k, p), s)),
                  v3_scale(k, v3_dot(k, p) * (1.0f - c)));
}

vec3 srv_xform_apply(const srv_xform *x, vec3 p)
{
    p = v3_mul(p, x->scale);
    if (x->angle_deg != 0.0f && v3_len(x->axis) > 0.0f)
        p = rotate(p, v3_norm(x->axis), x->angle_deg);
    return v3_add(p, x->translate);
}

static vec3 clamp_albedo(vec3 a)
{
    return v3(fminf(fmaxf(a.x, 0.0f), MAX_ALBEDO), fminf(fmaxf(a.y, 0.0f), MAX_ALBEDO),
              fminf(fmaxf(a.z, 0.0f), MAX_ALBEDO));
}

/* The material's diffuse colour (glTF: base colour), or 0 when it has none
 * (assimp's stand-in "DefaultMaterial" for files without materials counts
 * as none, so such meshes get lumo's documented default). */
static int material_albedo(const struct aiScene *sc, unsigned idx, vec3 *out)
{
    struct aiColor4D c;
    struct aiString name;
    if (idx >= sc->mNumMaterials)
        return 0;
    if (aiGetMaterialString(sc->mMaterials[idx], AI_MATKEY_NAME, &name) == aiReturn_SUCCESS &&
        !strcmp(name.data, AI_DEFAULT_MATERIAL_NAME))
        return 0;
    if (aiGetMaterialColor(sc->mMaterials[idx], AI_MATKEY_BASE_COLOR, &c) != aiReturn_SUCCESS &&
        aiGetMaterialColor(sc->mMaterials[idx], AI_MATKEY_COLOR_DIFFUSE, &c) != aiReturn_SUCCESS)
        return 0;
    *out = v3(c.r, c.g, c.b);
    return 1;
}

static lumo_status import_mesh(srv_scene *s, const struct aiScene *sc, const struct aiMesh *am,
                               const srv_xform *x, const vec3 *albedo, const char *path)
{
    uint32_t ntris = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++)
        ntris += am->mFaces[f].mNumIndices == 3;
    if (ntris == 0)
        return LUMO_OK;   /* point or line primitives: nothing to shade */
    const char *base = strrchr(path, '/');
    srv_mesh *m = srv_scene_add_mesh(s, base ? base + 1 : path, am->mNumVertices, ntris);
    if (!m)
        return LUMO_ERR_NOMEM;
    vec3 mat = v3(DEFAULT_ALBEDO, DEFAULT_ALBEDO, DEFAULT_ALBEDO);
    material_albedo(sc, am->mMaterialIndex, &mat);
    for (unsigned v = 0; v < am->mNumVertices; v++) {
        struct aiVector3D p = am->mVertices[v];
        m->pos[v] = srv_xform_apply(x, v3(p.x, p.y, p.z));
        /* Priority: the caller's override, vertex colours, the material. */
        vec3 a = mat;
        if (albedo)
            a = *albedo;
        else if (am->mColors[0])
            a = v3(am->mColors[0][v].r, am->mColors[0][v].g, am->mColors[0][v].b);
        m->albedo[v] = clamp_albedo(a);
    }
    uint32_t t = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        if (am->mFaces[f].mNumIndices != 3)
            continue;
        for (int k = 0; k < 3; k++)
            m->tris[3 * t + k] = am->mFaces[f].mIndices[k];
        t++;
    }
    return LUMO_OK;
}

/* The node's transform to world space (the file's own hierarchy). */
static struct aiMatrix4x4 node_world(const struct aiNode *n)
{
    struct aiMatrix4x4 m = n->mTransformation;
    for (const struct aiNode *p = n->mParent; p; p = p->mParent) {
        struct aiMatrix4x4 t = p->mTransformation;
        aiMultiplyMatrix4(&t, &m);
        m = t;
    }
    return m;
}

/* The node named like the light: it places the light in the file. */
static const struct aiNode *find_node(const struct aiNode *n, const char *name, int depth)
{
    if (!n || depth > 64)
        return NULL;
    if (!strcmp(n->mName.data, name))
        return n;
    for (unsigned c = 0; c < n->mNumChildren; c++) {
        const struct aiNode *hit = find_node(n->mChildren[c], name, depth + 1);
        if (hit)
            return hit;
    }
    return NULL;
}

static lumo_status import_light(srv_scene *s, const struct aiScene *sc, const struct aiLight *al,
                                const srv_xform *x)
{
    struct aiVector3D p = al->mPosition, d = al->mDirection;
    const struct aiNode *node = find_node(sc->mRootNode, al->mName.data, 0);
    if (node) {
        struct aiMatrix4x4 w = node_world(node);
        struct aiMatrix3x3 r;
        aiMatrix3FromMatrix4(&r, &w);
        aiTransformVecByMatrix4(&p, &w);
        aiTransformVecByMatrix3(&d, &r);
    }
    srv_light l;
    memset(&l, 0, sizeof l);
    vec3 col = v3(al->mColorDiffuse.r, al->mColorDiffuse.g, al->mColorDiffuse.b);
    l.pos = srv_xform_apply(x, v3(p.x, p.y, p.z));
    srv_xform rot = *x;
    rot.translate = v3(0, 0, 0);
    l.dir = v3_norm(srv_xform_apply(&rot, v3(d.x, d.y, d.z)));
    l.power = v3_scale(col, 4.0f * (float)M_PI);   /* assimp colour as intensity W/sr */
    switch (al->mType) {
    case aiLightSource_POINT: l.kind = LUMO_LIGHT_POINT; break;
    case aiLightSource_SPOT:
        l.kind = LUMO_LIGHT_SPOT;
        l.half_angle_deg = al->mAngleOuterCone * 180.0f / (float)M_PI;
        l.cos_half = cosf(al->mAngleOuterCone);
        break;
    case aiLightSource_DIRECTIONAL: l.kind = LUMO_LIGHT_DIRECTIONAL; l.power = col; break;
    default: return LUMO_OK;   /* ambient / area lights of the file format: not imported */
    }
    if (!v3_finite(l.pos) || !v3_finite(l.dir) || !v3_finite(l.power) ||
        (l.kind != LUMO_LIGHT_POINT && v3_len(l.dir) == 0.0f))
        return LUMO_OK;   /* a light the file cannot place is skipped, not guessed */
    return srv_scene_add_light(s, &l);
}

/* What came out of assimp, checked before lumo uses it: positions finite
 * and bounded, every kept face a triangle of existing vertices (assimp's
 * ValidateDataStructure checks the indices too; this is the backstop for
 * every format lumo does not read through itself). */
static lumo_status check_mesh(const char *path, unsigned i, const struct aiMesh *am, char *err, size_t errlen)
{
    lumo_status st = am->mVertices ? srv_model_check_positions(path, i, &am->mVertices[0].x, am->mNumVertices, err,
                                                               errlen)
                                   : LUMO_OK;
    if (st)
        return st;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *fc = &am->mFaces[f];
        if (fc->mNumIndices > 3) {
            snprintf(err, errlen, "%s: mesh %u, face %u: %u vertices after triangulation", path, i, f, fc->mNumIndices);
            return LUMO_ERR_CORRUPT;
        }
        for (unsigned k = 0; k < fc->mNumIndices; k++)
            if (fc->mIndices[k] >= am->mNumVertices) {
                snprintf(err, errlen, "%s: mesh %u, face %u: vertex index %u is outside [0, %u)", path, i, f,
                         fc->mIndices[k], am->mNumVertices);
                return LUMO_ERR_RANGE;
            }
    }
    return LUMO_OK;
}

/* lumo's own checks (which refuse every format they do not check), then
 * assimp's reader with its structure validation. */
static lumo_status read_scene(const char *path, const struct aiScene **out, char *err, size_t errlen)
{
    srv_model_format fmt = SRV_MODEL_OTHER;
    lumo_status st = srv_model_check_file(path, &fmt, err, errlen);
    if (st)
        return st;
    *out = aiImportFileEx(path, aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType |
                                    aiProcess_ValidateDataStructure, srv_import_io());
    if (!*out || !(*out)->mRootNode || (*out)->mNumMeshes == 0) {
        const char *why = *out ? "no mesh in the file" : aiGetErrorString();
        snprintf(err, errlen, "%s: cannot import: %s", path, why && *why ? why : "unknown format");
        if (*out)
            aiReleaseImport(*out);
        return LUMO_ERR_CORRUPT;
    }
    for (unsigned i = 0; i < (*out)->mNumMeshes; i++)
        if ((st = check_mesh(path, i, (*out)->mMeshes[i], err, errlen))) {
            aiReleaseImport(*out);
            return st;
        }
    return LUMO_OK;
}

lumo_status srv_import_file(srv_scene *s, const char *path, const srv_xform *x, const vec3 *albedo,
                            char *err, size_t errlen)
{
    const struct aiScene *sc = NULL;
    lumo_status rc = read_scene(path, &sc, err, errlen);
    if (rc)
        return rc;
    size_t before = srv_scene_triangle_count(s);
    for (unsigned i = 0; i < sc->mNumMeshes && !rc; i++)
        rc = import_mesh(s, sc, sc->mMeshes[i], x, albedo, path);
    for (unsigned i = 0; i < sc->mNumLights && !rc; i++)
        rc = import_light(s, sc, sc->mLights[i], x);
    aiReleaseImport(sc);
    if (rc) {
        snprintf(err, errlen, "%s: out of memory", path);
        return rc;
    }
    if (srv_scene_triangle_count(s) == before) {
        snprintf(err, errlen, "%s: no triangle in the file", path);
        return LUMO_ERR_CORRUPT;
    }
    return LUMO_OK;
}
