/* fuzz_checkpoint.c — the checkpoint reader (server/bake/checkpoint.c) on
 * arbitrary bytes. The first 8 bytes choose the work's item count and key,
 * so the rest may carry a matching header; whatever it accepts must fit the
 * work (every flagged chunk in range, the valid prefix within the input). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bake/checkpoint.h"

static lumo_status no_run(void *ctx, size_t first, size_t count, uint8_t *out, uint64_t *rays)
{
    (void)ctx, (void)first, (void)count, (void)out, (void)rays;
    return LUMO_ERR_STATE;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 9)
        return 0;
    size_t items = 1 + (data[0] | (size_t)data[1] << 8) % 5000;
    srv_work w = {.name = "fuzz", .items = items, .item_bytes = 1 + data[2] % 16,
                  .chunk_items = srv_work_chunk_items(items), .key = data[3], .run = no_run};
    uint8_t *out = malloc(w.items * w.item_bytes), *done = calloc(srv_work_chunks(&w), 1);
    FILE *f = fmemopen((void *)(data + 8), size - 8, "rb");
    size_t resumed = 0, flagged = 0;
    long end = 0;
    char err[256];
    if (f && out && done) {
        srv_ckpt_read(f, &w, out, done, &resumed, &end, err, sizeof err);
        for (size_t c = 0; c < srv_work_chunks(&w); c++)
            flagged += done[c];
        if (flagged != resumed || end < 0 || (size_t)end > size - 8)
            abort();
    }
    if (f)
        fclose(f);
    free(out);
    free(done);
    return 0;
}
