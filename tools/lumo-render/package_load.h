/*
 * package_load.h — a .lumo package (docs/package-format.md) into a host
 * scene: meshes, lights, default camera, and the IVG in an arena.
 *
 * The package is fed to the SDK's client session (lumo/session.h), exactly
 * as a device takes it: progressive streams refined to the asked level of
 * detail (seed 000 §4.2, docs/progressive-mesh.md) or raw MESH chunks, the
 * IVG with push-pull, all in one arena sized by the SDK.
 */
#ifndef LUMO_HOST_PACKAGE_LOAD_H
#define LUMO_HOST_PACKAGE_LOAD_H

#include <stddef.h>
#include "lumo/ivg.h"
#include "mesh_build.h"
#include "session_scene.h"

typedef struct host_ivg {
    const lumo_ivg *grid; /* NULL when the package has none */
    void *memory;         /* the session's arena (the grid lives in it) */
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

/* Parse --lod: "all", a vertex count "N" (1..4294967295) or a percentage
 * "P%" (0..100), through lumo_host/options.h. 0 on success, else -1 with
 * "--lod VALUE: why" in err (which may be NULL). */
int host_lod_parse(const char *s, host_lod *lod, char *err, size_t errlen);

/* Load a package; lod NULL means the full meshes; stats may be NULL.
 * 0 on success; else a one-line message in err. */
int host_package_load(const char *path, const host_lod *lod, host_scene *s, host_ivg *ivg,
                      host_load_stats *stats, char *err, size_t errlen);
void host_ivg_free(host_ivg *ivg);

#endif
