/* tools/lumo-inspect/summary.c — `lumo-inspect FILE`: header, chunk table, scene info,
 * IVG descriptor, IVG streaming order (IVGS) and recommended interleaving
 * (ORDR) of a package, as decoded by the client reader. */
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

/* 0 when the scene was printed, 1 when the package has no INFO chunk (a
 * stream-only package of lumo-pm build: listed, nothing to draw), -1 on a
 * refusal. */
static int print_scene(const lumo_package *pkg)
{
    lumo_pkg_info in;
    const uint8_t *p;
    uint32_t len;
    if (lumo_package_find(pkg, LUMO_PKG_INFO, 0, &p, &len) == LUMO_ERR_RANGE) {
        printf("scene     none: no INFO chunk (a stream-only package, as lumo-pm build writes;"
               " lumo-render and lumo-server refuse it)\n");
        return 1;
    }
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
        /* Only what the kind has: a directional light no position, a
         * point light no direction. */
        printf("light %u   %s", i, k_kinds[l.kind]);
        if (l.kind != LUMO_LIGHT_DIRECTIONAL)
            printf(" at (%.3f, %.3f, %.3f)", q16(l.pos[0]), q16(l.pos[1]), q16(l.pos[2]));
        if (l.kind != LUMO_LIGHT_POINT)
            printf(" dir (%.3f, %.3f, %.3f)", l.dir[0] / 16384.0, l.dir[1] / 16384.0, l.dir[2] / 16384.0);
        printf(" %s (%.3f, %.3f, %.3f)", l.kind == LUMO_LIGHT_DIRECTIONAL ? "irradiance" : "power",
               q16((int32_t)l.power[0]), q16((int32_t)l.power[1]), q16((int32_t)l.power[2]));
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

static const char k_axis[3] = {'x', 'y', 'z'};

/* IVGS: one line for the order, then the rounds grouped into runs of the
 * same record count (round 0, the full rounds, the shorter tail): records
 * and bytes of each run in both forms. `lumo-inspect --order` lists every
 * round. */
static int print_ivg_order(const lumo_package *pkg)
{
    lumo_ivg_order o;
    const uint8_t *p;
    uint32_t len;
    if (lumo_package_find(pkg, LUMO_PKG_IVGS, 0, &p, &len)) {
        printf("ivg order none\n");
        return 0;
    }
    lumo_status st = lumo_package_ivg_order(pkg, &o);
    if (st) {
        fprintf(stderr, "lumo-inspect: error: IVG order (IVGS): %s\n", lumo_strerror(st));
        return -1;
    }
    printf("ivg order %u rounds over %u slices along %c, %u records, seed %llu\n", o.rounds, o.slices,
           k_axis[o.axis], o.records, (unsigned long long)o.seed);
    for (uint32_t r = 0; r < o.rounds;) {
        uint32_t n = lumo_ivg_order_first(&o, r + 1) - lumo_ivg_order_first(&o, r), e = r + 1;
        while (e < o.rounds && lumo_ivg_order_first(&o, e + 1) - lumo_ivg_order_first(&o, e) == n)
            e++;
        printf("  rounds %5u..%-5u %3u record%s each  records %8u..%-8u IVGQ %9u bytes  IVGF %9u bytes\n", r,
               e - 1, n, n == 1 ? " " : "s", lumo_ivg_order_first(&o, r), lumo_ivg_order_first(&o, e) - 1,
               lumo_ivg_order_offset(&o, LUMO_IVG_FORM_QUANTIZED, e) - lumo_ivg_order_offset(&o, LUMO_IVG_FORM_QUANTIZED, r),
               lumo_ivg_order_offset(&o, LUMO_IVG_FORM_FLOAT, e) - lumo_ivg_order_offset(&o, LUMO_IVG_FORM_FLOAT, r));
        r = e;
    }
    return 0;
}

/* ORDR: the prefix and the cycle, one step a line. */
static int print_order(const lumo_package *pkg)
{
    lumo_scene_order o;
    const uint8_t *p;
    uint32_t len;
    if (lumo_package_find(pkg, LUMO_PKG_ORDR, 0, &p, &len)) {
        printf("order     none\n");
        return 0;
    }
    lumo_status st = lumo_package_order(pkg, &o);
    if (st) {
        fprintf(stderr, "lumo-inspect: error: streaming order (ORDR): %s\n", lumo_strerror(st));
        return -1;
    }
    printf("order     %u prefix steps, then a cycle of %u\n", o.prefix, o.cycle);
    for (uint32_t i = 0; i < o.prefix + o.cycle; i++) {
        lumo_scene_step s;
        lumo_scene_order_step(&o, i, &s);
        if (s.channel == LUMO_CHANNEL_GEOMETRY)
            printf("  %-6s  geometry mesh %u, %u vertices\n", i < o.prefix ? "prefix" : "cycle", s.mesh, s.amount);
        else
            printf("  %-6s  lighting, %u round%s\n", i < o.prefix ? "prefix" : "cycle", s.amount,
                   s.amount == 1 ? "" : "s");
    }
    return 0;
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
        rc = print_ivg_order(&pkg);
        if (!rc)
            rc = print_order(&pkg);
    }
    free(data);
    return rc < 0 ? 1 : 0;
}
