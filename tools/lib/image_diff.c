/*
 * image_diff.c — see lumo_host/image_diff.h.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/image_diff.h"

/* Delta E histogram for the 99th percentile: bins of 0.01 up to 200, the
 * last bin holding everything above (Delta E of sRGB colours stays < 200). */
enum { DE_BINS = 20001 };

/* IEC 61966-2-1 sRGB decoding to linear light. */
static double srgb_to_linear(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

/* CIE 1976 f(t): cube root above (6/29)^3, the linear toe below it. */
static double lab_f(double t)
{
    return t > 216.0 / 24389.0 ? cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0;
}

void host_srgb8_to_lab(const uint8_t rgb[3], double lab[3])
{
    double r = srgb_to_linear(rgb[0] / 255.0), g = srgb_to_linear(rgb[1] / 255.0),
           b = srgb_to_linear(rgb[2] / 255.0);
    /* sRGB -> XYZ (D65), each divided by the white point's coordinate. */
    double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    double fx = lab_f(x), fy = lab_f(y), fz = lab_f(z);

    lab[0] = 116 * fy - 16;
    lab[1] = 500 * (fx - fy);
    lab[2] = 200 * (fy - fz);
}

double host_delta_e76(const uint8_t a[3], const uint8_t b[3])
{
    double la[3], lb[3];

    host_srgb8_to_lab(a, la);
    host_srgb8_to_lab(b, lb);
    return sqrt((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1])
                + (la[2] - lb[2]) * (la[2] - lb[2]));
}

/* Smallest Delta E (a multiple of 0.01) at or below which 99 % of the n
 * pixels lie; 0 without a histogram. */
static double percentile99(const uint32_t *hist, size_t n)
{
    size_t acc = 0;

    for (int bin = 0; hist && bin < DE_BINS; bin++) {
        acc += hist[bin];
        if (acc * 100 >= n * 99)
            return bin / 100.0;
    }
    return 0;
}

void host_image_diff_rgb8(const uint8_t *a, const uint8_t *b, size_t n, host_image_diff *out)
{
    /* Without memory for the histogram only p99 is lost (reported 0). */
    uint32_t *hist = calloc(DE_BINS, sizeof *hist);
    double sum = 0, sq = 0, maxde = 0;

    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < n; i++) {
        double de = host_delta_e76(a + 3 * i, b + 3 * i);
        sum += de;
        if (de > maxde)
            maxde = de;
        if (hist)
            hist[de >= 200 ? DE_BINS - 1 : (int)(de * 100)]++;
        for (int k = 0; k < 3; k++) {
            double d = (double)a[3 * i + k] - b[3 * i + k];
            sq += d * d;
        }
    }
    out->mean_de = n ? sum / n : 0;
    out->max_de = maxde;
    out->psnr_db = sq == 0 ? 99.0 : 10 * log10(255.0 * 255.0 / (sq / (3.0 * n)));
    out->p99_de = percentile99(hist, n);
    free(hist);
}
