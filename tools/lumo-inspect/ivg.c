/* tools/lumo-inspect/ivg.c — `lumo-inspect --ivg [--quantized] FILE`: one line per grid
 * vertex and hemisphere, "i j k axis valid dx dy dz r g b", from the
 * package's IVG decoded by the client (lumo_ivg_apply_bundle). valid is 0
 * for vertices the bake marked solid (their values print as zero). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/ivg.h"
#include "inspect.h"

static const char *k_axes[LUMO_IVG_AXES] = {"+x", "-x", "+y", "-y", "+z", "-z"};

static void print_grid(const lumo_ivg *g)
{
    const lumo_ivg_desc *d = lumo_ivg_get_desc(g);
    for (uint32_t v = 0; v < lumo_ivg_vertex_count(g); v++) {
        uint32_t i = v % d->dims[0], j = (v / d->dims[0]) % d->dims[1], k = v / ((uint32_t)d->dims[0] * d->dims[1]);
        int valid = lumo_ivg_is_received(g, v);
        for (int a = 0; a < LUMO_IVG_AXES; a++) {
            lumo_ivg_entry e;
            (void)lumo_ivg_entry_get(g, v, (lumo_ivg_axis)a, &e);
            printf("%u %u %u %s %d %.5f %.5f %.5f %.6f %.6f %.6f\n", i, j, k, k_axes[a], valid,
                   valid ? e.d[0] / 16384.0 : 0.0, valid ? e.d[1] / 16384.0 : 0.0,
                   valid ? e.d[2] / 16384.0 : 0.0, valid ? e.c[0] / 65536.0 : 0.0,
                   valid ? e.c[1] / 65536.0 : 0.0, valid ? e.c[2] / 65536.0 : 0.0);
        }
    }
}

static int run_ivg(int argc, char **argv)
{
    const char *path = inspect_file_arg(argc, argv);
    lumo_ivg_form form = LUMO_IVG_FORM_FLOAT;
    uint8_t *data;
    size_t len;
    lumo_package pkg;
    lumo_ivg_desc d;
    for (int i = 1; i < argc - 1; i++)
        if (!strcmp(argv[i], "--quantized"))
            form = LUMO_IVG_FORM_QUANTIZED;
        else if (strcmp(argv[i], "--ivg")) {
            fprintf(stderr, "lumo-inspect: error: unknown option '%s' for --ivg\n", argv[i]);
            return 1;
        }
    if (!path) {
        fprintf(stderr, "lumo-inspect: error: --ivg needs a package file\n");
        return 1;
    }
    if (inspect_load(path, &data, &len, &pkg))
        return 1;
    lumo_status st = lumo_package_ivg_desc(&pkg, &d);
    if (st == LUMO_ERR_RANGE && lumo_package_find(&pkg, LUMO_PKG_IVGD, 0, &(const uint8_t *){0}, &(uint32_t){0})) {
        fprintf(stderr, "lumo-inspect: error: %s: the package has no IVG\n", path);
        free(data);
        return 1;
    }
    size_t bytes = st ? 0 : lumo_ivg_memory_size(&d) + LUMO_ARENA_SLACK;
    void *mem = bytes ? malloc(bytes) : NULL;
    lumo_arena arena;
    lumo_ivg *g;
    if (!st && !mem)
        st = LUMO_ERR_NOMEM;
    if (!st) {
        lumo_arena_init(&arena, mem, bytes);
        st = lumo_ivg_create(&g, &arena, &d);
    }
    if (!st)
        st = lumo_package_load_ivg(&pkg, g, form, NULL);
    if (!st)
        print_grid(g);
    else
        fprintf(stderr, "lumo-inspect: error: %s: IVG: %s\n", path, lumo_strerror(st));
    free(mem);
    free(data);
    return st ? 1 : 0;
}

INSPECT_COMMAND(ivg_cmd, "--ivg",
                "--ivg [--quantized] FILE.lumo  one line per vertex and hemisphere: "
                "i j k axis valid dx dy dz r g b",
                run_ivg)
