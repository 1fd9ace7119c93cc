/*
 * image_metrics.c — see image_metrics.h.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "image_metrics.h"

static double srgb_to_linear(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static double lab_f(double t)
{
    return t > 216.0 / 24389.0 ? cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0;
}

static void rgb_to_lab(const uint8_t *p, double lab[3])
{
    double r = srgb_to_linear(p[0] / 255.0), g = srgb_to_linear(p[1] / 255.0),
           b = srgb_to_linear(p[2] / 255.0);
    double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    double fx = lab_f(x), fy = lab_f(y), fz = lab_f(z);

    lab[0] = 116 * fy - 16;
    lab[1] = 500 * (fx - fy);
    lab[2] = 200 * (fy - fz);
}

void image_compare(const uint8_t *a, const uint8_t *b, size_t n, image_diff *out)
{
    /* Delta E histogram in steps of 0.01 up to 200 for the percentile. */
    enum { BINS = 20001 };
    uint32_t *hist = calloc(BINS, sizeof *hist);
    double sum = 0, sq = 0, maxde = 0;
    size_t i, acc = 0;
    int bin;

    memset(out, 0, sizeof *out);
    for (i = 0; i < n; i++) {
        double la[3], lb[3], de;
        int k;
        rgb_to_lab(a + 3 * i, la);
        rgb_to_lab(b + 3 * i, lb);
        de = sqrt((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1])
                  + (la[2] - lb[2]) * (la[2] - lb[2]));
        sum += de;
        if (de > maxde) maxde = de;
        if (hist) hist[de >= 200 ? BINS - 1 : (int)(de * 100)]++;
        for (k = 0; k < 3; k++) {
            double d = (double)a[3 * i + k] - b[3 * i + k];
            sq += d * d;
        }
    }
    out->mean_de = n ? sum / n : 0;
    out->max_de = maxde;
    out->psnr_db = sq == 0 ? 99.0 : 10 * log10(255.0 * 255.0 / (sq / (3.0 * n)));
    for (bin = 0; hist && bin < BINS; bin++) {
        acc += hist[bin];
        if (acc * 100 >= n * 99) {
            out->p99_de = bin / 100.0;
            break;
        }
    }
    free(hist);
}
