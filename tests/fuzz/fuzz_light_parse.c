/* fuzz_light_parse.c — hostile text into the light syntax (--light of
 * lumo-bake and lumo-render, "light" lines of scene files;
 * server/scene/light_parse.c). Nothing may read out of bounds; a refusal is
 * one terminated line that names the option; an accepted light has finite
 * values, positions within SRV_SCENE_MAX_COORD, a unit direction (but a
 * point light, which has none) and powers >= 0. Host code: built by tests/hostile/hostile.mk. Seeds in
 * tests/fuzz/seeds/fuzz_light_parse/. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int bad_vec(vec3 v, float lo, float hi)
{
    return !(v.x >= lo && v.x <= hi && v.y >= lo && v.y <= hi && v.z >= lo && v.z <= hi);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[512];
    srv_light l;
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;   /* the parser takes C strings: bytes after a NUL are not its */
    memset(err, 'x', sizeof err);
    err[sizeof err - 1] = 0;
    if (srv_light_parse_as("--light", text, &l, err, sizeof err)) {
        if (strncmp(err, "--light '", 9) || strlen(err) >= sizeof err)
            abort();
    } else if (bad_vec(l.pos, -SRV_SCENE_MAX_COORD, SRV_SCENE_MAX_COORD) || bad_vec(l.power, 0.0f, 1e9f) ||
               (l.kind != LUMO_LIGHT_POINT && !(fabsf(v3_len(l.dir) - 1.0f) < 1e-3f)) || !(l.cos_half >= -1.0f && l.cos_half <= 1.0f)) {
        abort();
    }
    free(text);
    return 0;
}
