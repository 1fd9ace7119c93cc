/* pm_meshes.h — generated meshes for the progressive-mesh tests. */
#ifndef LUMO_TEST_PM_MESHES_H
#define LUMO_TEST_PM_MESHES_H
#include <stdint.h>

typedef struct {
    float    *xyz;
    uint8_t  *rgb;    /* 3 per vertex, or NULL: albedo */
    uint32_t *tris;
    uint32_t  nv, nf;
} pm_test_mesh;

/* "sphere", "grid", "cornell" (coloured walls), "seam" (a sphere whose two
 * hemispheres differ in albedo: a colour seam), "scan", "tiny", "wall" (a
 * flat 8x8 quad), "box" (a closed box of flat quads).
 * 0, or -1 for an unknown name. */
int  pm_test_mesh_make(const char *name, pm_test_mesh *m);
void pm_test_mesh_free(pm_test_mesh *m);

#endif
