/* scene_file.c — the line-based scene description (docs/scene-format.md). */
#include <errno.h>
#include <libgen.h>
#include <limits.h>
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

static int vec_arg(const char *t, vec3 *v)
{
    float f[3];
    if (!t || srv_parse_floats(t, f, 3))
        return -1;
    *v = v3(f[0], f[1], f[2]);
    return 0;
}

/* A whole decimal integer in [0, INT_MAX], else -1. */
static int int_arg(const char *t)
{
    char *end;
    errno = 0;
    long v = strtol(t, &end, 10);
    return end == t || *end || errno || v < 0 || v > INT_MAX ? -1 : (int)v;
}

/* Trailing options "albedo R,G,B", "inward", "segments N"; `from` is the
 * first optional word. Unknown words are errors. */
static lumo_status shape_opts(parser *p, int from, vec3 *albedo, int *inward, int *segments)
{
    for (int i = from; i < p->n; i++) {
        if (!strcmp(p->w[i], "albedo") && i + 1 < p->n && !vec_arg(p->w[i + 1], albedo))
            i++;
        else if (!strcmp(p->w[i], "inward") && inward)
            *inward = 1;
        else if (!strcmp(p->w[i], "segments") && segments && i + 1 < p->n)
            *segments = int_arg(p->w[++i]);
        else {
            snprintf(p->err, sizeof p->err, "unexpected '%s'", p->w[i]);
            return LUMO_ERR_CORRUPT;
        }
    }
    return LUMO_OK;
}

static lumo_status st_mesh(parser *p)
{
    srv_xform x = srv_xform_identity();
    vec3 albedo;
    int has_albedo = 0;
    char path[2048];
    if (p->n < 2)
        return snprintf(p->err, sizeof p->err, "mesh needs a file"), LUMO_ERR_CORRUPT;
    for (int i = 2; i < p->n; i++) {
        const char *a = i + 1 < p->n ? p->w[i + 1] : NULL;
        float f[4];
        int ok = a != NULL;
        if (ok && !strcmp(p->w[i], "translate"))
            ok = !vec_arg(a, &x.translate);
        else if (ok && !strcmp(p->w[i], "scale") && !srv_parse_floats(a, f, 1))
            x.scale = v3(f[0], f[0], f[0]);
        else if (ok && !strcmp(p->w[i], "scale"))
            ok = !vec_arg(a, &x.scale);
        else if (ok && !strcmp(p->w[i], "rotate") && !srv_parse_floats(a, f, 4))
            x.axis = v3(f[0], f[1], f[2]), x.angle_deg = f[3];
        else if (ok && !strcmp(p->w[i], "albedo"))
            ok = !vec_arg(a, &albedo) && (has_albedo = 1);
        else
            ok = 0;
        if (!ok) {
            snprintf(p->err, sizeof p->err, "bad mesh option '%s'", p->w[i]);
            return LUMO_ERR_CORRUPT;
        }
        i++;
    }
    if (p->w[1][0] == '/')
        snprintf(path, sizeof path, "%s", p->w[1]);
    else
        snprintf(path, sizeof path, "%s/%s", p->dir, p->w[1]);
    return srv_import_file(p->s, path, &x, has_albedo ? &albedo : NULL, p->err, sizeof p->err);
}

static lumo_status st_shape(parser *p)
{
    vec3 a, b, c, albedo = v3(0.8f, 0.8f, 0.8f);
    int inward = 0, seg = 64;
    const char *k = p->w[0];
    if (!strcmp(k, "quad") && p->n >= 4 && !vec_arg(p->w[1], &a) && !vec_arg(p->w[2], &b) &&
        !vec_arg(p->w[3], &c))
        return shape_opts(p, 4, &albedo, NULL, NULL) ? LUMO_ERR_CORRUPT
               : srv_add_quad(p->s, "quad", a, b, c, albedo);
    if (!strcmp(k, "box") && p->n >= 3 && !vec_arg(p->w[1], &a) && !vec_arg(p->w[2], &b) &&
        a.x < b.x && a.y < b.y && a.z < b.z)
        return shape_opts(p, 3, &albedo, &inward, NULL) ? LUMO_ERR_CORRUPT
               : srv_add_box(p->s, "box", a, b, albedo, inward);
    float r;
    if (!strcmp(k, "sphere") && p->n >= 3 && !vec_arg(p->w[1], &a) &&
        !srv_parse_floats(p->w[2], &r, 1) && r > 0.0f) {
        if (shape_opts(p, 3, &albedo, &inward, &seg))
            return LUMO_ERR_CORRUPT;
        if (seg < 8 || seg > SRV_SCENE_MAX_SEGMENTS)
            return snprintf(p->err, sizeof p->err, "segments must be in [8, %d]", SRV_SCENE_MAX_SEGMENTS),
                   LUMO_ERR_RANGE;
        uint64_t tris = 2 * (uint64_t)seg * (uint64_t)(seg / 2 - 1);
        if (p->shape_tris + tris > SRV_SCENE_MAX_SHAPE_TRIS)
            return snprintf(p->err, sizeof p->err, "the description's spheres would hold %llu triangles, more than "
                            "%llu (SRV_SCENE_MAX_SHAPE_TRIS: text that small cannot justify more)",
                            (unsigned long long)(p->shape_tris + tris), (unsigned long long)SRV_SCENE_MAX_SHAPE_TRIS),
                   LUMO_ERR_LIMIT;
        p->shape_tris += tris;
        return srv_add_sphere(p->s, "sphere", a, r, seg, albedo, inward);
    }
    snprintf(p->err, sizeof p->err, "malformed %s", k);
    return LUMO_ERR_CORRUPT;
}

static lumo_status st_other(parser *p)
{
    const char *k = p->w[0];
    vec3 a;
    if (!strcmp(k, "light") && p->n == 2) {
        srv_light l;
        if (p->s->nlights >= LUMO_MAX_LIGHTS)
            return snprintf(p->err, sizeof p->err, "light '%.64s': more than %d lights; a scene holds at most %d "
                            "(LUMO_MAX_LIGHTS, lumo/config.h)", p->w[1], LUMO_MAX_LIGHTS, LUMO_MAX_LIGHTS),
                   LUMO_ERR_LIMIT;
        if (srv_light_parse(p->w[1], &l, p->err, sizeof p->err))
            return LUMO_ERR_CORRUPT;
        return l.kind == LUMO_LIGHT_AREA ? srv_add_area_light(p->s, &l) : srv_scene_add_light(p->s, &l);
    }
    if (!strcmp(k, "albedo") && p->n == 2 && !vec_arg(p->w[1], &a)) {
        srv_scene_override_albedo(p->s, a);
        return LUMO_OK;
    }
    if (!strcmp(k, "camera") && p->n == 2 && !srv_camera_parse(p->w[1], &p->s->camera)) {
        p->s->has_camera = 1;
        return LUMO_OK;
    }
    snprintf(p->err, sizeof p->err, "unknown or malformed statement '%s'", k);
    return LUMO_ERR_CORRUPT;
}

static lumo_status statement(parser *p)
{
    if (!strcmp(p->w[0], "motion"))   /* the dynamic engine's (server/vsl/vsl_motion.c) */
        return LUMO_OK;
    if (!strcmp(p->w[0], "mesh"))
        return st_mesh(p);
    if (!strcmp(p->w[0], "quad") || !strcmp(p->w[0], "box") || !strcmp(p->w[0], "sphere"))
        return st_shape(p);
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
