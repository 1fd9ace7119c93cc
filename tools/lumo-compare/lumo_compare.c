/*
 * lumo_compare.c — lumo-compare A.png B.png [C.png] -o SIDE.png
 *     [--labels "A,B,C"] [--max-mean-de X] [--min-psnr DB]
 *
 * Places the images side by side with a label under each, and prints the
 * mean CIE Lab Delta E (CIE76) and the PSNR of every pair. With the bounds,
 * exits 1 when the first image differs from another by more (tests).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/image_diff.h"
#include "lumo_host/options.h"
#include "lumo_host/png_io.h"

/* A 5x7 font for labels: upper case, digits and a little punctuation. */
static const struct glyph { char c; const char *rows[7]; } font[] = {
    {'A', {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'B', {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."}},
    {'C', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {'D', {"####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."}},
    {'E', {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
    {'F', {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
    {'G', {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"}},
    {'H', {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'I', {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'J', {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
    {'K', {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
    {'L', {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
    {'M', {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
    {'N', {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"}},
    {'O', {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'P', {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."}},
    {'Q', {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"}},
    {'R', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {'S', {".####", "#....", "#....", ".###.", "....#", "....#", "####."}},
    {'T', {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {'U', {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'V', {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {'W', {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."}},
    {'X', {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
    {'Y', {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
    {'Z', {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"}},
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {',', {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
    {'=', {".....", ".....", "#####", ".....", "#####", ".....", "....."}},
    {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
    {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
    {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
    {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
    {'_', {".....", ".....", ".....", ".....", ".....", ".....", "#####"}},
    {'%', {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"}},
};

#define SCALE 2
#define LABEL_H (7 * SCALE + 8)

static const struct glyph *find_glyph(char c)
{
    size_t i;
    if (c >= 'a' && c <= 'z')
        c = (char)(c - 'a' + 'A');
    for (i = 0; i < sizeof font / sizeof font[0]; i++)
        if (font[i].c == c)
            return &font[i];
    return NULL;
}

static void draw_text(uint8_t *img, int w, int h, int x0, int y0, const char *s)
{
    for (; *s; s++, x0 += 6 * SCALE) {
        const struct glyph *g = find_glyph(*s);
        int r, c, dy, dx;
        if (!g)
            continue;
        for (r = 0; r < 7; r++)
            for (c = 0; c < 5; c++)
                if (g->rows[r][c] == '#')
                    for (dy = 0; dy < SCALE; dy++)
                        for (dx = 0; dx < SCALE; dx++) {
                            int x = x0 + c * SCALE + dx, y = y0 + r * SCALE + dy;
                            if (x >= 0 && x < w && y >= 0 && y < h)
                                memset(img + ((size_t)y * w + x) * 3, 255, 3);
                        }
    }
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* Up to MAX_IN pictures, at most COLS to a row (seed 000 Fig. 1 style
 * progressions need more than three). */
#define MAX_IN 8
#define COLS   4

static const char k_usage[] =
    "usage: lumo-compare A.png B.png [C.png ... up to 8] [-o SIDE.png] [--labels A,B,...]\n"
    "                    [--max-mean-de X] [--min-psnr DB]\n"
    "  with three pictures or fewer every pair is compared; with more, each against the last\n"
    "  --max-mean-de X   exit 1 when the first picture's mean Delta E76 to another passes X (0..1000)\n"
    "  --min-psnr DB     exit 1 when its PSNR to another is below DB (0..1000)\n";

int main(int argc, char **argv)
{
    const char *in[MAX_IN], *out = NULL, *labels = NULL;
    char label[MAX_IN][64];
    uint8_t *img[MAX_IN], *side;
    int w[MAX_IN], h[MAX_IN], n = 0, i, j, sw, sh, fail = 0, cols, rows;
    double max_de = -1, min_psnr = -1;

    char err[600] = "";
    for (i = 1; i < argc && !err[0]; i++) {
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(k_usage, stdout);
            return 0;
        }
        if (argv[i][0] != '-') {
            if (n == MAX_IN)
                snprintf(err, sizeof err, "more than %d pictures", MAX_IN);
            else
                in[n++] = argv[i];
        } else if (!v && (!strcmp(argv[i], "-o") || !strcmp(argv[i], "--labels") ||
                          !strcmp(argv[i], "--max-mean-de") || !strcmp(argv[i], "--min-psnr")))
            snprintf(err, sizeof err, "%s needs a value (try --help)", argv[i]);
        else if (!strcmp(argv[i], "-o")) out = argv[++i];
        else if (!strcmp(argv[i], "--labels")) labels = argv[++i];
        else if (!strcmp(argv[i], "--max-mean-de")) host_opt_double("--max-mean-de", argv[++i], 0, 1000, &max_de, err, sizeof err);
        else if (!strcmp(argv[i], "--min-psnr")) host_opt_double("--min-psnr", argv[++i], 0, 1000, &min_psnr, err, sizeof err);
        else snprintf(err, sizeof err, "%.64s: unknown option (try --help)", argv[i]);
    }
    if (!err[0] && n < 2)
        snprintf(err, sizeof err, "%s (try --help)", n ? "one picture: give two or more" : "no pictures given");
    if (err[0]) {
        fprintf(stderr, "lumo-compare: error: %s\n", err);
        return 2;
    }
    for (i = 0; i < n; i++) {
        if (host_opt_file(NULL, in[i], "PNG picture", err, sizeof err) == 0 &&
            host_png_read_rgb8(in[i], &img[i], &w[i], &h[i]))
            snprintf(err, sizeof err, "%s: cannot read as an 8-bit PNG picture (of at most 2^26 pixels)", in[i]);
        if (err[0]) {
            fprintf(stderr, "lumo-compare: error: %s\n", err);
            return 1;
        }
        snprintf(label[i], sizeof label[i], "%s", base_name(in[i]));
    }
    if (labels) {
        const char *p = labels;
        for (i = 0; i < n && *p; i++) {
            size_t len = strcspn(p, ",");
            snprintf(label[i], sizeof label[i], "%.*s", (int)len, p);
            p += len + (p[len] == ',');
        }
    }
    for (i = 0; i < n; i++)
        for (j = n > 3 ? n - 1 : i + 1; j < n; j++) {
            host_image_diff d;
            if (i == j)
                continue;
            if (w[i] != w[j] || h[i] != h[j]) {
                fprintf(stderr, "lumo-compare: error: %s and %s differ in size\n", in[i], in[j]);
                return 1;
            }
            host_image_diff_rgb8(img[i], img[j], (size_t)w[i] * h[i], &d);
            printf("%s vs %s: mean dE76 %.3f, p99 dE %.2f, max dE %.2f, PSNR %.2f dB\n", label[i],
                   label[j], d.mean_de, d.p99_de, d.max_de, d.psnr_db);
            if (i == 0 && ((max_de >= 0 && d.mean_de > max_de) || (min_psnr >= 0 && d.psnr_db < min_psnr)))
                fail = 1;
        }
    if (out) {
        cols = n < COLS ? n : COLS;
        rows = (n + cols - 1) / cols;
        sw = w[0] * cols + 4 * (cols - 1);
        sh = (h[0] + LABEL_H) * rows;
        side = calloc((size_t)sw * sh, 3);
        for (i = 0; side && i < n; i++) {
            int x0 = (i % cols) * (w[0] + 4), y0 = (i / cols) * (h[0] + LABEL_H), y;
            for (y = 0; y < h[0]; y++)
                memcpy(side + ((size_t)(y0 + y) * sw + x0) * 3, img[i] + (size_t)y * w[0] * 3, (size_t)w[0] * 3);
            draw_text(side, sw, sh, x0 + 4, y0 + h[0] + 4, label[i]);
        }
        snprintf(err, sizeof err, "%s: out of memory", out);
        if (!side || host_png_write_rgb8(out, side, sw, sh, err, sizeof err)) {
            fprintf(stderr, "lumo-compare: error: %s\n", err);
            return 1;
        }
        free(side);
    }
    for (i = 0; i < n; i++)
        free(img[i]);
    return fail;
}
