/*
 * framed.c — `framed IMAGE.png MIN_PERCENT`: is the lit object in the
 * picture, whole and not lost in the distance? Prints the box of the pixels
 * brighter than the black background and exits 0 when that box keeps a
 * pixel off every edge (nothing cut off by the frame) and spans at least
 * MIN_PERCENT of the frame's width or height; 1 otherwise, 2 on a bad
 * command line or file. Used by tests/render/fit.sh.
 */
#include <stdio.h>
#include <stdlib.h>
#include "lumo_host/png_io.h"

int main(int argc, char **argv)
{
    uint8_t *rgb;
    int w, h, x, y, x0, y0, x1 = -1, y1 = -1;
    double min_percent;

    if (argc != 3 || (min_percent = atof(argv[2])) <= 0) {
        fprintf(stderr, "usage: framed IMAGE.png MIN_PERCENT\n");
        return 2;
    }
    if (host_png_read_rgb8(argv[1], &rgb, &w, &h)) {
        fprintf(stderr, "framed: %s: cannot read the PNG\n", argv[1]);
        return 2;
    }
    x0 = w, y0 = h;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            const uint8_t *p = &rgb[3 * ((size_t)y * w + x)];
            if (p[0] > 8 || p[1] > 8 || p[2] > 8) {
                if (x < x0) x0 = x;
                if (x > x1) x1 = x;
                if (y < y0) y0 = y;
                if (y > y1) y1 = y;
            }
        }
    free(rgb);
    if (x1 < 0) {
        printf("%s: nothing lit in the %dx%d frame\n", argv[1], w, h);
        return 1;
    }
    printf("%s: lit pixels in x %d..%d, y %d..%d of %dx%d\n", argv[1], x0, x1, y0, y1, w, h);
    if (x0 == 0 || y0 == 0 || x1 == w - 1 || y1 == h - 1)
        return 1;
    return (x1 - x0 + 1) * 100.0 < min_percent * w && (y1 - y0 + 1) * 100.0 < min_percent * h;
}
