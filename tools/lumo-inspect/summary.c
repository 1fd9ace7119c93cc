/* tools/lumo-inspect/summary.c — `lumo-inspect FILE`: header, chunk table, scene info
 * and IVG descriptor of a package, as decoded by the client reader. */
#include <stdio.h>
#include <stdlib.h>
#include "inspect.h"

static double q16(int32_t v) { return (double)v / 65536.0; }

static void print_type(uint32_t t)
{
    for (int i = 0; i < 4; i++) {
        int c = (int)((t >> (8 * i)) & 0xFF);
        putchar(c >= 32 && c < 127 ? c : '?');
    }
}

static void print_chunks(const lumo_package *pkg)
{
    printf("package   version %u.%u, %zu bytes, %u chunks\n", pkg->version_major, pkg->version_minor,
           pkg->size, pkg->chunk_count);
    for (uint32_t i = 0; i < pkg->chunk_count; i++) {
        lumo_pkg_chunk c;
        lumo_package_chunk(pkg, i, &c);
        printf("  chunk %2u ", i);
        print_type(c.type);
        printf("  offset %10u  length %10u  crc32 %08x\n", c.offset, c.length, c.crc);
    }
}

static const char *k_kinds[] = {"point", "spot", "directional", "area"};

static int print_scene(const lumo_package *pkg)
{
    lumo_pkg_info in;
    lumo_status st = lumo_package_info(pkg, &in);
    if (st) {
        fprintf(stderr, "lumo-inspect: error: scene info: %s\n", lumo_strerror(st));
        return -1;
    }
    printf("scene     %u meshes, %u triangles, %u lights\n", in.mesh_count, in.triangle_count, in.light_count);
    printf("bounds    (%.4f, %.4f, %.4f) .. (%.4f, %.4f, %.4f) m\n", q16(in.bmin[0]), q16(in.bmin[1]),
           q16(in.bmin[2]), q16(in.bmax[0]), q16(in.bmax[1]), q16(in.bmax[2]));
    printf("camera    %g,%g,%g:%g,%g,%g:%g,%g,%g:%g\n", q16(in.eye[0]), q16(in.eye[1]), q16(in.eye[2]),
           q16(in.target[0]), q16(in.target[1]), q16(in.target[2]), q16(in.up[0]), q16(in.up[1]),
           q16(in.up[2]), q16(in.fovy_deg));
    for (uint32_t i = 0; i < in.light_count; i++) {
        lumo_pkg_light l;
        if ((st = lumo_package_light(pkg, i, &l)) != LUMO_OK) {
            fprintf(stderr, "lumo-inspect: error: light %u: %s\n", i, lumo_strerror(st));
            return -1;
        }
        printf("light %u   %s at (%.3f, %.3f, %.3f) dir (%.3f, %.3f, %.3f) power (%.3f, %.3f, %.3f)", i,
               k_kinds[l.kind], q16(l.pos[0]), q16(l.pos[1]), q16(l.pos[2]), l.dir[0] / 16384.0,
               l.dir[1] / 16384.0, l.dir[2] / 16384.0, q16((int32_t)l.power[0]), q16((int32_t)l.power[1]),
               q16((int32_t)l.power[2]));
        if (l.kind == LUMO_LIGHT_SPOT)
            printf(" half-angle %.2f deg", q16(l.half_angle_deg));
        putchar('\n');
    }
    return 0;
}

static void print_meshes(const lumo_package *pkg)
{
    lumo_pkg_mesh_info mi;
    for (uint32_t i = 0; lumo_package_mesh_info(pkg, i, &mi) == LUMO_OK; i++)
        printf("mesh %-4u %u vertices, %u triangles%s\n", i, mi.nverts, mi.ntris,
               mi.flags & LUMO_PKG_MESH_EMITTER ? " (area-light emitter)" : "");
}

static void print_ivg(const lumo_package *pkg)
{
    lumo_ivg_desc d;
    const uint8_t *p;
    uint32_t len;
    if (lumo_package_ivg_desc(pkg, &d)) {
        printf("ivg       none\n");
        return;
    }
    lumo_package_find(pkg, LUMO_PKG_IVGD, 0, &p, &len);
    uint32_t spp = p[32] | p[33] << 8 | p[34] << 16 | (uint32_t)p[35] << 24;
    uint32_t valid = p[44] | p[45] << 8 | p[46] << 16 | (uint32_t)p[47] << 24;
    printf("ivg       %ux%ux%u vertices (%u valid), %u spp, box (%.4f, %.4f, %.4f) .. (%.4f, %.4f, %.4f)\n",
           d.dims[0], d.dims[1], d.dims[2], valid, spp, q16(d.bmin[0]), q16(d.bmin[1]), q16(d.bmin[2]),
           q16(d.bmax[0]), q16(d.bmax[1]), q16(d.bmax[2]));
}

int inspect_summary(int argc, char **argv);
int inspect_summary(int argc, char **argv)
{
    const char *path = inspect_file_arg(argc, argv);
    uint8_t *data;
    size_t len;
    lumo_package pkg;
    if (!path || argc != 2) {
        fprintf(stderr, "lumo-inspect: error: give one package file (try --help)\n");
        return 1;
    }
    if (inspect_load(path, &data, &len, &pkg))
        return 1;
    print_chunks(&pkg);
    int rc = print_scene(&pkg);
    if (!rc) {
        print_meshes(&pkg);
        print_ivg(&pkg);
    }
    free(data);
    return rc ? 1 : 0;
}
