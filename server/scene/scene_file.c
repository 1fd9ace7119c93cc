/* scene_file.c — the line-based scene description (docs/scene-format.md). */
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "scene/import.h"
#include "scene/shapes.h"

#define MAX_WORDS 16

/* The whole description, read at once (at most SRV_SCENE_MAX_BYTES). */
static char *read_text(const char *path, size_t size, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *text = f ? malloc(size ? size : 1) : NULL;
    if (text)
        *len = fread(text, 1, size, f);
    if (f)
        fclose(f);
    return text;
}

typedef struct {
    srv_scene *s;
    char dir[1024];
    char *w[MAX_WORDS];
    int  n;
    char err[256];
    uint64_t shape_tris;   /* triangles of the spheres so far */
} parser;

/* A refusal of the current statement: "WHAT: why" into p->err. */
__attribute__((format(printf, 3, 4))) static lumo_status refuse(parser *p, lumo_status st, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(p->err, sizeof p->err, fmt, ap);
    va_end(ap);
    return st;
}

/* Word i of the statement as 3 finite numbers; `what` names it (and its
 * syntax, "X,Y,Z") in the refusal. */
static lumo_status vec_word(parser *p, int i, const char *what, const char *syntax, vec3 *v)
{
    float f[3];
    if (i >= p->n)
        return refuse(p, LUMO_ERR_CORRUPT, "%s: %s is missing (%s)", p->w[0], what, syntax);
    if (srv_parse_floats(p->w[i], f, 3))
        return refuse(p, LUMO_ERR_CORRUPT, "%s: %s '%.48s' is not 3 finite numbers %s", p->w[0], what, p->w[i],
                      syntax);
    *v = v3(f[0], f[1], f[2]);
    return LUMO_OK;
}

/* A whole decimal integer in [0, INT_MAX], else -1. */
static int int_arg(const char *t)
{
    char *end;
    errno = 0;
    long v = strtol(t, &end, 10);
    return end == t || *end || errno || v < 0 || v > INT_MAX || *t == ' ' || *t == '+' ? -1 : (int)v;
}

/* Trailing options "albedo R,G,B", "inward", "segments N"; `from` is the
 * first optional word. Unknown words are errors. */
static lumo_status shape_opts(parser *p, int from, vec3 *albedo, int *inward, int *segments)
{
    for (int i = from; i < p->n; i++) {
        lumo_status st;
        if (!strcmp(p->w[i], "albedo")) {
            if ((st = vec_word(p, ++i, "albedo", "R,G,B", albedo)))
                return st;
        } else if (!strcmp(p->w[i], "inward") && inward) {
            *inward = 1;
        } else if (!strcmp(p->w[i], "segments") && segments) {
            if (++i >= p->n || (*segments = int_arg(p->w[i])) < 8 || *segments > SRV_SCENE_MAX_SEGMENTS)
                return refuse(p, LUMO_ERR_RANGE, "%s: segments '%.32s' must be in [8, %d]", p->w[0],
                              i < p->n ? p->w[i] : "", SRV_SCENE_MAX_SEGMENTS);
        } else {
            return refuse(p, LUMO_ERR_CORRUPT, "%s: unexpected '%.48s'", p->w[0], p->w[i]);
        }
    }
    return LUMO_OK;
}

/* One transform or albedo option of a mesh line at word i (its value at i + 1). */
static lumo_status mesh_opt(parser *p, int i, srv_xform *x, vec3 *albedo, int *has_albedo)
{
    const char *o = p->w[i], *a = i + 1 < p->n ? p->w[i + 1] : NULL;
    float f[4];
    if (!strcmp(o, "translate"))
        return vec_word(p, i + 1, "translate", "X,Y,Z", &x->translate);
    if (!strcmp(o, "albedo"))
        return *has_albedo = 1, vec_word(p, i + 1, "albedo", "R,G,B", albedo);
    if (!strcmp(o, "scale") && a && !srv_parse_floats(a, f, 1))
        return x->scale = v3(f[0], f[0], f[0]), LUMO_OK;
    if (!strcmp(o, "scale"))
        return vec_word(p, i + 1, "scale", "S or SX,SY,SZ", &x->scale);
    if (!strcmp(o, "rotate") && a && !srv_parse_floats(a, f, 4))
        return x->axis = v3(f[0], f[1], f[2]), x->angle_deg = f[3], LUMO_OK;
    if (!strcmp(o, "rotate"))
        return refuse(p, LUMO_ERR_CORRUPT, "mesh: rotate '%.48s' is not 4 finite numbers AX,AY,AZ,DEG", a ? a : "");
    return refuse(p, LUMO_ERR_CORRUPT, "mesh: unknown option '%.48s' (translate, scale, rotate, albedo)", o);
}

static lumo_status st_mesh(parser *p)
{
    srv_xform x = srv_xform_identity();
    vec3 albedo;
    int has_albedo = 0;
    char path[2048];
    if (p->n < 2)
        return refuse(p, LUMO_ERR_CORRUPT, "mesh needs a file");
    for (int i = 2; i < p->n; i += 2) {
        lumo_status st = mesh_opt(p, i, &x, &albedo, &has_albedo);
        if (st)
            return st;
    }
    if (p->w[1][0] == '/')
        snprintf(path, sizeof path, "%s", p->w[1]);
    else
        snprintf(path, sizeof path, "%s/%s", p->dir, p->w[1]);
    return srv_import_file(p->s, path, &x, has_albedo ? &albedo : NULL, p->err, sizeof p->err);
}

static lumo_status st_quad(parser *p)
{
    vec3 a, b, c, albedo = v3(0.8f, 0.8f, 0.8f);
    lumo_status st;
    if ((st = vec_word(p, 1, "corner", "X,Y,Z", &a)) || (st = vec_word(p, 2, "edge U", "UX,UY,UZ", &b)) ||
        (st = vec_word(p, 3, "edge V", "VX,VY,VZ", &c)) || (st = shape_opts(p, 4, &albedo, NULL, NULL)))
        return st;
    return srv_add_quad(p->s, "quad", a, b, c, albedo);
}

static lumo_status st_box(parser *p)
{
    vec3 a, b, albedo = v3(0.8f, 0.8f, 0.8f);
    int inward = 0;
    lumo_status st;
    if ((st = vec_word(p, 1, "corner 0", "X0,Y0,Z0", &a)) || (st = vec_word(p, 2, "corner 1", "X1,Y1,Z1", &b)))
        return st;
    if (!(a.x < b.x && a.y < b.y && a.z < b.z))
        return refuse(p, LUMO_ERR_CORRUPT, "box: corner 0 %s must lie below corner 1 %s on every axis", p->w[1],
                      p->w[2]);
    if ((st = shape_opts(p, 3, &albedo, &inward, NULL)))
        return st;
    return srv_add_box(p->s, "box", a, b, albedo, inward);
}

static lumo_status st_sphere(parser *p)
{
    vec3 a, albedo = v3(0.8f, 0.8f, 0.8f);
    int inward = 0, seg = 64;
    float r;
    lumo_status st;
    if ((st = vec_word(p, 1, "centre", "X,Y,Z", &a)))
        return st;
    if (p->n < 3 || srv_parse_floats(p->w[2], &r, 1) || !(r > 0.0f))
        return refuse(p, LUMO_ERR_CORRUPT, "sphere: radius '%.32s' is not a finite number above 0",
                      p->n < 3 ? "" : p->w[2]);
    if ((st = shape_opts(p, 3, &albedo, &inward, &seg)))
        return st;
    uint64_t tris = 2 * (uint64_t)seg * (uint64_t)(seg / 2 - 1);
    if (p->shape_tris + tris > SRV_SCENE_MAX_SHAPE_TRIS)
        return refuse(p, LUMO_ERR_LIMIT, "the description's spheres would hold %llu triangles, more than %llu "
                      "(SRV_SCENE_MAX_SHAPE_TRIS: text that small cannot justify more)",
                      (unsigned long long)(p->shape_tris + tris), (unsigned long long)SRV_SCENE_MAX_SHAPE_TRIS);
    p->shape_tris += tris;
    return srv_add_sphere(p->s, "sphere", a, r, seg, albedo, inward);
}

static lumo_status st_other(parser *p)
{
    const char *k = p->w[0];
    char why[200];
    vec3 a;
    lumo_status st;
    if (!strcmp(k, "light") && p->n == 2) {
        srv_light l;
        if (p->s->nlights >= LUMO_MAX_LIGHTS)
            return refuse(p, LUMO_ERR_LIMIT, "light '%.64s': more than %d lights; a scene holds at most %d "
                          "(LUMO_MAX_LIGHTS, lumo/config.h)", p->w[1], LUMO_MAX_LIGHTS, LUMO_MAX_LIGHTS);
        if (srv_light_parse(p->w[1], &l, p->err, sizeof p->err))
            return LUMO_ERR_CORRUPT;
        return l.kind == LUMO_LIGHT_AREA ? srv_add_area_light(p->s, &l) : srv_scene_add_light(p->s, &l);
    }
    if (!strcmp(k, "albedo") && p->n == 2) {
        if ((st = vec_word(p, 1, "albedo", "R,G,B", &a)))
            return st;
        srv_scene_override_albedo(p->s, a);
        return LUMO_OK;
    }
    if (!strcmp(k, "camera") && p->n == 2) {
        if (srv_camera_parse_why(p->w[1], &p->s->camera, why, sizeof why))
            return refuse(p, LUMO_ERR_CORRUPT, "camera '%.64s': %s", p->w[1], why);
        p->s->has_camera = 1;
        return LUMO_OK;
    }
    if (!strcmp(k, "light") || !strcmp(k, "albedo") || !strcmp(k, "camera"))
        return refuse(p, LUMO_ERR_CORRUPT, "%s takes one word, got %d", k, p->n - 1);
    return refuse(p, LUMO_ERR_CORRUPT, "unknown or malformed statement '%.48s'", k);
}

static lumo_status statement(parser *p)
{
    if (!strcmp(p->w[0], "motion"))   /* the dynamic engine's (server/vsl/vsl_motion.c) */
        return LUMO_OK;
    if (!strcmp(p->w[0], "mesh"))
        return st_mesh(p);
    if (!strcmp(p->w[0], "quad"))
        return st_quad(p);
    if (!strcmp(p->w[0], "box"))
        return st_box(p);
    if (!strcmp(p->w[0], "sphere"))
        return st_sphere(p);
    return st_other(p);
}

/* One line of the description (NUL-terminated in buf); LUMO_OK or the
 * statement's status with its reason in p->err. */
static lumo_status scene_line(parser *p, char *line)
{
    char *hash = strchr(line, '#'), *save = NULL;
    if (hash)
        *hash = 0;
    p->n = 0;
    for (char *t = strtok_r(line, " \t\r\n", &save); t; t = strtok_r(NULL, " \t\r\n", &save)) {
        if (p->n == MAX_WORDS) {
            snprintf(p->err, sizeof p->err, "more than %d words", MAX_WORDS);
            return LUMO_ERR_LIMIT;
        }
        p->w[p->n++] = t;
    }
    return p->n ? statement(p) : LUMO_OK;
}

lumo_status srv_scene_parse(srv_scene *s, const char *name, const char *dir, const char *text, size_t len,
                            char *err, size_t errlen)
{
    parser p;
    char line[SRV_SCENE_MAX_LINE + 2];
    size_t at = 0;
    memset(&p, 0, sizeof p);
    p.s = s;
    snprintf(p.dir, sizeof p.dir, "%s", dir);
    for (int lineno = 1; at < len; lineno++) {
        const char *nl = memchr(text + at, '\n', len - at);
        size_t n = (nl ? (size_t)(nl - text) : len) - at;
        if (n > SRV_SCENE_MAX_LINE) {
            snprintf(err, errlen, "%s:%d: line longer than %d characters", name, lineno, SRV_SCENE_MAX_LINE);
            return LUMO_ERR_LIMIT;
        }
        if (memchr(text + at, 0, n)) {
            snprintf(err, errlen, "%s:%d: a NUL byte: not a text file", name, lineno);
            return LUMO_ERR_CORRUPT;
        }
        memcpy(line, text + at, n);
        line[n] = 0;
        at += n + 1;
        lumo_status st = scene_line(&p, line);
        if (st) {
            snprintf(err, errlen, "%s:%d: %s", name, lineno, p.err);
            return st;
        }
    }
    return LUMO_OK;
}

lumo_status srv_scene_load(srv_scene *s, const char *path, char *err, size_t errlen)
{
    char tmp[1024];
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "%s: %s", path, stat(path, &st) ? "cannot open" : "not a regular file");
        return LUMO_ERR_IO;
    }
    if ((uint64_t)st.st_size > SRV_SCENE_MAX_BYTES) {
        snprintf(err, errlen, "%s: %lld bytes, scene descriptions of at most 1 MiB are read", path,
                 (long long)st.st_size);
        return LUMO_ERR_LIMIT;
    }
    size_t len = 0;
    char *text = read_text(path, (size_t)st.st_size, &len);
    if (!text) {
        snprintf(err, errlen, "%s: cannot open", path);
        return LUMO_ERR_IO;
    }
    snprintf(tmp, sizeof tmp, "%s", path);
    lumo_status rc = srv_scene_parse(s, path, dirname(tmp), text, len, err, errlen);
    free(text);
    return rc;
}
