/*
 * raster_gl_prt_shaders.h — GLSL of the GL backends' PRT multipass
 * (raster_gl_prt.c; seed 003 Ch. 4, Eq. 7). Compiled after the version
 * line and lumo_gl_common_glsl (u_eye, u_exposure, tonemap), with NP
 * (registers per cluster: the mean's and each component's dot products,
 * P + 1) defined and the weights' inputs and sum written by
 * raster_gl_prt.c for the chunk's component count.
 */
#ifndef LUMO_RASTER_GL_PRT_SHADERS_H
#define LUMO_RASTER_GL_PRT_SHADERS_H

#include "lumo/raster_gl_prt.h"

#define LUMO_GL_PRT_STR_(x) #x
#define LUMO_GL_PRT_STR(x) LUMO_GL_PRT_STR_(x)

/* One pass (§4.3): u_reg holds, for the pass's cluster in slot s,
 * u_reg[s * NP + j].rgb = (B_j . L) per channel (j = 0: the mean M . L).
 * A vertex of another pass, or seen from its back (the transfer holds
 * the front hemisphere only, as lumo_prt_shade's back entries), adds
 * zero; the blend sums the passes. The depth pre-pass draws with
 * u_pass = -1: invariant positions make the passes' depths equal to it. */
/* Three parts: raster_gl_prt.c writes the weight inputs (a_w0.., vec4)
 * between the first two and the weighted sum between the last two. */
static const char lumo_gl_prt_vertex_head_glsl[] =
    "in vec3 a_pos;\n"
    "in vec3 a_nrm;\n"
    "in vec3 a_alb;\n"
    "in vec2 a_ps;\n";                    /* the vertex's pass, its cluster's slot in the pass */

static const char lumo_gl_prt_vertex_mid_glsl[] =
    "uniform mat4 u_mvp;\n"
    "uniform float u_pass;\n"
    "uniform vec4 u_reg[" LUMO_GL_PRT_STR(LUMO_GL_PRT_REGISTERS) "];\n"
    "out vec3 v_rad;\n"
    "invariant gl_Position;\n"
    "void main() {\n"
    "    gl_Position = u_mvp * vec4(a_pos, 1.0);\n"
    "    v_rad = vec3(0.0);\n"
    "    if (a_ps.x != u_pass || dot(a_nrm, u_eye - a_pos) < 0.0) return;\n"
    "    int b = int(a_ps.y) * NP;\n"
    "    vec3 t = u_reg[b].rgb;\n";

static const char lumo_gl_prt_vertex_tail_glsl[] =
    "    v_rad = a_alb * max(t, 0.0);\n"
    "}\n";

static const char lumo_gl_prt_fragment_glsl[] =
    "in vec3 v_rad;\n"
    "out vec4 o_color;\n"
    "void main() { o_color = vec4(v_rad, 1.0); }\n";

/* The summed radiance tone-mapped into the renderer's frame: one
 * triangle covering the viewport, each pixel fetched unfiltered. */
static const char lumo_gl_prt_resolve_vertex_glsl[] =
    "void main() {\n"
    "    gl_Position = vec4(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1), 0.0, 1.0);\n"
    "}\n";

static const char lumo_gl_prt_resolve_fragment_glsl[] =
    "uniform highp sampler2D u_acc;\n"
    "out vec4 o_color;\n"
    "void main() { o_color = vec4(tonemap(texelFetch(u_acc, ivec2(gl_FragCoord.xy), 0).rgb), 1.0); }\n";

#endif
