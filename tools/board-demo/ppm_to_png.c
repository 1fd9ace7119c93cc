/*
 * ppm_to_png.c — lumo-ppm-to-png IN.ppm OUT.png: the binary PPM (P6, maxval
 * 255) a board program writes over semihosting (boards/client/client.c
 * --out) as an 8-bit RGB PNG, for `make demo-board`. Anything else in IN is
 * refused with one line on stderr and status 1.
 */
#include <stdio.h>
#include <stdlib.h>
#include "lumo_host/png_io.h"

/* P6 header: magic, width, height, maxval 255, one whitespace byte. */
static unsigned char *read_ppm(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    unsigned char *rgb = NULL;
    int maxval = 0;

    if (f == NULL)
        return NULL;
    if (fscanf(f, "P6 %d %d %d", w, h, &maxval) == 3 && maxval == 255 && *w > 0 && *h > 0 && *w <= 16384
        && *h <= 16384 && fgetc(f) != EOF) {
        size_t n = (size_t)*w * (size_t)*h * 3u;
        rgb = malloc(n);
        if (rgb != NULL && fread(rgb, 1, n, f) != n) {
            free(rgb);
            rgb = NULL;
        }
    }
    fclose(f);
    return rgb;
}

int main(int argc, char **argv)
{
    char err[256];
    unsigned char *rgb;
    int w = 0, h = 0, rc;

    if (argc != 3) {
        fprintf(stderr, "usage: lumo-ppm-to-png IN.ppm OUT.png\n");
        return 2;
    }
    rgb = read_ppm(argv[1], &w, &h);
    if (rgb == NULL) {
        fprintf(stderr, "lumo-ppm-to-png: %s: not a readable binary PPM (P6, maxval 255)\n", argv[1]);
        return 1;
    }
    rc = host_png_write_rgb8(argv[2], rgb, w, h, err, sizeof err);
    if (rc != 0)
        fprintf(stderr, "lumo-ppm-to-png: %s: %s\n", argv[2], err);
    free(rgb);
    return rc != 0;
}
