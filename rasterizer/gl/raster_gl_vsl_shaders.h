/*
 * raster_gl_vsl_shaders.h — GLSL 3.30 core of seed 004's renderer
 * (lumo/raster_gl_vsl.h, §0.6, §0.7.3). Every program is the common part
 * followed by its own stages.
 */
#ifndef LUMO_RASTER_GL_VSL_SHADERS_H
#define LUMO_RASTER_GL_VSL_SHADERS_H

/* The G-buffer's textures, the lights with their shadow maps, one VSL's
 * uniforms and the light functions every program may call. */
static const char vsl_common_glsl[] =
    "#version 330 core\n"
    "const float PI = 3.14159265358979;\n"
    "uniform vec3 u_eye;\n"
    "uniform sampler2D u_gpos, u_gnrm, u_galb;\n"
    "uniform sampler2DArrayShadow u_shadow;\n"
    "uniform int u_nlights;\n"
    "uniform vec3 u_lpos[4], u_ldir[4], u_lint[4];\n"
    "uniform float u_lcos[4];\n"
    "uniform int u_lspot[4], u_lfirst[4], u_lcount[4];\n"
    "uniform mat4 u_lmat[24];\n"
    "uniform vec3 u_vpos, u_vnrm, u_vflux;\n"
    "uniform float u_varea, u_vcut2;\n"
    /* §0.4.1 with the engine's disc term (vsl_light.h): rho/pi Phi cos cos'
     * / (pi r^2 + dS'), nothing beyond the cut-off sphere (§0.7.3). */
    "vec3 vsl_light(vec3 p, vec3 n, vec3 alb, vec3 vp, vec3 vn, vec3 flux, float area, float cut2) {\n"
    "    vec3 d = vp - p;\n"
    "    float r2 = dot(d, d);\n"
    "    if (!(r2 > 0.0) || r2 > cut2) return vec3(0.0);\n"
    "    vec3 w = d * inversesqrt(r2);\n"
    "    float cl = -dot(vn, w), c = dot(n, w);\n"
    "    if (cl <= 0.0 || c <= 0.0) return vec3(0.0);\n"
    "    return alb / PI * flux * (c * cl / (PI * r2 + area));\n"
    "}\n"
    /* The first of the light's frusta that holds p answers (a spot has one,
     * a point light six). The point is pushed along its normal by about a
     * shadow-map texel against acne. */
    "float lit_fraction(int l, vec3 p, vec3 n) {\n"
    "    float dist = length(u_lpos[l] - p);\n"
    "    vec3 q0 = p + n * (0.002 + 0.004 * dist);\n"
    "    for (int k = 0; k < 6; k++) {\n"
    "        if (k >= u_lcount[l]) break;\n"
    "        vec4 c = u_lmat[u_lfirst[l] + k] * vec4(q0, 1.0);\n"
    "        if (c.w <= 0.0) continue;\n"
    "        vec3 q = c.xyz / c.w;\n"
    "        if (abs(q.x) > 1.0 || abs(q.y) > 1.0) continue;\n"
    "        q = q * 0.5 + 0.5;\n"
    "        return texture(u_shadow, vec4(q.xy, float(u_lfirst[l] + k), q.z));\n"
    "    }\n"
    "    return 1.0;\n"
    "}\n"
    /* Point and spot lights (intensity W/sr, a spot's hard cone as the
     * path tracer's), each through its shadow map. */
    "vec3 direct_light(vec3 p, vec3 n, vec3 alb) {\n"
    "    vec3 e = vec3(0.0);\n"
    "    for (int i = 0; i < 4; i++) {\n"
    "        if (i >= u_nlights) break;\n"
    "        vec3 l = u_lpos[i] - p;\n"
    "        float d2 = max(dot(l, l), 1e-8);\n"
    "        vec3 w = l * inversesqrt(d2);\n"
    "        float c = dot(n, w);\n"
    "        if (c <= 0.0) continue;\n"
    "        if (u_lspot[i] != 0 && -dot(w, u_ldir[i]) < u_lcos[i]) continue;\n"
    "        e += u_lint[i] * c / d2 * lit_fraction(i, p, n);\n"
    "    }\n"
    "    return alb / PI * e;\n"
    "}\n"
    "vec3 facing(vec3 p, vec3 n) {\n"
    "    n = normalize(n);\n"
    "    return dot(n, u_eye - p) < 0.0 ? -n : n;\n"
    "}\n";

/* Geometry with its attributes: the G-buffer pass, the whole-scene VSL
 * passes, and (no fragment output) the shadow maps. */
static const char vsl_geometry_vs[] =
    "in vec3 a_pos; in vec3 a_nrm; in vec3 a_alb;\n"
    "uniform mat4 u_mvp;\n"
    "out vec3 v_pos; out vec3 v_nrm; out vec3 v_alb;\n"
    "void main() {\n"
    "    gl_Position = u_mvp * vec4(a_pos, 1.0);\n"
    "    v_pos = a_pos; v_nrm = a_nrm; v_alb = a_alb;\n"
    "}\n";

static const char vsl_depth_fs[] =
    "void main() {}\n";

static const char vsl_gbuffer_fs[] =
    "in vec3 v_pos; in vec3 v_nrm; in vec3 v_alb;\n"
    "layout(location = 0) out vec4 o_pos;\n"
    "layout(location = 1) out vec4 o_nrm;\n"
    "layout(location = 2) out vec4 o_alb;\n"
    "void main() {\n"
    "    o_pos = vec4(v_pos, 1.0);\n"
    "    o_nrm = vec4(facing(v_pos, v_nrm), 0.0);\n"
    "    o_alb = vec4(v_alb, 1.0);\n"
    "}\n";

/* The paper's second value of Tables 2-3: the whole geometry again for
 * one VSL, shaded from its own attributes. */
static const char vsl_whole_fs[] =
    "in vec3 v_pos; in vec3 v_nrm; in vec3 v_alb;\n"
    "out vec4 o_color;\n"
    "void main() {\n"
    "    o_color = vec4(vsl_light(v_pos, facing(v_pos, v_nrm), v_alb, u_vpos, u_vnrm, u_vflux, u_varea, u_vcut2), 1.0);\n"
    "}\n";

/* One VSL's sphere of the cut-off radius (§0.7.3), a unit sphere scaled. */
static const char vsl_sphere_vs[] =
    "in vec3 a_pos;\n"
    "uniform mat4 u_mvp;\n"
    "uniform float u_vrad;\n"
    "uniform int u_fullscreen;\n"
    "void main() {\n"
    "    if (u_fullscreen != 0) {\n"
    "        vec2 q = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));\n"
    "        gl_Position = vec4(q, 0.0, 1.0);\n"
    "    } else {\n"
    "        gl_Position = u_mvp * vec4(u_vpos + a_pos * u_vrad, 1.0);\n"
    "    }\n"
    "}\n";

/* A full-screen triangle (three vertices, no attributes). */
static const char vsl_screen_vs[] =
    "void main() {\n"
    "    vec2 q = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));\n"
    "    gl_Position = vec4(q, 0.0, 1.0);\n"
    "}\n";

/* Reading the G-buffer at this pixel: 0 where no surface is. */
#define VSL_GBUFFER_READ                                                        \
    "    ivec2 px = ivec2(gl_FragCoord.xy);\n"                                  \
    "    vec4 p = texelFetch(u_gpos, px, 0);\n"                                 \
    "    if (p.w == 0.0) discard;\n"                                            \
    "    vec3 n = texelFetch(u_gnrm, px, 0).xyz;\n"                             \
    "    vec3 alb = texelFetch(u_galb, px, 0).rgb;\n"

static const char vsl_direct_fs[] =
    "out vec4 o_color;\n"
    "void main() {\n" VSL_GBUFFER_READ
    "    o_color = vec4(direct_light(p.xyz, n, alb), 1.0);\n"
    "}\n";

static const char vsl_deferred_fs[] =
    "out vec4 o_color;\n"
    "void main() {\n" VSL_GBUFFER_READ
    "    o_color = vec4(vsl_light(p.xyz, n, alb, u_vpos, u_vnrm, u_vflux, u_varea, u_vcut2), 1.0);\n"
    "}\n";

/* Every VSL at every pixel: VSL i is texels (0..2, i) of u_vsls: position
 * and area, normal and cut-off radius squared, flux. */
static const char vsl_onepass_fs[] =
    "uniform sampler2D u_vsls;\n"
    "uniform int u_nvsls;\n"
    "out vec4 o_color;\n"
    "void main() {\n" VSL_GBUFFER_READ
    "    vec3 s = vec3(0.0);\n"
    "    for (int i = 0; i < u_nvsls; i++) {\n"
    "        vec4 a = texelFetch(u_vsls, ivec2(0, i), 0), b = texelFetch(u_vsls, ivec2(1, i), 0);\n"
    "        vec3 f = texelFetch(u_vsls, ivec2(2, i), 0).rgb;\n"
    "        s += vsl_light(p.xyz, n, alb, a.xyz, b.xyz, f, a.w, b.w);\n"
    "    }\n"
    "    o_color = vec4(s, 1.0);\n"
    "}\n";

#endif
