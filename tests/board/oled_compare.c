/*
 * oled_compare.c — the lm3s6965evb's OLED as QEMU shows it against the
 * host's prediction (boards/lm3s6965evb/client-test.sh).
 *
 *   oled-compare SCREENDUMP.ppm HOST.pgm
 *
 * SCREENDUMP is QMP's `screendump` of the SSD0323 console: a binary PPM of
 * 512 x 256, each OLED pixel drawn as a 4 x 4 block of grey 17 x level
 * (QEMU hw/display/ssd0323.c, MAGNIFY 4, 32-bit surface). HOST is the host
 * client's grey picture (boards/client/client.c --out: grey-*-128x64.pgm,
 * 17 x level too). Every block must be one grey and a multiple of 17; the
 * 128 x 64 levels are compared pixel by pixel. Prints how many differ and
 * by how much; exit 0 only when none does, 1 when some do, 2 on a file
 * that is not what it should be.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 128
#define H 64
#define MAG 4

/* A binary PNM (P5 or P6, maxval 255) of exactly w x h into px. */
static int read_pnm(const char *path, const char *magic, int w, int h, unsigned char *px, size_t bytes)
{
    FILE *f = fopen(path, "rb");
    char m[3] = {0};
    int fw, fh, maxval;

    if (!f) {
        fprintf(stderr, "oled-compare: cannot open %s\n", path);
        return -1;
    }
    if (fscanf(f, "%2s %d %d %d", m, &fw, &fh, &maxval) != 4 || strcmp(m, magic) || fw != w || fh != h ||
        maxval != 255 || fgetc(f) == EOF || fread(px, 1, bytes, f) != bytes) {
        fprintf(stderr, "oled-compare: %s is not a %dx%d %s image with maxval 255\n", path, w, h, magic);
        fclose(f);
        return -1;
    }
    fclose(f);
    return 0;
}

/* The level of the block at (x, y): -1 when it is not one grey of 17 k. */
static int block_level(const unsigned char *rgb, int x, int y)
{
    const unsigned char *first = rgb + ((size_t)(y * MAG) * W * MAG + (size_t)x * MAG) * 3;
    int i, j, k;

    for (j = 0; j < MAG; j++)
        for (i = 0; i < MAG; i++)
            for (k = 0; k < 3; k++)
                if (rgb[((size_t)(y * MAG + j) * W * MAG + (size_t)(x * MAG + i)) * 3 + k] != first[0])
                    return -1;
    return first[0] % 17 ? -1 : first[0] / 17;
}

int main(int argc, char **argv)
{
    static unsigned char dump[W * MAG * H * MAG * 3], host[W * H];
    int x, y, differ = 0, worst = 0;

    if (argc != 3) {
        fprintf(stderr, "usage: oled-compare SCREENDUMP.ppm HOST.pgm\n");
        return 2;
    }
    if (read_pnm(argv[1], "P6", W * MAG, H * MAG, dump, sizeof dump) ||
        read_pnm(argv[2], "P5", W, H, host, sizeof host))
        return 2;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int got = block_level(dump, x, y), want = host[y * W + x] / 17, d;
            if (got < 0 || host[y * W + x] % 17) {
                fprintf(stderr, "oled-compare: pixel %d,%d is not a 16-level grey\n", x, y);
                return 2;
            }
            d = abs(got - want);
            differ += d != 0;
            worst = d > worst ? d : worst;
        }
    printf("oled-compare: %d of %d pixels differ (largest difference %d of 15 levels)\n", differ, W * H, worst);
    return differ ? 1 : 0;
}
