/*
 * test_cli_options.c — the tools' one command-line value parser
 * (lumo_host/options.h, issue 24): every kind of value taken at its
 * bounds, refused one past them and refused when it wraps, is not finite
 * or is garbage, each refusal naming the option, the value and why, and
 * the output left untouched by a refusal.
 */
#include "test_common.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/options.h"

static char g_err[256];

/* The message of the last refusal is exactly `want`. */
static void assert_msg(const char *want)
{
    assert_string_equal(g_err, want);
}

static void test_integers(void **state)
{
    int v = 42;
    (void)state;
    assert_int_equal(host_opt_int("--frames", "1", 1, 100, &v, g_err, sizeof g_err), 0);
    assert_int_equal(v, 1);
    assert_int_equal(host_opt_int("--frames", "100", 1, 100, &v, g_err, sizeof g_err), 0);
    assert_int_equal(v, 100);
    assert_int_equal(host_opt_int("--frames", "007", 1, 100, &v, g_err, sizeof g_err), 0);
    assert_int_equal(v, 7);
    assert_int_equal(host_opt_int("--frames", "-3", -5, 5, &v, g_err, sizeof g_err), 0);
    assert_int_equal(v, -3);
    v = 42;
    assert_int_equal(host_opt_int("--frames", "101", 1, 100, &v, g_err, sizeof g_err), -1);
    assert_msg("--frames 101: must be 1..100");
    assert_int_equal(host_opt_int("--frames", "0", 1, 100, &v, g_err, sizeof g_err), -1);
    assert_msg("--frames 0: must be 1..100");
    assert_int_equal(host_opt_int("--frames", "-1", 1, 100, &v, g_err, sizeof g_err), -1);
    assert_msg("--frames -1: must be 1..100");
    assert_int_equal(v, 42);
}

static void test_integer_garbage(void **state)
{
    static const char *bad[] = {"", "abc", "12x", "x12", " 12", "12 ", "+12", "1.5", "1e3", "0x10", "-", "--1",
                                "1,2", "٣"};
    int v = 42;
    (void)state;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(host_opt_int("--bands", bad[i], 0, 1000, &v, g_err, sizeof g_err), -1);
        assert_non_null(strstr(g_err, ": not an integer"));
        assert_int_equal(strncmp(g_err, "--bands ", 8), 0);
    }
    assert_int_equal(v, 42);
    host_opt_int("--bands", "", 0, 10, &v, g_err, sizeof g_err);
    assert_msg("--bands '': not an integer");
}

/* No wrap: values past 32 and 64 bits are refused, not taken modulo. */
static void test_integer_wrap(void **state)
{
    uint32_t u = 7;
    int64_t w = 7;
    uint64_t s = 7;
    (void)state;
    assert_int_equal(host_opt_u32("--vertices", "4294967296", 0, UINT32_MAX, &u, g_err, sizeof g_err), -1);
    assert_msg("--vertices 4294967296: must be 0..4294967295");
    assert_int_equal(host_opt_u32("--vertices", "4294967295", 0, UINT32_MAX, &u, g_err, sizeof g_err), 0);
    assert_int_equal(u, UINT32_MAX);
    assert_int_equal(host_opt_i64("--x", "99999999999999999999999", INT64_MIN, INT64_MAX, &w, g_err, sizeof g_err),
                     -1);
    assert_int_equal(host_opt_i64("--x", "-9223372036854775808", INT64_MIN, INT64_MAX, &w, g_err, sizeof g_err), 0);
    assert_true(w == INT64_MIN);
    assert_int_equal(host_opt_i64("--x", "-9223372036854775809", INT64_MIN, INT64_MAX, &w, g_err, sizeof g_err),
                     -1);
    assert_int_equal(host_opt_i64("--x", "9223372036854775807", INT64_MIN, INT64_MAX, &w, g_err, sizeof g_err), 0);
    assert_true(w == INT64_MAX);
    assert_int_equal(host_opt_u64("--seed", "18446744073709551615", &s, g_err, sizeof g_err), 0);
    assert_true(s == UINT64_MAX);
    assert_int_equal(host_opt_u64("--seed", "18446744073709551616", &s, g_err, sizeof g_err), -1);
    assert_msg("--seed 18446744073709551616: must be 0..18446744073709551615");
    assert_int_equal(host_opt_u64("--seed", "-1", &s, g_err, sizeof g_err), -1);
    assert_msg("--seed -1: must be 0..18446744073709551615");
    assert_int_equal(host_opt_u64("--seed", "1x", &s, g_err, sizeof g_err), -1);
    assert_msg("--seed 1x: not an integer");
    assert_true(s == UINT64_MAX);
}

static void test_numbers(void **state)
{
    double v = 7;
    (void)state;
    assert_int_equal(host_opt_double("--exposure", "2.5", 0, 65535, &v, g_err, sizeof g_err), 0);
    assert_true(v == 2.5);
    assert_int_equal(host_opt_double("--exposure", "1e-3", 0, 65535, &v, g_err, sizeof g_err), 0);
    assert_true(v == 1e-3);
    assert_int_equal(host_opt_double("--exposure", "0", 0, 65535, &v, g_err, sizeof g_err), 0);
    assert_int_equal(host_opt_double("--exposure", "65535", 0, 65535, &v, g_err, sizeof g_err), 0);
    assert_int_equal(host_opt_double("--exposure", "65535.01", 0, 65535, &v, g_err, sizeof g_err), -1);
    assert_msg("--exposure 65535.01: must be 0..65535");
    assert_int_equal(host_opt_double("--exposure", "-0.5", 0, 65535, &v, g_err, sizeof g_err), -1);
    assert_msg("--exposure -0.5: must be 0..65535");
    assert_true(v == 65535);
}

static void test_numbers_not_finite(void **state)
{
    static const char *inf[] = {"nan", "NaN", "-nan", "inf", "-inf", "infinity", "1e999", "-1e400"};
    static const char *junk[] = {"", "abc", "1.5x", " 1", "1 ", "1,5", ".", "e5", "--1", "0x"};
    double v = 7;
    (void)state;
    for (size_t i = 0; i < sizeof inf / sizeof inf[0]; i++) {
        assert_int_equal(host_opt_double("--max-mean-de", inf[i], 0, 1e9, &v, g_err, sizeof g_err), -1);
        assert_non_null(strstr(g_err, ": not a finite number"));
    }
    for (size_t i = 0; i < sizeof junk / sizeof junk[0]; i++) {
        assert_int_equal(host_opt_double("--min-psnr", junk[i], 0, 1e9, &v, g_err, sizeof g_err), -1);
        assert_non_null(strstr(g_err, ": not a number"));
    }
    host_opt_double("--max-mean-de", "nan", 0, 100, &v, g_err, sizeof g_err);
    assert_msg("--max-mean-de nan: not a finite number");
    host_opt_double("--min-psnr", "abc", 0, 100, &v, g_err, sizeof g_err);
    assert_msg("--min-psnr abc: not a number");
    assert_true(v == 7);
}

static void test_positive(void **state)
{
    double v = 7;
    (void)state;
    assert_int_equal(host_opt_positive("--cell", "0.25", 1e6, &v, g_err, sizeof g_err), 0);
    assert_true(v == 0.25);
    assert_int_equal(host_opt_positive("--cell", "0", 1e6, &v, g_err, sizeof g_err), -1);
    assert_msg("--cell 0: must be above 0 and at most 1e+06");
    assert_int_equal(host_opt_positive("--cell", "-0", 1e6, &v, g_err, sizeof g_err), -1);
    assert_int_equal(host_opt_positive("--cell", "1e-400", 1e6, &v, g_err, sizeof g_err), -1);
    assert_true(v == 0.25);
}

static void test_sizes(void **state)
{
    uint32_t w = 1, h = 1;
    (void)state;
    assert_int_equal(host_opt_size("--size", "320x240", 4096, 4096, &w, &h, g_err, sizeof g_err), 0);
    assert_int_equal(w, 320);
    assert_int_equal(h, 240);
    assert_int_equal(host_opt_size("--size", "4096x1", 4096, 4096, &w, &h, g_err, sizeof g_err), 0);
    assert_int_equal(host_opt_size("--size", "4294967312x16", 4096, 4096, &w, &h, g_err, sizeof g_err), -1);
    assert_msg("--size 4294967312x16: width must be 1..4096");
    assert_int_equal(host_opt_size("--size", "16x4294967312", 4096, 4096, &w, &h, g_err, sizeof g_err), -1);
    assert_msg("--size 16x4294967312: height must be 1..4096");
    assert_int_equal(host_opt_size("--size", "0x10", 4096, 4096, &w, &h, g_err, sizeof g_err), -1);
    assert_msg("--size 0x10: width must be 1..4096");
    assert_int_equal(host_opt_size("--size", "640", 4096, 4096, &w, &h, g_err, sizeof g_err), -1);
    assert_msg("--size 640: not WxH (e.g. 320x240)");
    assert_int_equal(host_opt_size("--size", "1x2x3", 4096, 4096, &w, &h, g_err, sizeof g_err), -1);
    assert_int_equal(host_opt_size("--size", "x5", 4096, 4096, &w, &h, g_err, sizeof g_err), -1);
    assert_msg("--size x5: width is not an integer");
    assert_int_equal(host_opt_size("--size", "5x", 4096, 4096, &w, &h, g_err, sizeof g_err), -1);
    assert_msg("--size 5x: height is not an integer");
    assert_int_equal(host_opt_size("--size", "-5x5", 4096, 4096, &w, &h, g_err, sizeof g_err), -1);
    assert_msg("--size -5x5: width must be 1..4096");
    assert_int_equal(w, 4096);
    assert_int_equal(h, 1);
}

static void test_vectors(void **state)
{
    double v[3] = {9, 9, 9};
    (void)state;
    assert_int_equal(host_opt_vec("--albedo", "0.5,0,1", 3, 0, 1, v, g_err, sizeof g_err), 0);
    assert_true(v[0] == 0.5 && v[1] == 0 && v[2] == 1);
    assert_int_equal(host_opt_vec("--albedo", "0.5,0", 3, 0, 1, v, g_err, sizeof g_err), -1);
    assert_msg("--albedo 0.5,0: 3 values separated by commas wanted, 2 given");
    assert_int_equal(host_opt_vec("--albedo", "1,1,1,1", 3, 0, 1, v, g_err, sizeof g_err), -1);
    assert_msg("--albedo 1,1,1,1: more than 3 values");
    assert_int_equal(host_opt_vec("--albedo", "1,nan,1", 3, 0, 1, v, g_err, sizeof g_err), -1);
    assert_msg("--albedo 1,nan,1: value 2: not a finite number");
    assert_int_equal(host_opt_vec("--albedo", "1,,1", 3, 0, 1, v, g_err, sizeof g_err), -1);
    assert_msg("--albedo 1,,1: value 2: not a number");
    assert_int_equal(host_opt_vec("--albedo", "1,1,2", 3, 0, 1, v, g_err, sizeof g_err), -1);
    assert_msg("--albedo 1,1,2: value 3 must be 0..1");
    assert_int_equal(host_opt_vec("--albedo", "1,1,", 3, 0, 1, v, g_err, sizeof g_err), -1);
    assert_true(v[0] == 0.5 && v[1] == 0 && v[2] == 1);
}

static void test_lists(void **state)
{
    double v[4] = {0};
    int n = 0;
    (void)state;
    assert_int_equal(host_opt_list("--frames-at", "10,50,100", 0, 100, 1, v, 4, &n, g_err, sizeof g_err), 0);
    assert_int_equal(n, 3);
    assert_true(v[2] == 100);
    assert_int_equal(host_opt_list("--frames-at", "50,10", 0, 100, 1, v, 4, &n, g_err, sizeof g_err), -1);
    assert_msg("--frames-at 50,10: values must increase (value 2 is 10 after 50)");
    assert_int_equal(host_opt_list("--frames-at", "1,2,3,4,5", 0, 100, 1, v, 4, &n, g_err, sizeof g_err), -1);
    assert_msg("--frames-at 1,2,3,4,5: more than 4 values");
    assert_int_equal(host_opt_list("--frames-at", "50,50", 0, 100, 0, v, 4, &n, g_err, sizeof g_err), 0);
    assert_int_equal(n, 2);
}

static void test_choice(void **state)
{
    static const char *const modes[] = {"pm", "raw", "both"};
    int m = 9;
    (void)state;
    assert_int_equal(host_opt_choice("--mesh", "raw", modes, 3, &m, g_err, sizeof g_err), 0);
    assert_int_equal(m, 1);
    assert_int_equal(host_opt_choice("--mesh", "RAW", modes, 3, &m, g_err, sizeof g_err), -1);
    assert_msg("--mesh RAW: must be one of pm, raw, both");
    assert_int_equal(m, 1);
}

/* Unprintable, quoted and long values are shown escaped and cut, so the
 * refusal stays one line; a short buffer is still terminated. */
static void test_message_escaping(void **state)
{
    char longv[300], small[12];
    int v;
    (void)state;
    host_opt_int("--frames", "1\n2", 1, 9, &v, g_err, sizeof g_err);
    assert_msg("--frames '1\\x0a2': not an integer");
    host_opt_int("--frames", "it's", 1, 9, &v, g_err, sizeof g_err);
    assert_msg("--frames 'it\\x27s': not an integer");
    memset(longv, '7', sizeof longv - 1);
    longv[sizeof longv - 1] = 0;
    assert_int_equal(host_opt_int("--frames", longv, 1, 9, &v, g_err, sizeof g_err), -1);
    assert_null(strchr(g_err, '\n'));
    assert_non_null(strstr(g_err, "...': must be 1..9"));
    assert_int_equal(host_opt_int("--frames", "99", 1, 9, &v, small, sizeof small), -1);
    assert_int_equal(strlen(small), sizeof small - 1);
}

/* Named files: missing, a directory, a device, empty, then a real one. */
static void test_files(void **state)
{
    char dir[] = "/tmp/lumo_test_cli_XXXXXX", path[64];
    FILE *f;
    (void)state;
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/m.ply", dir);
    assert_int_equal(host_opt_file("--model", path, "model file", g_err, sizeof g_err), -1);
    assert_non_null(strstr(g_err, "m.ply: cannot read: No such file or directory"));
    assert_int_equal(strncmp(g_err, "--model /tmp/", 13), 0);
    assert_int_equal(host_opt_file(NULL, dir, "scene file", g_err, sizeof g_err), -1);
    assert_non_null(strstr(g_err, ": a directory, not a scene file"));
    assert_int_equal(strncmp(g_err, "/tmp/", 5), 0);
    assert_int_equal(host_opt_file("--dragon", "/dev/null", "model file", g_err, sizeof g_err), -1);
    assert_msg("--dragon /dev/null: not a regular file (a model file is read whole)");
    f = fopen(path, "w");
    assert_non_null(f);
    fclose(f);
    assert_int_equal(host_opt_file("--model", path, "model file", g_err, sizeof g_err), -1);
    assert_non_null(strstr(g_err, "m.ply: empty file, not a model file"));
    f = fopen(path, "w");
    assert_non_null(f);
    fputs("ply\n", f);
    fclose(f);
    assert_int_equal(host_opt_file("--model", path, "model file", g_err, sizeof g_err), 0);
    assert_int_equal(remove(path), 0);
    assert_int_equal(remove(dir), 0);
}

static void test_getopt_errors(void **state)
{
    (void)state;
    host_opt_getopt_error(':', "--size", 0, g_err, sizeof g_err);
    assert_msg("--size needs a value (try --help)");
    host_opt_getopt_error('?', "--sise", 0, g_err, sizeof g_err);
    assert_msg("--sise: unknown option (try --help)");
    host_opt_getopt_error('?', "--orbit=3", 0, g_err, sizeof g_err);
    assert_msg("--orbit=3: unknown option, or one that takes no value (try --help)");
    host_opt_getopt_error(':', "-o", 'o', g_err, sizeof g_err);
    assert_msg("-o needs a value (try --help)");
    host_opt_getopt_error('?', "--help=3", 'h', g_err, sizeof g_err);
    assert_msg("--help=3: unknown option, or one that takes no value (try --help)");
    host_opt_getopt_error('?', "-qz", 'z', g_err, sizeof g_err);
    assert_msg("-z: unknown option (try --help)");
}

/* Runs host_getopt over argv to its end; returns the options taken as
 * letters ('p' --port-file, 'q' --quiet, 'r' --rate) and, on a refusal,
 * '?' with the word host_opt_getopt_error is given (argv[optind - 1]). */
static const char *getopt_run(int argc, char **argv, const char **word)
{
    static char taken[16];
    static const struct option longs[] = {
        {"port-file", required_argument, NULL, 'p'}, {"quiet", no_argument, NULL, 'q'},
        {"rate", required_argument, NULL, 'r'}, {NULL, 0, NULL, 0},
    };
    int c, n = 0;
    optind = 0;
    opterr = 0;
    *word = NULL;
    while ((c = host_getopt(argc, argv, ":h", longs)) != -1 && n < 15) {
        taken[n++] = (char)c;
        if (c == '?' || c == ':') {
            *word = argv[optind - 1];
            break;
        }
    }
    taken[n] = 0;
    return taken;
}

/* Long options only when typed whole: a unique prefix is refused, by the
 * word typed (not the value after it). */
static void test_getopt_whole_names(void **state)
{
    const char *w;
    char *whole[] = {"t", "--port-file", "f", "--quiet", "--rate=3", "--", "x", NULL};
    char *prefix[] = {"t", "--port", "7791", NULL};
    char *prefix_eq[] = {"t", "--qu", NULL};
    char *prefix_val[] = {"t", "--quiet", "--rat=3", NULL};
    char *ambiguous[] = {"t", "--r", "1", NULL};
    (void)state;
    assert_string_equal(getopt_run(7, whole, &w), "pqr");
    assert_string_equal(getopt_run(3, prefix, &w), "?");
    assert_string_equal(w, "--port");
    host_opt_getopt_error('?', w, optopt, g_err, sizeof g_err);
    assert_msg("--port: unknown option (try --help)");
    assert_string_equal(getopt_run(2, prefix_eq, &w), "?");
    assert_string_equal(w, "--qu");
    assert_string_equal(getopt_run(3, prefix_val, &w), "q?");
    assert_string_equal(w, "--rat=3");
    assert_string_equal(getopt_run(3, ambiguous, &w), "?");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_integers),        cmocka_unit_test(test_integer_garbage),
        cmocka_unit_test(test_integer_wrap),    cmocka_unit_test(test_numbers),
        cmocka_unit_test(test_numbers_not_finite), cmocka_unit_test(test_positive),
        cmocka_unit_test(test_sizes),           cmocka_unit_test(test_vectors),
        cmocka_unit_test(test_lists),           cmocka_unit_test(test_choice),
        cmocka_unit_test(test_message_escaping), cmocka_unit_test(test_files),
        cmocka_unit_test(test_getopt_errors),  cmocka_unit_test(test_getopt_whole_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
