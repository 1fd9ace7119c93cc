/* light_parse.c — the light syntax of docs/scene-format.md ("point:X,Y,Z:R,G,B",
 * "spot:...", "directional:...", "area:...") read field by field, so a
 * refusal names the field that is wrong and the value it got (issue 24):
 *
 *   --light 'point:0,1:1,1,1': position needs 3 numbers, got 2
 *
 * Used by lumo-bake and lumo-render (--light) and by scene files. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "scene/scene.h"

#define LIGHT_MAX_TEXT   511
#define LIGHT_MAX_FIELDS 5
/* Largest power (W) or irradiance (W/m^2) per channel: far above any room
 * (a 100 W bulb is ~10 W of light), low enough that Φ/(4π d²) never
 * overflows a float on the way to the client's fixed point. */
#define LIGHT_MAX_POWER 1.0e9f

/* What is being read: the option or statement, the text, where to say why. */
typedef struct lp {
    const char *opt, *text;
    char       *err;
    size_t      errlen;
} lp;

static lumo_status refuse(const lp *p, const char *fmt, ...)
{
    char why[200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    snprintf(p->err, p->errlen, "%s '%.*s': %s", p->opt, 200, p->text, why);
    return LUMO_ERR_ARG;
}

/* The syntax of each kind, for "a spot light is ...". */
typedef struct kind_syntax {
    const char     *name, *syntax;
    int             fields;
    lumo_light_kind kind;
} kind_syntax;

static const kind_syntax k_kinds[] = {
    {"point", "point:X,Y,Z:R,G,B", 3, LUMO_LIGHT_POINT},
    {"spot", "spot:X,Y,Z:DX,DY,DZ:HALF_ANGLE_DEG:R,G,B", 5, LUMO_LIGHT_SPOT},
    {"directional", "directional:DX,DY,DZ:R,G,B", 3, LUMO_LIGHT_DIRECTIONAL},
    {"area", "area:X,Y,Z:UX,UY,UZ:VX,VY,VZ:R,G,B", 5, LUMO_LIGHT_AREA},
};

/* Split buf at every ':' (empty fields kept); the count, or max + 1. */
static int split_fields(char *buf, char **f, int max)
{
    int n = 0;
    for (char *s = buf;; s++) {
        char *colon = strchr(s, ':');
        if (n == max)
            return max + 1;
        f[n++] = s;
        if (!colon)
            return n;
        *colon = 0;
        s = colon;
    }
}

/* One number of a field: whole, finite; 0 or -1. */
static int read_number(const char *s, size_t n, float *out)
{
    char buf[64], *end;
    if (n == 0 || n >= sizeof buf || s[0] == ' ' || s[0] == '+' || (s[0] >= '\t' && s[0] <= '\r'))
        return -1;
    memcpy(buf, s, n);
    buf[n] = 0;
    errno = 0;
    *out = strtof(buf, &end);
    return *end || !isfinite(*out) || (errno == ERANGE && fabsf(*out) > 1.0f) ? -1 : 0;
}

/* n comma-separated numbers of the field called `what`, each within
 * [lo, hi] (`unit` says what they are in the message). */
static lumo_status read_field(const lp *p, const char *what, const char *field, int n, float lo, float hi,
                              const char *unit, float *out)
{
    int got = 1, k = 0;
    for (const char *c = field; *c; c++)
        got += *c == ',';
    if (got != n)
        return refuse(p, "%s needs %d number%s, got %d", what, n, n > 1 ? "s" : "", *field ? got : 0);
    for (const char *s = field;; k++) {
        const char *comma = strchr(s, ',');
        size_t len = comma ? (size_t)(comma - s) : strlen(s);
        if (read_number(s, len, &out[k]))
            return refuse(p, "%s%s%.0d '%.*s' is not a finite number", what, n > 1 ? " value " : "", n > 1 ? k + 1 : 0,
                          (int)(len > 40 ? 40 : len), s);
        if (!(out[k] >= lo && out[k] <= hi))
            return refuse(p, "%s%s%.0d = %g is outside [%g, %g]%s", what, n > 1 ? " value " : "", n > 1 ? k + 1 : 0,
                          out[k], lo, hi, unit);
        if (!comma)
            return LUMO_OK;
        s = comma + 1;
    }
}

static lumo_status read_vec(const lp *p, const char *what, const char *field, float lo, float hi, const char *unit,
                            vec3 *out)
{
    float f[3];
    lumo_status st = read_field(p, what, field, 3, lo, hi, unit, f);
    if (!st)
        *out = v3(f[0], f[1], f[2]);
    return st;
}

static lumo_status read_position(const lp *p, const char *what, const char *field, vec3 *out)
{
    return read_vec(p, what, field, -SRV_SCENE_MAX_COORD, SRV_SCENE_MAX_COORD, " m (SRV_SCENE_MAX_COORD)", out);
}

static lumo_status read_direction(const lp *p, const char *what, const char *field, vec3 *out)
{
    lumo_status st = read_vec(p, what, field, -SRV_SCENE_MAX_COORD, SRV_SCENE_MAX_COORD, "", out);
    if (!st && !(v3_len(*out) > 0.0f))
        return refuse(p, "%s %s has no length", what, field);
    return st;
}

static lumo_status read_power(const lp *p, lumo_light_kind kind, const char *field, vec3 *out)
{
    const char *what = kind == LUMO_LIGHT_DIRECTIONAL ? "irradiance" : "power";
    const char *unit = kind == LUMO_LIGHT_DIRECTIONAL ? " W/m^2" : " W";
    return read_vec(p, what, field, 0.0f, LIGHT_MAX_POWER, unit, out);
}

static lumo_status read_cone(const lp *p, const char *field, float *half)
{
    lumo_status st = read_field(p, "cone half-angle", field, 1, 0.0f, 180.0f, " degrees", half);
    if (!st && !(*half > 0.0f))
        return refuse(p, "cone half-angle %s must be above 0 degrees", field);
    return st;
}

/* An area light's edges span a parallelogram whose normal float can hold:
 * at least 1 um^2 and not a sliver (sine of the edges' angle >= 1e-4), so
 * the normalised U x V is a unit vector (near-parallel or denormal edges
 * gave a "unit" normal 0.1 % too long). Computed in double. */
static int area_ok(vec3 u, vec3 v)
{
    double cx = (double)u.y * v.z - (double)u.z * v.y, cy = (double)u.z * v.x - (double)u.x * v.z,
           cz = (double)u.x * v.y - (double)u.y * v.x;
    double a = sqrt(cx * cx + cy * cy + cz * cz);
    double lu = sqrt((double)u.x * u.x + (double)u.y * u.y + (double)u.z * u.z);
    double lv = sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
    return a >= 1e-12 && a >= 1e-4 * lu * lv;
}

/* The fields after the kind, by kind. */
static lumo_status read_kind(const lp *p, lumo_light_kind kind, char **f, srv_light *l)
{
    lumo_status st;
    switch (kind) {
    case LUMO_LIGHT_POINT:
        return (st = read_position(p, "position", f[1], &l->pos)) ? st : read_power(p, kind, f[2], &l->power);
    case LUMO_LIGHT_SPOT:
        if ((st = read_position(p, "position", f[1], &l->pos)) || (st = read_direction(p, "direction", f[2],
            &l->dir)) ||
            (st = read_cone(p, f[3], &l->half_angle_deg)))
            return st;
        return read_power(p, kind, f[4], &l->power);
    case LUMO_LIGHT_DIRECTIONAL:
        return (st = read_direction(p, "direction", f[1], &l->dir)) ? st : read_power(p, kind, f[2], &l->power);
    default:
        if ((st = read_position(p, "corner", f[1], &l->pos)) || (st = read_position(p, "edge U", f[2], &l->u)) ||
            (st = read_position(p, "edge V", f[3], &l->v)))
            return st;
        if (!area_ok(l->u, l->v))
            return refuse(p, "edges U %s and V %s are parallel or zero: no area", f[2], f[3]);
        return read_power(p, kind, f[4], &l->power);
    }
}

lumo_status srv_light_parse_as(const char *opt, const char *text, srv_light *out, char *err, size_t errlen)
{
    lp p = {opt, text, err, errlen};
    char buf[LIGHT_MAX_TEXT + 1], *f[LIGHT_MAX_FIELDS];
    srv_light l;
    const kind_syntax *k = NULL;
    int n;
    if (strlen(text) > LIGHT_MAX_TEXT)
        return refuse(&p, "longer than %d characters", LIGHT_MAX_TEXT), LUMO_ERR_LIMIT;
    memcpy(buf, text, strlen(text) + 1);
    n = split_fields(buf, f, LIGHT_MAX_FIELDS);
    for (size_t i = 0; i < sizeof k_kinds / sizeof k_kinds[0]; i++)
        if (!strcmp(f[0], k_kinds[i].name))
            k = &k_kinds[i];
    if (!k)
        return refuse(&p, "kind '%.20s' is not point, spot, directional or area", f[0]);
    if (n != k->fields)
        return refuse(&p, "a %s light is %s (%d fields), got %s%d", k->name, k->syntax, k->fields,
                      n > LIGHT_MAX_FIELDS ? "more than " : "", n > LIGHT_MAX_FIELDS ? LIGHT_MAX_FIELDS : n);
    memset(&l, 0, sizeof l);
    l.kind = k->kind;
    lumo_status st = read_kind(&p, k->kind, f, &l);
    if (st)
        return st;
    l.dir = v3_norm(l.kind == LUMO_LIGHT_AREA ? v3_cross(l.u, l.v) : l.dir);
    l.cos_half = cosf(l.half_angle_deg * (float)M_PI / 180.0f);
    *out = l;
    return LUMO_OK;
}

lumo_status srv_light_parse(const char *text, srv_light *out, char *err, size_t errlen)
{
    return srv_light_parse_as("light", text, out, err, errlen);
}
