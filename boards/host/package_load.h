/*
 * package_load.h — a .lumo package (docs/package-format.md) into a host
 * scene: meshes, lights, default camera, and the IVG in an arena.
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

/* 0 on success; else a message in err. */
int host_package_load(const char *path, host_scene *s, host_ivg *ivg, char *err, size_t errlen);
void host_ivg_free(host_ivg *ivg);

#endif
