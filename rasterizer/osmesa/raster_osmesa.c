/*
 * raster_osmesa.c — Mesa's off-screen GL as a lumo backend: the paper's
 * GPU path (seed 000, §3.3) on a machine without a GPU. The Gallium driver
 * is Mesa's choice (GALLIUM_DRIVER=llvmpipe|softpipe; LP_NUM_THREADS for
 * llvmpipe). Rendering goes to the shared renderer's FBO; OSMesa's own
 * buffer is only what makes the context current.
 */
#include <stdio.h>
#include <stdlib.h>
#include <GL/osmesa.h>
#include "lumo/raster_gl.h"

struct lumo_osmesa {
    OSMesaContext ctx;
    uint8_t *buffer;
    lumo_gl *gl;
};

static lumo_gl_proc getproc(const char *name)
{
    return (lumo_gl_proc)OSMesaGetProcAddress(name);
}

static OSMesaContext create_context(void)
{
    /* A 3.3 core profile first (GLSL 330); older Mesa only has the default. */
    static const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
        OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0
    };
    OSMesaContext c = OSMesaCreateContextAttribs(attribs, NULL);
    return c ? c : OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, NULL);
}

lumo_osmesa *lumo_osmesa_open(int width, int height, char *err, size_t errlen)
{
    lumo_osmesa *o = calloc(1, sizeof *o);

    if (!o) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    o->buffer = malloc((size_t)width * height * 4);
    o->ctx = create_context();
    if (!o->buffer || !o->ctx) {
        snprintf(err, errlen, "OSMesa: cannot create a context");
        lumo_osmesa_close(o);
        return NULL;
    }
    if (!OSMesaMakeCurrent(o->ctx, o->buffer, GL_UNSIGNED_BYTE, width, height)) {
        snprintf(err, errlen, "OSMesa: cannot make the context current");
        lumo_osmesa_close(o);
        return NULL;
    }
    o->gl = lumo_gl_create(getproc, 0, width, height, err, errlen);
    if (!o->gl) {
        lumo_osmesa_close(o);
        return NULL;
    }
    return o;
}

lumo_gl *lumo_osmesa_gl(lumo_osmesa *o)
{
    return o->gl;
}

void lumo_osmesa_close(lumo_osmesa *o)
{
    if (!o)
        return;
    lumo_gl_destroy(o->gl);
    if (o->ctx)
        OSMesaDestroyContext(o->ctx);
    free(o->buffer);
    free(o);
}
