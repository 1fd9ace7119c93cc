/*
 * test_hostlib.c — the desktop library tools/lib (libhost.a) against
 * closed forms: whole-file reads (content, the extra zero byte, empty and
 * missing files), the tone map against a double-precision sRGB curve,
 * CIE Lab / Delta E / PSNR on images with known answers, and PNG files
 * round-tripped byte for byte (with the sRGB chunk both writers relied on).
 */
#include "test_common.h"
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#include "lumo_host/file_io.h"
#include "lumo_host/image_diff.h"
#include "lumo_host/png_io.h"
#include "lumo_host/tonemap.h"

/* A fresh path in the temp directory; the file does not exist yet. */
static void temp_path(char *buf, size_t n, const char *suffix)
{
    static int counter;
    snprintf(buf, n, "%s/lumo_test_hostlib_%ld_%d%s", P_tmpdir, (long)getpid(), counter++, suffix);
    unlink(buf);
}

static void write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

static void test_read_file(void **state)
{
    (void)state;
    char path[256];
    const uint8_t data[5] = {'l', 0, 'u', 0xff, 'm'};
    size_t size = 99;
    temp_path(path, sizeof path, ".bin");
    write_bytes(path, data, sizeof data);
    uint8_t *buf = host_read_file(path, &size);
    assert_non_null(buf);
    assert_int_equal(size, sizeof data);
    assert_memory_equal(buf, data, sizeof data);
    assert_int_equal(buf[size], 0);   /* the terminator text parsers rely on */
    free(buf);
    unlink(path);
}

static void test_read_file_empty_and_missing(void **state)
{
    (void)state;
    char path[256];
    size_t size = 99;
    temp_path(path, sizeof path, ".empty");
    write_bytes(path, "", 0);
    uint8_t *buf = host_read_file(path, &size);
    assert_non_null(buf);
    assert_int_equal(size, 0);
    assert_int_equal(buf[0], 0);
    free(buf);
    unlink(path);
    size = 7;
    assert_null(host_read_file(path, &size));
    assert_int_equal(size, 7);   /* untouched on failure */
    assert_null(host_read_file(P_tmpdir, &size));   /* a directory is not a file */
    assert_int_equal(size, 7);
}

static double srgb_encode_ref(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static void test_tonemap(void **state)
{
    (void)state;
    assert_int_equal(host_tonemap(0.0f, 1.0f), 0);
    assert_int_equal(host_tonemap(1.0f, 1.0f), 255);
    assert_int_equal(host_tonemap(7.0f, 1.0f), 255);    /* clamped */
    assert_int_equal(host_tonemap(-1.0f, 1.0f), 0);
    assert_int_equal(host_tonemap(NAN, 1.0f), 0);
    assert_int_equal(host_tonemap(0.25f, 4.0f), 255);   /* exposure first */
    /* Everywhere within half a step of the double-precision curve. */
    for (int i = 0; i <= 4096; i++) {
        float v = (float)i / 4096.0f;
        assert_close(host_tonemap(v, 1.0f), 255.0 * srgb_encode_ref(v), 0.5 + 1e-3);
    }
    float rgb[6] = {0.0f, 0.5f, 1.0f, 2.0f, -3.0f, 0.01f};
    uint8_t *px = host_tonemap_rgb8(rgb, 6, 0.5f);
    assert_non_null(px);
    for (int i = 0; i < 6; i++)
        assert_int_equal(px[i], host_tonemap(rgb[i], 0.5f));
    free(px);
}

static void test_lab(void **state)
{
    (void)state;
    const uint8_t white[3] = {255, 255, 255}, black[3] = {0, 0, 0}, red[3] = {255, 0, 0};
    double lab[3];
    host_srgb8_to_lab(white, lab);
    assert_close(lab[0], 100.0, 1e-3);
    assert_close(lab[1], 0.0, 1e-2);
    assert_close(lab[2], 0.0, 1e-2);
    host_srgb8_to_lab(red, lab);   /* published sRGB red: L 53.24, a 80.09, b 67.20 */
    assert_close(lab[0], 53.24, 0.01);
    assert_close(lab[1], 80.09, 0.01);
    assert_close(lab[2], 67.20, 0.01);
    assert_close(host_delta_e76(white, black), 100.0, 1e-2);
    assert_close(host_delta_e76(red, red), 0.0, 0.0);
}

static void test_image_diff(void **state)
{
    (void)state;
    enum { N = 200 };
    uint8_t a[N * 3], b[N * 3];
    host_image_diff d;
    test_rng r = {12345};
    for (int i = 0; i < N * 3; i++)
        a[i] = b[i] = (uint8_t)(test_rng_next(&r) >> 56);
    host_image_diff_rgb8(a, b, N, &d);
    assert_close(d.mean_de, 0.0, 0.0);
    assert_close(d.max_de, 0.0, 0.0);
    assert_close(d.psnr_db, 99.0, 0.0);
    /* One pixel in 200 black against white: the 99th percentile is still 0,
     * the mean is 100/200, and every channel error is 255 on 1/200. */
    memset(a, 255, 3);
    memset(b, 0, 3);
    host_image_diff_rgb8(a, b, N, &d);
    assert_close(d.mean_de, host_delta_e76(a, b) / N, 1e-12);
    assert_close(d.max_de, 100.0, 1e-2);
    assert_close(d.p99_de, 0.0, 0.0);
    assert_close(d.psnr_db, 10 * log10((double)N), 1e-9);
    /* All channels off by one: MSE 1, PSNR 20 log10(255). */
    for (int i = 0; i < N * 3; i++)
        b[i] = (uint8_t)(a[i] ^ 1);
    host_image_diff_rgb8(a, b, N, &d);
    assert_close(d.psnr_db, 20 * log10(255.0), 1e-9);
    assert_true(d.p99_de > 0 && d.p99_de <= d.max_de);
}

static void test_png_round_trip(void **state)
{
    (void)state;
    enum { W = 37, H = 23 };
    uint8_t px[W * H * 3], *back = NULL;
    char path[256], err[512];
    int w = 0, h = 0;
    size_t size;
    test_rng r = {777};
    for (int i = 0; i < W * H * 3; i++)
        px[i] = (uint8_t)(test_rng_next(&r) >> 56);
    temp_path(path, sizeof path, ".png");
    assert_int_equal(host_png_write_rgb8(path, px, W, H, err, sizeof err), 0);
    assert_int_equal(host_png_read_rgb8(path, &back, &w, &h), 0);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_memory_equal(back, px, sizeof px);
    free(back);
    /* Signature, IHDR, then the sRGB chunk (perceptual intent). */
    uint8_t *file = host_read_file(path, &size);
    assert_non_null(file);
    assert_true(size > 45);
    assert_memory_equal(file + 37, "sRGB\0", 5);
    free(file);
    unlink(path);
}

static void test_png_radiance_and_errors(void **state)
{
    (void)state;
    float rgb[2 * 3] = {0.0f, 0.1f, 0.2f, 0.5f, 1.0f, 4.0f};
    uint8_t *back = NULL;
    char path[256], err[512] = "";
    int w, h;
    temp_path(path, sizeof path, ".png");
    assert_int_equal(host_png_write_radiance(path, rgb, 2, 1, 1.5f, err, sizeof err), 0);
    assert_int_equal(host_png_read_rgb8(path, &back, &w, &h), 0);
    for (int i = 0; i < 6; i++)
        assert_int_equal(back[i], host_tonemap(rgb[i], 1.5f));
    free(back);
    /* Not a PNG, missing, unwritable: -1, with the path in the message. */
    write_bytes(path, "not a png", 9);
    assert_int_equal(host_png_read_rgb8(path, &back, &w, &h), -1);
    unlink(path);
    assert_int_equal(host_png_read_rgb8(path, &back, &w, &h), -1);
    assert_int_equal(host_png_write_rgb8("/nonexistent-dir/x.png", (const uint8_t *)"abc", 1, 1, err, sizeof err),
                     -1);
    assert_non_null(strstr(err, "/nonexistent-dir/x.png: cannot write PNG"));
    assert_int_equal(host_png_write_rgb8("/nonexistent-dir/x.png", (const uint8_t *)"abc", 1, 1, NULL, 0), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_read_file),
        cmocka_unit_test(test_read_file_empty_and_missing),
        cmocka_unit_test(test_tonemap),
        cmocka_unit_test(test_lab),
        cmocka_unit_test(test_image_diff),
        cmocka_unit_test(test_png_round_trip),
        cmocka_unit_test(test_png_radiance_and_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
