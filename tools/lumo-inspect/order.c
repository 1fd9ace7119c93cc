/* tools/lumo-inspect/order.c — `lumo-inspect --order FILE`: the IVG's stratified
 * streaming order (IVGS, docs/package-format.md) round by round, as the
 * client decodes it (lumo_package_ivg_order): "round first records ivgq_offset
 * ivgq_bytes ivgf_offset ivgf_bytes", offsets inside each bundle's payload. */
#include <stdio.h>
#include <stdlib.h>
#include "inspect.h"

static int run_order(int argc, char **argv)
{
    const char *path = inspect_file_arg(argc, argv);
    uint8_t *data;
    size_t len;
    lumo_package pkg;
    lumo_ivg_order o;
    if (!path) {
        fprintf(stderr, "lumo-inspect: error: --order needs a package file\n");
        return 1;
    }
    if (inspect_load(path, &data, &len, &pkg))
        return 1;
    lumo_status st = lumo_package_ivg_order(&pkg, &o);
    if (st) {
        fprintf(stderr, "lumo-inspect: error: %s: IVG order (IVGS): %s\n", path,
                st == LUMO_ERR_RANGE ? "the package has none" : lumo_strerror(st));
        free(data);
        return 1;
    }
    printf("# %u rounds, %u slices along %c, %u records, seed %llu\n", o.rounds, o.slices, "xyz"[o.axis], o.records,
           (unsigned long long)o.seed);
    printf("# round first records ivgq_offset ivgq_bytes ivgf_offset ivgf_bytes\n");
    for (uint32_t r = 0; r < o.rounds; r++) {
        uint32_t q = lumo_ivg_order_offset(&o, LUMO_IVG_FORM_QUANTIZED, r);
        uint32_t f = lumo_ivg_order_offset(&o, LUMO_IVG_FORM_FLOAT, r);
        printf("%u %u %u %u %u %u %u\n", r, lumo_ivg_order_first(&o, r),
               lumo_ivg_order_first(&o, r + 1) - lumo_ivg_order_first(&o, r), q,
               lumo_ivg_order_offset(&o, LUMO_IVG_FORM_QUANTIZED, r + 1) - q, f,
               lumo_ivg_order_offset(&o, LUMO_IVG_FORM_FLOAT, r + 1) - f);
    }
    free(data);
    return 0;
}

INSPECT_COMMAND(order_cmd, "--order",
                "--order FILE.lumo   the IVG streaming order (IVGS), one line per round: "
                "round first records ivgq_offset ivgq_bytes ivgf_offset ivgf_bytes",
                run_order)
