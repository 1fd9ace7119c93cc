/* test_mpi_work.c — the pieces under lumo-bake's MPI runs, in one process:
 * the chunk table (every item in exactly one chunk, independent of ranks),
 * the local run, the checkpoint (resume, torn and damaged tails, another
 * bake's file, garbage, random bytes) and the bake split into chunks and
 * resumed from a checkpoint giving exactly srv_bake's bytes. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "bake/checkpoint.h"
#include "bake/work.h"
#include "common/rng.h"
#include "../server/bake_fixture.h"

/* A synthetic work: item i is item_bytes bytes drawn from the stream (7, i),
 * so any chunk's bytes are known; calls counts the items computed. */
typedef struct { size_t calls; size_t fail_after; } fake_ctx;

static void fake_item(size_t i, size_t bytes, uint8_t *out)
{
    srv_rng r;
    srv_rng_seed(&r, 7, i);
    for (size_t b = 0; b < bytes; b++)
        out[b] = (uint8_t)srv_rng_u32(&r);
}

static lumo_status fake_run(void *ctx, size_t first, size_t count, uint8_t *out, uint64_t *rays)
{
    fake_ctx *f = ctx;
    for (size_t i = 0; i < count; i++)
        fake_item(first + i, 12, out + i * 12);
    f->calls += count;
    *rays += count;
    return LUMO_OK;
}

static srv_work fake_work(fake_ctx *f, size_t items, uint64_t key)
{
    srv_work w = {.name = "fake", .items = items, .item_bytes = 12, .chunk_items = srv_work_chunk_items(items),
                  .key = key, .run = fake_run, .ctx = f};
    return w;
}

static uint8_t *expected(size_t items)
{
    uint8_t *e = malloc(items * 12);
    for (size_t i = 0; i < items; i++)
        fake_item(i, 12, e + i * 12);
    return e;
}

static char g_dir[64];
static char g_path[128];

static int make_dir(void **state)
{
    (void)state;
    snprintf(g_dir, sizeof g_dir, "/tmp/lumo-ckpt-XXXXXX");
    assert_non_null(mkdtemp(g_dir));
    snprintf(g_path, sizeof g_path, "%s/fake.ckpt", g_dir);
    return 0;
}

static int remove_dir(void **state)
{
    (void)state;
    remove(g_path);
    char ivg[128];
    snprintf(ivg, sizeof ivg, "%s/ivg.ckpt", g_dir);
    remove(ivg);
    rmdir(g_dir);
    return 0;
}

static void test_chunk_table(void **state)
{
    (void)state;
    size_t counts[] = {1, 2, 15, 16, 17, 255, 256, 4096, 4097, 65536, 262144, 16777216, 123457};
    for (size_t t = 0; t < sizeof counts / sizeof counts[0]; t++) {
        fake_ctx f = {0, 0};
        srv_work w = fake_work(&f, counts[t], 1);
        size_t next = 0, n = srv_work_chunks(&w);
        assert_true(w.chunk_items >= 16 && w.chunk_items <= 4096);
        assert_true(n >= 1 && (n <= 1024 || w.chunk_items == 4096));
        for (size_t c = 0; c < n; c++) {
            size_t first, count;
            srv_work_chunk(&w, c, &first, &count);
            assert_int_equal(first, next);
            assert_true(count >= 1 && count <= w.chunk_items);
            next = first + count;
        }
        assert_int_equal(next, counts[t]);
    }
}

static void run_fake(size_t items, uint64_t key, const char *dir, srv_work_report *rep, fake_ctx *f,
                     lumo_status want)
{
    char err[512] = "";
    srv_work w = fake_work(f, items, key);
    uint8_t *out = calloc(items, 12), *e = expected(items);
    lumo_status st = srv_work_run_local(&w, dir, out, rep, err, sizeof err);
    assert_int_equal(st, want);
    if (!st)
        assert_memory_equal(out, e, items * 12);
    else
        assert_non_null(strstr(err, "checkpoint"));
    free(out);
    free(e);
}

static void test_local_run(void **state)
{
    (void)state;
    srv_work_report rep;
    fake_ctx f = {0, 0};
    run_fake(1000, 1, NULL, &rep, &f, LUMO_OK);
    assert_int_equal(f.calls, 1000);
    assert_int_equal(rep.rays, 1000);
    assert_int_equal(rep.resumed, 0);
}

static void test_resume_whole(void **state)
{
    (void)state;
    srv_work_report rep;
    fake_ctx f = {0, 0};
    run_fake(1000, 1, g_dir, &rep, &f, LUMO_OK);
    assert_int_equal(f.calls, 1000);
    f.calls = 0;
    run_fake(1000, 1, g_dir, &rep, &f, LUMO_OK);
    assert_int_equal(f.calls, 0);                 /* everything from the checkpoint */
    assert_int_equal(rep.resumed, rep.chunks);
}

static long file_size(const char *p)
{
    struct stat st;
    return stat(p, &st) ? -1 : (long)st.st_size;
}

/* A record of 16 items: 8 + 16*12 + 4 bytes. */
#define REC (8 + 16 * 12 + 4)

static void test_torn_tail(void **state)
{
    (void)state;
    srv_work_report rep;
    fake_ctx f = {0, 0};
    run_fake(160, 1, g_dir, &rep, &f, LUMO_OK);   /* 10 chunks of 16 */
    long full = file_size(g_path);
    assert_int_equal(full, SRV_CKPT_HEADER + 10 * REC);
    assert_int_equal(truncate(g_path, full - 5), 0);   /* the last record torn */
    f.calls = 0;
    run_fake(160, 1, g_dir, &rep, &f, LUMO_OK);
    assert_int_equal(rep.resumed, 9);
    assert_int_equal(f.calls, 16);
    assert_int_equal(file_size(g_path), full);         /* cut, then completed */
}

static void test_damaged_record(void **state)
{
    (void)state;
    srv_work_report rep;
    fake_ctx f = {0, 0};
    run_fake(160, 1, g_dir, &rep, &f, LUMO_OK);
    int fd = open(g_path, O_RDWR);
    uint8_t b;
    assert_true(fd >= 0);
    off_t at = SRV_CKPT_HEADER + 3 * REC + 40;           /* inside the 4th record's data */
    assert_int_equal(pread(fd, &b, 1, at), 1);
    b ^= 0x10;
    assert_int_equal(pwrite(fd, &b, 1, at), 1);
    close(fd);
    f.calls = 0;
    run_fake(160, 1, g_dir, &rep, &f, LUMO_OK);          /* output checked: recomputed, not trusted */
    assert_int_equal(rep.resumed, 3);
    assert_int_equal(f.calls, 7 * 16);
}

static void test_other_bake_refused(void **state)
{
    (void)state;
    srv_work_report rep;
    fake_ctx f = {0, 0};
    run_fake(160, 1, g_dir, &rep, &f, LUMO_OK);
    long before = file_size(g_path);
    run_fake(160, 2, g_dir, &rep, &f, LUMO_ERR_STATE);  /* another key */
    run_fake(161, 1, g_dir, &rep, &f, LUMO_ERR_STATE);  /* other sizes */
    assert_int_equal(file_size(g_path), before);         /* left alone */
    FILE *g = fopen(g_path, "wb");
    fputs("not a checkpoint at all, but somebody's notes\n", g);
    fclose(g);
    run_fake(160, 1, g_dir, &rep, &f, LUMO_ERR_STATE);
    g = fopen(g_path, "wb");   /* empty: killed before its header, a fresh start */
    fclose(g);
    f.calls = 0;
    run_fake(160, 1, g_dir, &rep, &f, LUMO_OK);
    assert_int_equal(f.calls, 160);
}

/* The reader on hostile bytes: a valid file with random damage, random
 * lengths and random bytes; never reads or writes out of bounds (ASan),
 * and what it accepts is always the true data. */
static void test_reader_random(void **state)
{
    (void)state;
    srv_work_report rep;
    fake_ctx f = {0, 0};
    char err[256];
    run_fake(160, 1, g_dir, &rep, &f, LUMO_OK);
    FILE *g = fopen(g_path, "rb");
    static uint8_t good[SRV_CKPT_HEADER + 10 * REC], buf[sizeof good];
    assert_int_equal(fread(good, 1, sizeof good, g), sizeof good);
    fclose(g);
    srv_work w = fake_work(&f, 160, 1);
    uint8_t *e = expected(160), *out = malloc(160 * 12), done[10];
    srv_rng r;
    srv_rng_seed(&r, 99, 0);
    for (int it = 0; it < 20000; it++) {
        size_t len = srv_rng_u32(&r) % (sizeof buf + 1);
        memcpy(buf, good, sizeof buf);
        for (int k = (int)(srv_rng_u32(&r) % 4); k > 0; k--)
            buf[srv_rng_u32(&r) % sizeof buf] ^= (uint8_t)(1u << (srv_rng_u32(&r) % 8));
        if (it % 10 == 0)
            for (size_t i = SRV_CKPT_HEADER; i < len; i++)
                buf[i] = (uint8_t)srv_rng_u32(&r);
        memset(done, 0, sizeof done);
        memset(out, 0xee, 160 * 12);
        size_t resumed;
        long end;
        FILE *m = fmemopen(buf, len ? len : 1, "rb");
        if (!len)
            fgetc(m);
        lumo_status st = srv_ckpt_read(m, &w, out, done, &resumed, &end, err, sizeof err);
        fclose(m);
        assert_true(st == LUMO_OK || st == LUMO_ERR_STATE);
        assert_true(end >= 0 && (size_t)end <= len);
        for (size_t c = 0; c < 10; c++)
            if (done[c])
                assert_memory_equal(out + c * 16 * 12, e + c * 16 * 12, 16 * 12);
    }
    free(e);
    free(out);
}

/* The IVG bake through chunks and a checkpoint equals srv_bake: records of
 * half the chunks written, then a second run resumes and completes them. */
static void test_bake_resumed_equals_bake(void **state)
{
    (void)state;
    bake_fixture f;
    char err[256];
    memset(&f, 0, sizeof f);
    srv_scene_init(&f.scene);
    srv_add_box(&f.scene, "room", v3(-1, -1, -1), v3(1, 1, 1), v3(0.7f, 0.6f, 0.5f), 1);
    srv_light l = {.kind = LUMO_LIGHT_POINT, .pos = v3(0.2f, 0.5f, 0.1f), .power = v3(20, 20, 20)};
    assert_int_equal(srv_scene_add_light(&f.scene, &l), 0);
    srv_grid g = fixture_grid(v3(-1, -1, -1), v3(1, 1, 1), 9);
    fixture_bake(&f, &g, 16, 5, 2);

    srv_bake_opts o = {16, 5, 2, 0, 0.25f};
    srv_bake_task k;
    srv_work_report rep;
    assert_int_equal(srv_bake_task_init(&k, &f.tracer, &g, &o, err, sizeof err), 0);
    size_t bytes = k.work.items * k.work.item_bytes;
    uint8_t *rec = calloc(1, bytes);
    assert_int_equal(srv_work_run_local(&k.work, g_dir, rec, &rep, err, sizeof err), 0);
    char ivg[128];
    snprintf(ivg, sizeof ivg, "%s/ivg.ckpt", g_dir);
    long full = file_size(ivg), rec_bytes = 8 + 16 * (long)sizeof(srv_bake_record) + 4;
    assert_int_equal(full, SRV_CKPT_HEADER + (long)rep.chunks * rec_bytes - (long)(rep.chunks * 16 - k.work.items) *
                           (long)sizeof(srv_bake_record));
    assert_int_equal(truncate(ivg, SRV_CKPT_HEADER + (long)(rep.chunks / 2) * rec_bytes), 0);
    memset(rec, 0, bytes);
    assert_int_equal(srv_work_run_local(&k.work, g_dir, rec, &rep, err, sizeof err), 0);
    assert_int_equal(rep.resumed, rep.chunks / 2);

    srv_bake_result res;
    assert_int_equal(srv_bake_task_result(&k, rec, &res, err, sizeof err), 0);
    assert_memory_equal(res.I, f.res.I, res.nverts * 6 * 9 * sizeof(float));
    assert_memory_equal(res.se, f.res.se, res.nverts * 6 * 3 * sizeof(float));
    assert_memory_equal(res.valid, f.res.valid, res.nverts);
    srv_bake_result_free(&res);
    free(rec);
    srv_bake_task_free(&k);
    fixture_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chunk_table),
        cmocka_unit_test(test_local_run),
        cmocka_unit_test_setup_teardown(test_resume_whole, make_dir, remove_dir),
        cmocka_unit_test_setup_teardown(test_torn_tail, make_dir, remove_dir),
        cmocka_unit_test_setup_teardown(test_damaged_record, make_dir, remove_dir),
        cmocka_unit_test_setup_teardown(test_other_bake_refused, make_dir, remove_dir),
        cmocka_unit_test_setup_teardown(test_reader_random, make_dir, remove_dir),
        cmocka_unit_test_setup_teardown(test_bake_resumed_equals_bake, make_dir, remove_dir),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
