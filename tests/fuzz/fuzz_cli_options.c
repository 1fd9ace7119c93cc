/*
 * fuzz_cli_options.c — the tools' command-line value parser
 * (lumo_host/options.h, issue 24) on arbitrary bytes. The first byte picks
 * the kind of value and its range, the rest is the text. Beyond "no
 * crash": a taken value lies in its range and agrees with a reference
 * reading (strtoll / strtod), a refused one leaves the output untouched
 * and gives one printable line starting with the option's name.
 * Built by tests/hostile/cli.mk (it needs tools/lib/options.c beside the
 * client sources).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/options.h"

#define CHECK(c) do { if (!(c)) abort(); } while (0)

static char g_err[256];

/* A refusal: one printable line naming the option. */
static void check_refusal(int rc, const char *opt)
{
    size_t i;
    CHECK(rc == -1);
    CHECK(strncmp(g_err, opt, strlen(opt)) == 0 && g_err[strlen(opt)] == ' ');
    for (i = 0; g_err[i]; i++)
        CHECK(g_err[i] >= ' ' && g_err[i] < 127);
}

/* Whether text is "-?[0-9]{1,18}" (strtoll reads it exactly). */
static int plain_integer(const char *t)
{
    size_t i = t[0] == '-', n = 0;
    for (; t[i]; i++, n++)
        if (t[i] < '0' || t[i] > '9')
            return 0;
    return n >= 1 && n <= 18;
}

static void fuzz_int(const char *t, int64_t lo, int64_t hi)
{
    int64_t v = 12345;
    int rc = host_opt_i64("--n", t, lo, hi, &v, g_err, sizeof g_err);
    if (rc == 0) {
        CHECK(v >= lo && v <= hi);
        CHECK(t[0] != '+' && t[0] != ' ');
        if (plain_integer(t))
            CHECK(v == strtoll(t, NULL, 10));
        return;
    }
    check_refusal(rc, "--n");
    CHECK(v == 12345);
    if (plain_integer(t)) {
        long long r = strtoll(t, NULL, 10);
        CHECK(r < lo || r > hi);
    }
}

static void fuzz_double(const char *t, double lo, double hi)
{
    double v = 0.125;
    int rc = host_opt_double("--x", t, lo, hi, &v, g_err, sizeof g_err);
    if (rc == 0) {
        char *end;
        CHECK(isfinite(v) && v >= lo && v <= hi);
        CHECK(strtod(t, &end) == v && *end == 0);
        return;
    }
    check_refusal(rc, "--x");
    CHECK(v == 0.125);
}

static void fuzz_size(const char *t)
{
    uint32_t w = 7, h = 7;
    int rc = host_opt_size("--size", t, 4096, 2048, &w, &h, g_err, sizeof g_err);
    if (rc == 0) {
        CHECK(w >= 1 && w <= 4096 && h >= 1 && h <= 2048);
        return;
    }
    check_refusal(rc, "--size");
    CHECK(w == 7 && h == 7);
}

static void fuzz_vec(const char *t, int n)
{
    double v[4] = {0.5, 0.5, 0.5, 0.5};
    int rc = host_opt_vec("--v", t, n, -10, 10, v, g_err, sizeof g_err), i;
    for (i = 0; rc == 0 && i < n; i++)
        CHECK(isfinite(v[i]) && v[i] >= -10 && v[i] <= 10);
    if (rc)
        check_refusal(rc, "--v");
}

static void fuzz_list(const char *t)
{
    double v[8];
    int n = -1, rc = host_opt_list("--l", t, 0, 100, 1, v, 8, &n, g_err, sizeof g_err), i;
    if (rc) {
        check_refusal(rc, "--l");
        CHECK(n == -1);
        return;
    }
    CHECK(n >= 1 && n <= 8);
    for (i = 0; i < n; i++)
        CHECK(v[i] >= 0 && v[i] <= 100 && (i == 0 || v[i] > v[i - 1]));
}

static void fuzz_other(const char *t)
{
    static const char *const names[] = {"pm", "raw", "both"};
    uint64_t u = 3;
    int c = -1;
    if (host_opt_u64("--seed", t, &u, g_err, sizeof g_err))
        check_refusal(-1, "--seed");
    if (host_opt_choice("--mesh", t, names, 3, &c, g_err, sizeof g_err))
        check_refusal(-1, "--mesh");
    else
        CHECK(c >= 0 && c < 3 && !strcmp(t, names[c]));
    host_opt_getopt_error(t[0] == ':' ? ':' : '?', t, 0, g_err, sizeof g_err);
    CHECK(strchr(g_err, '\n') == NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char text[512];
    uint8_t pick;

    if (size < 1 || size > sizeof text)
        return 0;
    pick = data[0];
    memcpy(text, data + 1, size - 1);
    text[size - 1] = 0;
    switch (pick % 9) {
    case 0: fuzz_int(text, 1, 4096); break;
    case 1: fuzz_int(text, INT64_MIN, INT64_MAX); break;
    case 2: fuzz_int(text, -5, 0); break;
    case 3: fuzz_double(text, 0, 65535); break;
    case 4: fuzz_double(text, -1e300, 1e300); break;
    case 5: fuzz_size(text); break;
    case 6: fuzz_vec(text, 1 + pick / 9 % 4); break;
    case 7: fuzz_list(text); break;
    default: fuzz_other(text); break;
    }
    return 0;
}
