/*
 * raster_egl.c — the GL shaders through EGL, for a device with a GPU (or
 * Mesa's software drivers) and no window system. Tries, in order: Mesa's
 * surfaceless platform, then the default display; desktop OpenGL 3.3 core,
 * then OpenGL ES 3.0; no surface (EGL_KHR_surfaceless_context), then a
 * pbuffer. The renderer draws into its own FBO either way. LUMO_EGL_API=gles
 * in the environment starts at GLES 3 (tests the path of GLES-only devices).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include "lumo/raster_gl.h"

struct lumo_egl {
    EGLDisplay dpy;
    EGLContext ctx;
    EGLSurface surf;
    lumo_gl *gl;
    char desc[96];
};

static lumo_gl_proc getproc(const char *name)
{
    return (lumo_gl_proc)eglGetProcAddress(name);
}

static EGLDisplay open_display(const char **which)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    EGLDisplay d = EGL_NO_DISPLAY;
    EGLint major, minor;

    if (get_platform_display && ext && strstr(ext, "EGL_MESA_platform_surfaceless")) {
        d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
            *which = "surfaceless";
            return d;
        }
    }
    d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
        *which = "default display";
        return d;
    }
    return EGL_NO_DISPLAY;
}

/* A context of one API; 0 on success. */
static int make_context(lumo_egl *e, int gles, int width, int height, const char **surface)
{
    const EGLint cfg_attr[] = {
        EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
        EGL_RENDERABLE_TYPE, gles ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT,
        EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_NONE
    };
    const EGLint gl_attr[] = {
        EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE
    };
    const EGLint es_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    const EGLint pb_attr[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
    const char *ext = eglQueryString(e->dpy, EGL_EXTENSIONS);
    EGLConfig cfg;
    EGLint n = 0;

    if (!eglBindAPI(gles ? EGL_OPENGL_ES_API : EGL_OPENGL_API))
        return -1;
    if (!eglChooseConfig(e->dpy, cfg_attr, &cfg, 1, &n) || n < 1)
        return -1;
    e->ctx = eglCreateContext(e->dpy, cfg, EGL_NO_CONTEXT, gles ? es_attr : gl_attr);
    if (e->ctx == EGL_NO_CONTEXT)
        return -1;
    if (ext && strstr(ext, "EGL_KHR_surfaceless_context")
        && eglMakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, e->ctx)) {
        *surface = "no surface";
        return 0;
    }
    e->surf = eglCreatePbufferSurface(e->dpy, cfg, pb_attr);
    if (e->surf != EGL_NO_SURFACE && eglMakeCurrent(e->dpy, e->surf, e->surf, e->ctx)) {
        *surface = "pbuffer";
        return 0;
    }
    if (e->surf != EGL_NO_SURFACE)
        eglDestroySurface(e->dpy, e->surf);
    e->surf = EGL_NO_SURFACE;
    eglDestroyContext(e->dpy, e->ctx);
    e->ctx = EGL_NO_CONTEXT;
    return -1;
}

lumo_egl *lumo_egl_open(int width, int height, char *err, size_t errlen)
{
    lumo_egl *e = calloc(1, sizeof *e);
    const char *platform = "", *surface = "";
    int gles;

    if (!e) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    e->ctx = EGL_NO_CONTEXT;
    e->surf = EGL_NO_SURFACE;
    e->dpy = open_display(&platform);
    if (e->dpy == EGL_NO_DISPLAY) {
        snprintf(err, errlen, "EGL: no display (error 0x%x)", (unsigned)eglGetError());
        free(e);
        return NULL;
    }
    /* LUMO_EGL_API=gles skips desktop GL: the path of GLES-only devices. */
    gles = getenv("LUMO_EGL_API") && !strcmp(getenv("LUMO_EGL_API"), "gles");
    for (; gles < 2; gles++)
        if (make_context(e, gles, width, height, &surface) == 0)
            break;
    if (gles == 2) {
        snprintf(err, errlen, "EGL: no GL or GLES 3 context on the %s (error 0x%x)", platform,
                 (unsigned)eglGetError());
        lumo_egl_close(e);
        return NULL;
    }
    snprintf(e->desc, sizeof e->desc, "%s, %s, %s", platform,
             gles ? "OpenGL ES 3.0" : "OpenGL 3.3 core", surface);
    e->gl = lumo_gl_create(getproc, gles, width, height, err, errlen);
    if (!e->gl) {
        lumo_egl_close(e);
        return NULL;
    }
    return e;
}

lumo_gl *lumo_egl_gl(lumo_egl *e)
{
    return e->gl;
}

const char *lumo_egl_describe(const lumo_egl *e)
{
    return e->desc;
}

void lumo_egl_close(lumo_egl *e)
{
    if (!e)
        return;
    lumo_gl_destroy(e->gl);
    if (e->dpy != EGL_NO_DISPLAY) {
        eglMakeCurrent(e->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (e->ctx != EGL_NO_CONTEXT) eglDestroyContext(e->dpy, e->ctx);
        if (e->surf != EGL_NO_SURFACE) eglDestroySurface(e->dpy, e->surf);
        eglTerminate(e->dpy);
    }
    free(e);
}
