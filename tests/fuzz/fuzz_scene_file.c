/* fuzz_scene_file.c — hostile text into the scene-description parser
 * (srv_scene_parse, server/scene/scene_file.c; docs/scene-format.md):
 * statements, shapes, lights, cameras, mesh options. Mesh files are looked
 * up in an empty private directory, so a relative "mesh" statement meets
 * the model front end's refusals; the scene is freed after every input.
 * Host code: built by tests/hostile/hostile.mk with the server's scene
 * room and assimp. Seeds in tests/fuzz/seeds/fuzz_scene_file/. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "scene/import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char *empty_dir(void)
{
    static char dir[64];
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/lumo-fuzz-scene-XXXXXX");
        if (!mkdtemp(dir))
            abort();
    }
    return dir;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[512];
    srv_scene s;
    srv_scene_init(&s);
    lumo_status st = srv_scene_parse(&s, "fuzz.txt", empty_dir(), (const char *)data, size, err, sizeof err);
    if (st && strncmp(err, "fuzz.txt:", 9))
        abort();   /* a refusal names the file and line */
    if (!st)
        srv_scene_validate(&s, err, sizeof err);
    srv_scene_free(&s);
    return 0;
}
