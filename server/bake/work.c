/* work.c — sample-parallel work in chunks (work.h): the chunk table, the
 * run in this process (with a checkpoint when asked), the output key. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bake/checkpoint.h"
#include "bake/work.h"
#include "common/progress.h"
#include "scene/scene.h"

size_t srv_work_chunk_items(size_t items)
{
    size_t c = (items + 1023) / 1024;
    return c < 16 ? 16 : c > 4096 ? 4096 : c;
}

size_t srv_work_chunks(const srv_work *w)
{
    return (w->items + w->chunk_items - 1) / w->chunk_items;
}

void srv_work_chunk(const srv_work *w, size_t c, size_t *first, size_t *count)
{
    *first = c * w->chunk_items;
    *count = w->items - *first < w->chunk_items ? w->items - *first : w->chunk_items;
}

static lumo_status run_chunks(const srv_work *w, srv_ckpt *ck, const uint8_t *done, uint8_t *out,
                              srv_work_report *rep, char *err, size_t errlen)
{
    srv_progress bar;
    size_t finished = 0;
    lumo_status st = LUMO_OK;
    srv_progress_begin(&bar, w->name, rep->chunks, w->progress);
    for (size_t c = 0; c < rep->chunks && !st; c++) {
        size_t first, count;
        srv_work_chunk(w, c, &first, &count);
        if (!done[c]) {
            uint8_t *dst = out + first * w->item_bytes;
            if ((st = w->run(w->ctx, first, count, dst, &rep->rays)))
                snprintf(err, errlen, "cannot start worker threads");
            else if (ck)
                st = srv_ckpt_append(ck, w, c, dst, err, errlen);
            rep->rank_chunks[0]++;
        }
        srv_progress_update(&bar, ++finished);
    }
    srv_progress_end(&bar);
    return st;
}

lumo_status srv_work_run_local(const srv_work *w, const char *ckpt_dir, uint8_t *out,
                               srv_work_report *rep, char *err, size_t errlen)
{
    srv_ckpt ck;
    double t0 = srv_now();
    memset(rep, 0, sizeof *rep);
    rep->ranks = 1;
    rep->chunks = srv_work_chunks(w);
    uint8_t *done = calloc(rep->chunks, 1);
    if (!done) {
        snprintf(err, errlen, "out of memory");
        return LUMO_ERR_NOMEM;
    }
    lumo_status st = LUMO_OK;
    if (ckpt_dir)
        st = srv_ckpt_open(&ck, ckpt_dir, w, out, done, &rep->resumed, err, errlen);
    if (!st)
        st = run_chunks(w, ckpt_dir ? &ck : NULL, done, out, rep, err, errlen);
    if (ckpt_dir && ck.fd >= 0)
        srv_ckpt_close(&ck);
    free(done);
    rep->seconds = srv_now() - t0;
    return st;
}

uint64_t srv_key_bytes(uint64_t h, const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

uint64_t srv_key_u64(uint64_t h, uint64_t v)
{
    uint8_t b[8];
    for (int i = 0; i < 8; i++)
        b[i] = (uint8_t)(v >> (8 * i));
    return srv_key_bytes(h, b, 8);
}

uint64_t srv_key_float(uint64_t h, float f)
{
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    return srv_key_u64(h, bits);
}

static uint64_t key_vec(uint64_t h, vec3 v)
{
    return srv_key_float(srv_key_float(srv_key_float(h, v.x), v.y), v.z);
}

static uint64_t key_light(uint64_t h, const srv_light *l)
{
    h = srv_key_u64(h, (uint64_t)l->kind);
    h = key_vec(key_vec(key_vec(key_vec(h, l->pos), l->dir), l->u), l->v);
    h = srv_key_float(srv_key_float(h, l->half_angle_deg), l->cos_half);
    return key_vec(h, l->power);
}

uint64_t srv_key_scene(uint64_t h, const srv_scene *s)
{
    h = srv_key_u64(h, s->nmeshes);
    for (size_t i = 0; i < s->nmeshes; i++) {
        const srv_mesh *m = &s->meshes[i];
        h = srv_key_u64(srv_key_u64(srv_key_u64(h, m->nverts), m->ntris), (uint64_t)m->emitter);
        for (uint32_t v = 0; v < m->nverts; v++)
            h = key_vec(key_vec(h, m->pos[v]), m->albedo[v]);
        for (size_t t = 0; t < 3 * (size_t)m->ntris; t++)
            h = srv_key_u64(h, m->tris[t]);
    }
    h = srv_key_u64(h, s->nlights);
    for (size_t i = 0; i < s->nlights; i++)
        h = key_light(h, &s->lights[i]);
    return h;
}
