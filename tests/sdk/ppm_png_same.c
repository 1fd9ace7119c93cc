/*
 * ppm_png_same.c — ppm_png_same A.ppm B.png: whether a binary PPM (P6, 255)
 * and an 8-bit PNG hold the same RGB pixels. Prints "same" or where they
 * differ (size, pixels that differ, the largest channel difference);
 * exit 0 when the same, 1 when not, 2 when a file cannot be read.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include "lumo_host/png_io.h"

/* A P6 file with maxval 255 (as lumo_view writes it), malloc'ed RGB8. */
static uint8_t *read_ppm(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    uint8_t *rgb = NULL;
    int maxval = 0;
    size_t n;

    if (!f)
        return NULL;
    if (fscanf(f, "P6 %d %d %d", w, h, &maxval) == 3 && maxval == 255 && *w > 0 && *h > 0 && *w <= 8192
        && *h <= 8192 && fgetc(f) != EOF) {
        n = (size_t)*w * (size_t)*h * 3;
        rgb = malloc(n);
        if (rgb && fread(rgb, 1, n, f) != n) {
            free(rgb);
            rgb = NULL;
        }
    }
    fclose(f);
    return rgb;
}

int main(int argc, char **argv)
{
    uint8_t *a, *b = NULL;
    int wa = 0, ha = 0, wb = 0, hb = 0, maxd = 0, rc;
    size_t i, n, differ = 0;

    if (argc != 3) {
        fprintf(stderr, "usage: ppm_png_same A.ppm B.png\n");
        return 2;
    }
    a = read_ppm(argv[1], &wa, &ha);
    if (!a || host_png_read_rgb8(argv[2], &b, &wb, &hb)) {
        fprintf(stderr, "ppm_png_same: cannot read %s\n", a ? argv[2] : argv[1]);
        free(a);
        return 2;
    }
    if (wa != wb || ha != hb) {
        printf("size differs: %dx%d vs %dx%d\n", wa, ha, wb, hb);
        rc = 1;
    } else {
        n = (size_t)wa * ha;
        for (i = 0; i < n * 3; i++) {
            int d = abs(a[i] - b[i]);
            if (d > maxd)
                maxd = d;
        }
        for (i = 0; i < n; i++)
            differ += a[3 * i] != b[3 * i] || a[3 * i + 1] != b[3 * i + 1] || a[3 * i + 2] != b[3 * i + 2];
        if (differ)
            printf("%zu of %zu pixels differ, by up to %d\n", differ, n, maxd);
        else
            printf("same (%dx%d)\n", wa, ha);
        rc = differ != 0;
    }
    free(a);
    free(b);
    return rc;
}
