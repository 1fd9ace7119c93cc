/* pm_load.c — mesh files for the progressive-mesh tools (assimp through
 * server/scene/import.c in; binary PLY out, which stock draco_encoder reads). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "scene/import.h"
#include "pm/pm_load.h"

static uint8_t to_byte(float a)
{
    float v = a * 255.0f + 0.5f;
    return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

static lumo_status merge(const srv_scene *s, float **xyz, uint8_t **rgb, uint32_t *nv,
                         uint32_t **tris, uint32_t *nf)
{
    size_t v = 0, f = 0;
    for (size_t m = 0; m < s->nmeshes; m++)
        v += s->meshes[m].nverts, f += s->meshes[m].ntris;
    *xyz = malloc(sizeof **xyz * 3 * (v ? v : 1));
    *tris = malloc(sizeof **tris * 3 * (f ? f : 1));
    if (rgb && !(*rgb = malloc(3 * (v ? v : 1))))
        return LUMO_ERR_NOMEM;
    if (!*xyz || !*tris)
        return LUMO_ERR_NOMEM;
    if (v > UINT32_MAX / 4 || f > UINT32_MAX / 4)
        return LUMO_ERR_LIMIT;
    *nv = 0, *nf = 0;
    for (size_t m = 0; m < s->nmeshes; m++) {
        const srv_mesh *me = &s->meshes[m];
        for (uint32_t i = 0; i < me->nverts; i++) {
            float *p = *xyz + 3 * (size_t)(*nv + i);
            p[0] = me->pos[i].x, p[1] = me->pos[i].y, p[2] = me->pos[i].z;
            if (rgb) {
                uint8_t *c = *rgb + 3 * (size_t)(*nv + i);
                c[0] = to_byte(me->albedo[i].x), c[1] = to_byte(me->albedo[i].y), c[2] = to_byte(me->albedo[i].z);
            }
        }
        for (size_t i = 0; i < 3 * (size_t)me->ntris; i++)
            (*tris)[3 * (size_t)*nf + i] = me->tris[i] + *nv;
        *nv += me->nverts, *nf += me->ntris;
    }
    return LUMO_OK;
}

lumo_status srv_pm_load(const char *path, float **xyz, uint8_t **rgb, uint32_t *nv, uint32_t **tris,
                        uint32_t *nf, char *err, size_t errlen)
{
    srv_scene s;
    srv_xform x = srv_xform_identity();
    srv_scene_init(&s);
    *xyz = NULL, *tris = NULL;
    if (rgb)
        *rgb = NULL;
    lumo_status rc = srv_import_file(&s, path, &x, NULL, err, errlen);
    if (!rc)
        rc = srv_scene_check_range(&s, err, errlen);   /* the mesh is named for the file */
    if (!rc && (rc = merge(&s, xyz, rgb, nv, tris, nf)))
        snprintf(err, errlen, "%s: out of memory", path);
    srv_scene_free(&s);
    if (rc) {
        free(*xyz), free(*tris);
        *xyz = NULL, *tris = NULL;
        if (rgb)
            free(*rgb), *rgb = NULL;
    if (rgb)
        *rgb = NULL;
    }
    return rc;
}

lumo_status srv_pm_write_ply(const char *path, const float *xyz, uint32_t nv, const uint32_t *tris,
                             uint32_t nf)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return LUMO_ERR_IO;
    fprintf(f, "ply\nformat binary_little_endian 1.0\nelement vertex %u\n"
               "property float x\nproperty float y\nproperty float z\nelement face %u\n"
               "property list uchar int vertex_indices\nend_header\n", nv, nf);
    fwrite(xyz, sizeof(float), 3 * (size_t)nv, f);  /* the host is little-endian */
    for (uint32_t i = 0; i < nf; i++) {
        uint8_t three = 3;
        fwrite(&three, 1, 1, f);
        fwrite(tris + 3 * (size_t)i, sizeof(uint32_t), 3, f);
    }
    return fclose(f) ? LUMO_ERR_IO : LUMO_OK;
}
