/*
 * raster_gl_api.h — the GL entry points of lumo's GL backends, one table for
 * every file of rasterizer/gl (the renderer, its shadow maps, the PRT
 * multipass, the VSL renderer). Desktop code, not client API: the backends
 * reach GL through the context's get-proc-address (lumo/raster_gl.h), so
 * no libGL is linked. Every name is in OpenGL 3.3 core and OpenGL ES 3.0
 * but the optional ones (glDrawBuffer is desktop-only; query objects are
 * used for counting only where they exist).
 */
#ifndef LUMO_RASTER_GL_API_H
#define LUMO_RASTER_GL_API_H

#include <stddef.h>
#include <GL/glcorearb.h>
#include "lumo/raster_gl.h"

#define LUMO_GL_FUNCS(X)                                                       \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
    X(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)                         \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                                           \
    X(PFNGLBUFFERDATAPROC, BufferData)                                         \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
    X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
    X(PFNGLCLEARPROC, Clear)                                                   \
    X(PFNGLCOLORMASKPROC, ColorMask)                                           \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
    X(PFNGLCREATESHADERPROC, CreateShader)                                     \
    X(PFNGLCULLFACEPROC, CullFace)                                             \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
    X(PFNGLDISABLEPROC, Disable)                                               \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                         \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                                       \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                                     \
    X(PFNGLENABLEPROC, Enable)                                                 \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
    X(PFNGLFINISHPROC, Finish)                                                 \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                     \
    X(PFNGLFRAMEBUFFERTEXTURELAYERPROC, FramebufferTextureLayer)               \
    X(PFNGLFRONTFACEPROC, FrontFace)                                           \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
    X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
    X(PFNGLGETERRORPROC, GetError)                                             \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
    X(PFNGLGETSTRINGPROC, GetString)                                           \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
    X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                   \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                                         \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                       \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
    X(PFNGLTEXIMAGE3DPROC, TexImage3D)                                         \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
    X(PFNGLUNIFORM1FVPROC, Uniform1fv)                                         \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
    X(PFNGLUNIFORM1IVPROC, Uniform1iv)                                         \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv)                                         \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv)                                         \
    X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                             \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                             \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
    X(PFNGLVIEWPORTPROC, Viewport)

#define LUMO_GL_OPTIONAL_FUNCS(X)                                              \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                                         \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                   \
    X(PFNGLDRAWBUFFERPROC, DrawBuffer)                                         \
    X(PFNGLENDQUERYPROC, EndQuery)                                             \
    X(PFNGLGENQUERIESPROC, GenQueries)                                         \
    X(PFNGLGETQUERYOBJECTUIVPROC, GetQueryObjectuiv)

typedef struct lumo_gl_api {
#define LUMO_GL_MEMBER(type, name) type name;
    LUMO_GL_FUNCS(LUMO_GL_MEMBER)
    LUMO_GL_OPTIONAL_FUNCS(LUMO_GL_MEMBER)
#undef LUMO_GL_MEMBER
} lumo_gl_api;

/* Fill gl from getproc: 0, or -1 with "GL entry point glX missing" in err
 * when a required one is missing (the optional ones are left NULL). */
int lumo_gl_api_load(lumo_gl_api *gl, lumo_gl_getproc_fn getproc, char *err, size_t errlen);

#endif
