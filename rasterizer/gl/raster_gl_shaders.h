/*
 * raster_gl_shaders.h — GLSL of the GL backends, shared by OSMesa and EGL.
 * Compiled as "#version 330 core" or "#version 300 es" plus PER_PIXEL when
 * lighting per pixel. The model is docs/rasterizer.md, the same as the soft
 * rasterizer's integer code (rasterizer/soft/raster_shade.c).
 */
#ifndef LUMO_RASTER_GL_SHADERS_H
#define LUMO_RASTER_GL_SHADERS_H

#include "lumo/config.h"

/* The light arrays are sized by LUMO_MAX_LIGHTS, spelled into the source. */
#define LUMO_GL_STR_(x) #x
#define LUMO_GL_STR(x) LUMO_GL_STR_(x)
#define LUMO_GL_MAX_LIGHTS LUMO_GL_STR(LUMO_MAX_LIGHTS)

/* Uniforms and functions both stages use. */
static const char lumo_gl_common_glsl[] =
    "const float PI = 3.14159265358979;\n"
    "uniform vec3 u_eye;\n"
    "uniform float u_exposure;\n"
    "uniform int u_nlights;\n"
    "uniform int u_kind[" LUMO_GL_MAX_LIGHTS "];\n"          /* 0 point, 1 spot, 2 directional */
    "uniform vec3 u_lpos[" LUMO_GL_MAX_LIGHTS "];\n"
    "uniform vec3 u_ldir[" LUMO_GL_MAX_LIGHTS "];\n"
    "uniform float u_lcos[" LUMO_GL_MAX_LIGHTS "];\n"
    "uniform vec3 u_lval[" LUMO_GL_MAX_LIGHTS "];\n"         /* intensity W/sr, or E W/m^2 */
    "uniform int u_indirect;\n"
    "uniform vec3 u_gmin, u_gext, u_tscale, u_toff;\n"
    "uniform highp sampler3D u_cpx, u_cnx, u_cpy, u_cny, u_cpz, u_cnz;\n"
    "uniform highp sampler3D u_dpx, u_dnx, u_dpy, u_dny, u_dpz, u_dnz;\n"
    /* Seed 000 §3.2: hemisphere by the sign of each normal component,
     * c and d filtered separately by the hardware, I_n . n =
     * sum n_a^2 (d_a . n) c_a. */
    "vec3 ivg_irradiance(vec3 p, vec3 n) {\n"
    "    vec3 tc = clamp((p - u_gmin) / u_gext, 0.0, 1.0) * u_tscale + u_toff;\n"
    "    vec3 c, d, s = vec3(0.0);\n"
    "    if (n.x >= 0.0) { c = texture(u_cpx, tc).rgb; d = texture(u_dpx, tc).rgb; }\n"
    "    else            { c = texture(u_cnx, tc).rgb; d = texture(u_dnx, tc).rgb; }\n"
    "    s += n.x * n.x * dot(d * 2.0 - 1.0, n) * c;\n"
    "    if (n.y >= 0.0) { c = texture(u_cpy, tc).rgb; d = texture(u_dpy, tc).rgb; }\n"
    "    else            { c = texture(u_cny, tc).rgb; d = texture(u_dny, tc).rgb; }\n"
    "    s += n.y * n.y * dot(d * 2.0 - 1.0, n) * c;\n"
    "    if (n.z >= 0.0) { c = texture(u_cpz, tc).rgb; d = texture(u_dpz, tc).rgb; }\n"
    "    else            { c = texture(u_cnz, tc).rgb; d = texture(u_dnz, tc).rgb; }\n"
    "    s += n.z * n.z * dot(d * 2.0 - 1.0, n) * c;\n"
    "    return max(s, vec3(0.0));\n"
    "}\n"
    /* Shadow maps (raster_gl_shadow.c): per light its first layer, faces
     * (0: none, 1, or 6 for a cube), texels per side and far plane; the
     * eye and near plane of its views; cot(fov/2); the basis (rows as
     * columns) of its one face; the six cube faces' bases. */
    "uniform highp sampler2DArray u_smap;\n"
    "uniform vec4 u_sinfo[" LUMO_GL_MAX_LIGHTS "];\n"
    "uniform vec4 u_seye[" LUMO_GL_MAX_LIGHTS "];\n"
    "uniform float u_scot[" LUMO_GL_MAX_LIGHTS "];\n"
    "uniform mat3 u_srot[" LUMO_GL_MAX_LIGHTS "];\n"
    "uniform mat3 u_scube[6];\n"
    /* 1 when texel t of the layer does not hide view depth wb (stored:
     * w / far, cleared to 1). */
    "float shadow_texel(vec2 t, float layer, float size, float far, float wb) {\n"
    "    ivec2 ij = ivec2(clamp(t, 0.0, size - 1.0));\n"
    "    return texelFetch(u_smap, ivec3(ij, int(layer)), 0).r * far >= wb ? 1.0 : 0.0;\n"
    "}\n"
    /* The soft path's lookup (rasterizer/soft/raster_shadow.c): the cube
     * face of the major axis, normal offset 1.5 texel footprints, depth
     * bias one footprint, 2x2 PCF with 1/16-texel weights; a point outside
     * a one-face map or before the near plane is lit. */
    "float shadow_visibility(int i, vec3 p, vec3 n) {\n"
    "    vec4 info = u_sinfo[i];\n"
    "    if (info.y < 0.5) return 1.0;\n"
    "    vec3 d = p - u_seye[i].xyz;\n"
    "    mat3 r = u_srot[i];\n"
    "    float layer = info.x, size = info.z, far = info.w, zn = u_seye[i].w, ct = u_scot[i];\n"
    "    if (info.y > 1.5) {\n"
    "        vec3 a = abs(d);\n"
    "        int k = a.y > a.x ? 1 : 0;\n"
    "        if (a.z > max(a.x, a.y)) k = 2;\n"
    "        int f = 2 * k + (d[k] < 0.0 ? 1 : 0);\n"
    "        r = u_scube[f];\n"
    "        layer += float(f);\n"
    "    }\n"
    "    vec3 c = d * r;\n"
    "    if (c.z < zn) return 1.0;\n"
    "    float foot = 2.0 * c.z / (size * ct);\n"
    "    c = (d + n * (1.5 * foot)) * r;\n"
    "    if (c.z < zn) return 1.0;\n"
    "    vec2 uv = size * 0.5 + c.xy * (ct * size * 0.5 / c.z) - 0.5;\n"
    "    if (info.y < 1.5 && (min(uv.x, uv.y) < -0.5 || max(uv.x, uv.y) > size - 0.5)) return 1.0;\n"
    "    float wb = c.z - foot;\n"
    "    if (wb <= 0.0) return 1.0;\n"
    "    uv = floor(uv * 16.0 + 0.5) / 16.0;\n"
    "    vec2 t = floor(uv), w = uv - t;\n"
    "    return mix(mix(shadow_texel(t, layer, size, far, wb),\n"
    "                   shadow_texel(t + vec2(1.0, 0.0), layer, size, far, wb), w.x),\n"
    "               mix(shadow_texel(t + vec2(0.0, 1.0), layer, size, far, wb),\n"
    "                   shadow_texel(t + vec2(1.0, 1.0), layer, size, far, wb), w.x), w.y);\n"
    "}\n"
    /* Direct diffuse light, each light scaled by its map's visibility
     * (docs/scene-format.md, docs/rasterizer.md "Shadows"). */
    "vec3 direct_irradiance(vec3 p, vec3 n) {\n"
    "    vec3 e = vec3(0.0);\n"
    "    for (int i = 0; i < 16; i++) {\n"
    "        if (i >= u_nlights) break;\n"
    "        if (u_kind[i] == 2) {\n"
    "            float cd = -dot(n, u_ldir[i]);\n"
    "            if (cd > 0.0) e += u_lval[i] * cd * shadow_visibility(i, p, n);\n"
    "            continue;\n"
    "        }\n"
    "        vec3 l = u_lpos[i] - p;\n"
    "        float d2 = max(dot(l, l), 256.0 / 65536.0);\n"
    "        vec3 w = normalize(l);\n"
    "        float c = dot(n, w);\n"
    "        if (c <= 0.0) continue;\n"
    "        if (u_kind[i] == 1 && -dot(w, u_ldir[i]) < u_lcos[i]) continue;\n"
    "        e += u_lval[i] * c / d2 * shadow_visibility(i, p, n);\n"
    "    }\n"
    "    return e;\n"
    "}\n"
    /* Two-sided: the normal faces the eye. */
    "vec3 radiance(vec3 p, vec3 n, vec3 albedo) {\n"
    "    n = normalize(n);\n"
    "    if (dot(n, u_eye - p) < 0.0) n = -n;\n"
    "    vec3 e = direct_irradiance(p, n);\n"
    "    if (u_indirect != 0) e += ivg_irradiance(p, n);\n"
    "    return albedo / PI * e;\n"
    "}\n"
    "vec3 tonemap(vec3 l) {\n"
    "    vec3 v = clamp(l * u_exposure, 0.0, 1.0);\n"
    "    return mix(12.92 * v, 1.055 * pow(v, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, v));\n"
    "}\n";

static const char lumo_gl_vertex_glsl[] =
    "in vec3 a_pos;\n"
    "in vec3 a_nrm;\n"
    "in vec3 a_alb;\n"
    "uniform mat4 u_mvp;\n"
    "#ifdef PER_PIXEL\n"
    "out vec3 v_pos; out vec3 v_nrm; out vec3 v_alb;\n"
    "#else\n"
    "out vec3 v_rad;\n"
    "#endif\n"
    "void main() {\n"
    "    gl_Position = u_mvp * vec4(a_pos, 1.0);\n"
    "#ifdef PER_PIXEL\n"
    "    v_pos = a_pos; v_nrm = a_nrm; v_alb = a_alb;\n"
    "#else\n"
    "    v_rad = radiance(a_pos, a_nrm, a_alb);\n"
    "#endif\n"
    "}\n";

static const char lumo_gl_fragment_glsl[] =
    "#ifdef PER_PIXEL\n"
    "in vec3 v_pos; in vec3 v_nrm; in vec3 v_alb;\n"
    "#else\n"
    "in vec3 v_rad;\n"
    "#endif\n"
    "out vec4 o_color;\n"
    "void main() {\n"
    "#ifdef PER_PIXEL\n"
    "    o_color = vec4(tonemap(radiance(v_pos, v_nrm, v_alb)), 1.0);\n"
    "#else\n"
    "    o_color = vec4(tonemap(v_rad), 1.0);\n"
    "#endif\n"
    "}\n";

/* Shadow maps: depth only, w / far (linear view depth) into a
 * GL_DEPTH_COMPONENT32F layer (raster_gl_shadow.c). */
static const char lumo_gl_depth_vertex_glsl[] =
    "in vec3 a_pos;\n"
    "uniform mat4 u_smvp;\n"
    "void main() { gl_Position = u_smvp * vec4(a_pos, 1.0); }\n";

static const char lumo_gl_depth_fragment_glsl[] =
    "uniform float u_sinvfar;\n"
    "void main() { gl_FragDepth = u_sinvfar / gl_FragCoord.w; }\n";

#endif
