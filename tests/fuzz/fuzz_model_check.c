/* fuzz_model_check.c — hostile bytes into lumo's own model checks, the
 * front end every model passes before assimp (server/scene/model_check.h).
 * The first byte picks the reader (OBJ, PLY, OFF, STL, glTF, GLB, by name
 * or by content);
 * the rest is the file. Nothing may read out of bounds or overflow, the
 * reason must be one terminated line naming the file, and an accepted PLY
 * or OFF must declare no more than its bytes can hold. Host code: built
 * by tests/hostile/hostile.mk with the server's flags. Seeds in
 * tests/fuzz/seeds/fuzz_model_check/ (first byte 'o', 'p', 'f', 's', 'g',
 * 'b' or 'x'). A glTF's external buffers are looked up beside "fuzz.gltf"
 * (the working directory): only stat'ed, never read. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "scene/model_check.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char *name_of(uint8_t pick)
{
    switch (pick) {
    case 'o': return "fuzz.obj";
    case 'p': return "fuzz.ply";
    case 'f': return "fuzz.off";
    case 's': return "fuzz.stl";
    case 'g': return "fuzz.gltf";
    case 'b': return "fuzz.glb";
    default: return "fuzz";   /* by content */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[256];
    if (size < 1)
        return 0;
    const char *name = name_of(data[0]);
    /* A copy of exactly the file's size: ASan sees any read past its end. */
    uint8_t *file = malloc(size - 1 ? size - 1 : 1);
    if (!file)
        return 0;
    memcpy(file, data + 1, size - 1);
    memset(err, 'x', sizeof err);
    err[sizeof err - 1] = 0;
    srv_model_format fmt = srv_model_format_of(name, file, size - 1);
    lumo_status st = srv_model_check_bytes(name, file, size - 1, fmt, err, sizeof err);
    if (st && (strncmp(err, name, strlen(name)) || strchr(err, '\n')))
        abort();   /* a refusal names the file in one line */
    free(file);
    return 0;
}
