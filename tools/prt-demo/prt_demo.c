/* prt_demo.c — the helpers of `make demo-prt` (tools/prt-demo/demo_prt.sh):
 *   prt-demo env OUT.png W H     an equirectangular sky (y up, docs/prt.md):
 *                                blue above, a warm sun, dark ground
 *   prt-demo stack OUT.png IN...  PNG rows stacked top to bottom (the
 *                                contact sheet; narrower rows padded black) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/options.h"
#include "lumo_host/png_io.h"

static void sky(double th, double ph, double *rgb)
{
    double d[3] = {sin(th) * cos(ph), cos(th), sin(th) * sin(ph)}, sun[3] = {0.55, 0.6, 0.58};
    double l = sqrt(sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2]);
    double c = (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2]) / l;
    double up = d[1] > 0 ? d[1] : 0, s = pow(fmax(c, 0.0), 12.0);
    rgb[0] = d[1] > 0 ? 0.04 + 0.04 * up + s : 0.02;
    rgb[1] = d[1] > 0 ? 0.06 + 0.06 * up + 0.85 * s : 0.02;
    rgb[2] = d[1] > 0 ? 0.12 + 0.12 * up + 0.6 * s : 0.02;
}

static int env(const char *out, int w, int h)
{
    uint8_t *px = malloc(3u * (size_t)w * (size_t)h);
    if (!px)
        return 1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double rgb[3];
            sky(M_PI * (y + 0.5) / h, 2 * M_PI * (x + 0.5) / w, rgb);
            for (int c = 0; c < 3; c++)
                px[3 * ((size_t)y * (size_t)w + (size_t)x) + (size_t)c] = (uint8_t)lrint(fmin(rgb[c], 1.0) * 255);
        }
    int rc = host_png_write_rgb8(out, px, w, h, NULL, 0);
    free(px);
    return rc ? 1 : 0;
}

static int stack(const char *out, int n, char **in)
{
    uint8_t *img[16], *px;
    int w[16], h[16], W = 0, H = 0;
    if (n > 16)
        return 1;
    for (int i = 0; i < n; i++) {
        if (host_png_read_rgb8(in[i], &img[i], &w[i], &h[i])) {
            fprintf(stderr, "prt-demo: cannot read %s\n", in[i]);
            return 1;
        }
        W = w[i] > W ? w[i] : W, H += h[i];
    }
    if (!(px = calloc(3u * (size_t)W * (size_t)H, 1)))
        return 1;
    for (int i = 0, y0 = 0; i < n; y0 += h[i++]) {
        for (int y = 0; y < h[i]; y++)
            memcpy(px + 3u * ((size_t)(y0 + y) * (size_t)W), img[i] + 3u * (size_t)y * (size_t)w[i], 3u * (size_t)w[i]);
        free(img[i]);
    }
    int rc = host_png_write_rgb8(out, px, W, H, NULL, 0);
    free(px);
    return rc ? 1 : 0;
}

int main(int argc, char **argv)
{
    if (argc == 5 && !strcmp(argv[1], "env")) {
        char why[160];
        int w, h;
        if (host_opt_int("W", argv[3], 1, 16384, &w, why, sizeof why) ||
            host_opt_int("H", argv[4], 1, 16384, &h, why, sizeof why)) {
            fprintf(stderr, "prt-demo: error: %s\n", why);
            return 2;
        }
        return env(argv[2], w, h);
    }
    if (argc >= 4 && !strcmp(argv[1], "stack"))
        return stack(argv[2], argc - 3, argv + 3);
    fputs("usage: prt-demo env OUT.png W H | prt-demo stack OUT.png IN.png...\n", stderr);
    return 2;
}
