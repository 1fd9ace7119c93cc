/* color_diff.c — sRGB -> XYZ -> CIE Lab (D65) and the mean CIE76 Delta E,
 * the image metric of the benchmarks (issue 3, "mean CIE Lab Delta E"). */
#include <math.h>
#include "lumo_server/color_diff.h"

static double srgb_decode(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

void lumo_srgb8_to_lab(const uint8_t rgb[3], double lab[3])
{
    double r = srgb_decode(rgb[0] / 255.0), g = srgb_decode(rgb[1] / 255.0), b = srgb_decode(rgb[2] / 255.0);
    /* IEC 61966-2-1 primaries, D65; white normalised to Y = 1. */
    double x = 0.4124 * r + 0.3576 * g + 0.1805 * b;
    double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    double z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
    double fx = lab_f(x / 0.95047), fy = lab_f(y), fz = lab_f(z / 1.08883);
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 500.0 * (fx - fy);
    lab[2] = 200.0 * (fy - fz);
}

double lumo_mean_delta_e(const uint8_t *a, const uint8_t *b, size_t npixels)
{
    double sum = 0.0;
    for (size_t i = 0; i < npixels; i++) {
        double la[3], lb[3];
        lumo_srgb8_to_lab(a + 3 * i, la);
        lumo_srgb8_to_lab(b + 3 * i, lb);
        sum += sqrt((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1]) +
                    (la[2] - lb[2]) * (la[2] - lb[2]));
    }
    return npixels ? sum / (double)npixels : 0.0;
}
