/*
 * package_load.h — a .lumo package (docs/package-format.md) into a host
 * scene: meshes, lights, default camera, and the IVG in an arena.
 *
 * Meshes come from the progressive streams (PMSH chunks, one per mesh)
 * when the package has them, decoded exactly as a device does it: the
 * SDK's lumo_pmesh in an arena sized from the stream header, batches
 * applied in order (seed 000 §4.2, docs/progressive-mesh.md). A package
 * without streams gives its raw MESH chunks.
 */
#ifndef LUMO_HOST_PACKAGE_LOAD_H
#define LUMO_HOST_PACKAGE_LOAD_H

#include <stddef.h>
#include "lumo/ivg.h"
#include "mesh_build.h"

typedef struct host_ivg {
    lumo_ivg *grid;       /* NULL when the package has none */
    void *memory;         /* the arena's buffer */
    uint32_t received;
} host_ivg;

/* The level of detail taken from each progressive stream. `vertices` > 0:
 * at most that many vertices per mesh. Else `fraction` in [0, 1] of the
 * vertices streamed after the base mesh, rounded up (0: the base mesh, 1:
 * the full mesh, so a small mesh keeps its shape at any fraction above
 * 0). Never fewer than the base mesh's vertices: the base arrives whole. */
typedef struct host_lod {
    uint32_t vertices;
    double   fraction;
} host_lod;

/* What host_package_load took. */
typedef struct host_load_stats {
    uint32_t progressive;     /* meshes from PMSH streams (0: raw MESH chunks) */
    uint32_t vertices;        /* vertices of the level loaded, all meshes */
    uint32_t full_vertices;   /* vertices of the full meshes */
} host_load_stats;

/* Parse "all", a vertex count "N" (>= 1) or a percentage "P%" (0..100).
 * 0 on success. */
int host_lod_parse(const char *s, host_lod *lod);

/* Load a package; lod NULL means the full meshes; stats may be NULL.
 * 0 on success; else a one-line message in err. */
int host_package_load(const char *path, const host_lod *lod, host_scene *s, host_ivg *ivg,
                      host_load_stats *stats, char *err, size_t errlen);
void host_ivg_free(host_ivg *ivg);

#endif
