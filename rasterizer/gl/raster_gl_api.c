/*
 * raster_gl_api.c — loads the GL entry point table (raster_gl_api.h).
 */
#include <stdio.h>
#include "raster_gl_api.h"

int lumo_gl_api_load(lumo_gl_api *gl, lumo_gl_getproc_fn getproc, char *err, size_t errlen)
{
#define LUMO_GL_LOAD(type, name)                                               \
    if (!(gl->name = (type)getproc("gl" #name))) {                             \
        snprintf(err, errlen, "GL entry point gl%s missing", #name);           \
        return -1;                                                             \
    }
    LUMO_GL_FUNCS(LUMO_GL_LOAD)
#undef LUMO_GL_LOAD
#define LUMO_GL_TRY(type, name) gl->name = (type)getproc("gl" #name);
    LUMO_GL_OPTIONAL_FUNCS(LUMO_GL_TRY)
#undef LUMO_GL_TRY
    return 0;
}
