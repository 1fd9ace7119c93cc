/* model_check.c — lumo's checks of a model file around assimp (model_check.h):
 * the file itself, OBJ and OFF line by line, PLY header and body. */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include "scene/model_check.h"
#include "scene/model_check_internal.h"

typedef srv_mc mc;

lumo_status srv_mc_fail(mc *c, lumo_status st, const char *fmt, ...)
{
    char why[200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    snprintf(c->err, c->errlen, "%s: %s", c->name, why);
    return st;
}

/* ---- the format ------------------------------------------------------------- */

static int has_ext(const char *name, const char *ext)
{
    size_t n = strlen(name), e = strlen(ext);
    return n > e && name[n - e - 1] == '.' && !strcasecmp(name + n - e, ext);
}

srv_model_format srv_model_format_of(const char *name, const uint8_t *data, size_t size)
{
    if (name && has_ext(name, "obj"))
        return SRV_MODEL_OBJ;
    if (name && has_ext(name, "ply"))
        return SRV_MODEL_PLY;
    if (name && has_ext(name, "off"))
        return SRV_MODEL_OFF;
    if (name && has_ext(name, "stl"))
        return SRV_MODEL_STL;
    if (name && has_ext(name, "gltf"))
        return SRV_MODEL_GLTF;
    if (name && has_ext(name, "glb"))
        return SRV_MODEL_GLB;
    if (size >= 4 && !memcmp(data, "glTF", 4))
        return SRV_MODEL_GLB;
    if (size >= 4 && !memcmp(data, "ply", 3) && (data[3] == '\n' || data[3] == '\r'))
        return SRV_MODEL_PLY;
    if (size >= 3 && memmem(data, size < 8 ? size : 8, "OFF", 3))
        return SRV_MODEL_OFF;
    return SRV_MODEL_OTHER;
}

/* ---- text: lines and tokens ------------------------------------------------- */

/* Text has no NUL and no control byte but tab, CR, LF, FF, VT (a PNG or
 * a binary file named .obj stops here, not in assimp). */
lumo_status srv_mc_check_text(mc *c, const uint8_t *p, const uint8_t *end)
{
    for (const uint8_t *q = p; q < end; q++)
        if (*q < 0x20 && !(*q >= '\t' && *q <= '\r'))
            return srv_mc_fail(c, LUMO_ERR_CORRUPT, "byte %zu is 0x%02x: not a text file", (size_t)(q - c->base), *q);
    return LUMO_OK;
}

typedef struct span {
    const char *s, *e;
} span;

/* The next line (without its end of line) into *l; 0 at the end. */
static int next_line(mc *c, span *l)
{
    const uint8_t *nl;
    if (c->p >= c->end)
        return 0;
    nl = memchr(c->p, '\n', (size_t)(c->end - c->p));
    l->s = (const char *)c->p;
    l->e = (const char *)(nl ? nl : c->end);
    c->p = nl ? nl + 1 : c->end;
    c->line++;
    return 1;
}

/* The next whitespace-separated token of line *l into *t; 0 when none. */
static int next_tok(span *l, span *t)
{
    while (l->s < l->e && isspace((unsigned char)*l->s))
        l->s++;
    if (l->s >= l->e)
        return 0;
    t->s = l->s;
    while (l->s < l->e && !isspace((unsigned char)*l->s))
        l->s++;
    t->e = l->s;
    return 1;
}

static int tok_is(span t, const char *word)
{
    size_t n = strlen(word);
    return (size_t)(t.e - t.s) == n && !memcmp(t.s, word, n);
}

/* The token as a C string in buf (strtod and strtoll need the NUL the
 * mapped file lacks): 0, or -1 when it is empty or longer than cap - 1. */
static int tok_cstr(span t, char *buf, size_t cap)
{
    size_t n = (size_t)(t.e - t.s);
    if (n == 0 || n >= cap)
        return -1;
    memcpy(buf, t.s, n);
    buf[n] = 0;
    return 0;
}

/* A whole token as a number: 0 on success. */
static int tok_double(span t, double *out)
{
    char buf[64], *end;
    if (tok_cstr(t, buf, sizeof buf))
        return -1;
    *out = strtod(buf, &end);
    return *end ? -1 : 0;
}

static int tok_int(span t, long long *out)
{
    char buf[32], *end;
    if (tok_cstr(t, buf, sizeof buf))
        return -1;
    errno = 0;
    *out = strtoll(buf, &end, 10);
    return *end || errno ? -1 : 0;
}

/* A text line with nothing to read: blank or a comment. */
static int blank(span l)
{
    span t;
    return !next_tok(&l, &t) || *t.s == '#';
}

/* ---- a coordinate ----------------------------------------------------------- */

lumo_status srv_mc_coord_status(double v)
{
    return isfinite(v) ? LUMO_ERR_RANGE : LUMO_ERR_NONFINITE;
}

const char *srv_mc_coord_problem(double v)
{
    if (!isfinite(v))
        return "is not finite";
    if (fabs(v) > SRV_MODEL_MAX_COORD)
        return "is beyond the 1e6 m coordinate bound";
    return NULL;
}

/* Three coordinate tokens of vertex v (1-based in OBJ's counting when obj). */
static lumo_status text_vertex(mc *c, span *l, unsigned long long v)
{
    static const char axis[3] = {'x', 'y', 'z'};
    for (int k = 0; k < 3; k++) {
        span t;
        double d;
        const char *why;
        if (!next_tok(l, &t) || tok_double(t, &d))
            return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: vertex %llu: %c is missing or not a number", c->line,
                        v, axis[k]);
        if ((why = srv_mc_coord_problem(d)))
            return srv_mc_fail(c, srv_mc_coord_status(d), "line %u: vertex %llu: %c = %.9g %s", c->line, v, axis[k],
                               d, why);
    }
    return LUMO_OK;
}

/* ---- OFF -------------------------------------------------------------------- */

/* assimp's OFF reader takes polygons of at most 9 vertices and drops
 * larger ones without a word; lumo refuses them instead. */
#define OFF_MAX_FACE_VERTS 9

/* The next token that is not on a blank or comment line. */
static int off_tok(mc *c, span *l, span *t)
{
    while (!next_tok(l, t) || *t->s == '#') {
        if (!next_line(c, l))
            return 0;
    }
    return 1;
}

/* "[ST][C][N]OFF": the kinds assimp reads as three-dimensional text. */
static lumo_status off_magic(mc *c, span t, span *l)
{
    const char *s = t.s;
    span b, rest = *l;
    if (t.e - s >= 2 && !memcmp(s, "ST", 2))
        s += 2;
    if (s < t.e && *s == 'C')
        s++;
    if (s < t.e && *s == 'N')
        s++;
    if (s < t.e && (*s == '4' || *s == 'n'))
        return srv_mc_fail(c, LUMO_ERR_UNSUPPORTED, "line %u: '%.*s': homogeneous or n-dimensional OFF is not read",
                    c->line, (int)(t.e - t.s), t.s);
    if (t.e - s != 3 || memcmp(s, "OFF", 3))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: no OFF header", c->line);
    if (next_tok(&rest, &b) && tok_is(b, "BINARY"))
        return srv_mc_fail(c, LUMO_ERR_UNSUPPORTED, "line %u: binary OFF is not read", c->line);
    return LUMO_OK;
}

static lumo_status off_counts(mc *c, span *l, unsigned long long n[3])
{
    static const char *what[3] = {"vertex count", "face count", "edge count"};
    for (int k = 0; k < 3; k++) {
        span t;
        long long v;
        if (!off_tok(c, l, &t) || tok_int(t, &v) || v < 0 || v > UINT32_MAX)
            return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: the header's %s is missing or not a count in [0, 2^32)",
                        c->line, what[k]);
        n[k] = (unsigned long long)v;
    }
    if (n[0] == 0 || n[1] == 0)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT,
                           "line %u: the header declares %llu vertices and %llu faces: nothing to draw",
                    c->line, n[0], n[1]);
    return LUMO_OK;
}

/* Each vertex takes at least "0 0 0\n", each face "3 0 1 2\n" minus one
 * digit per index: declared counts beyond that are refused before any
 * reader allocates for them. */
static lumo_status off_fits(mc *c, const unsigned long long n[3])
{
    unsigned long long need = 6 * n[0] + 8 * n[1], have = (unsigned long long)(c->end - c->p) + 1;
    if (need > have)
        return srv_mc_fail(c, LUMO_ERR_TRUNCATED,
                           "the header declares %llu vertices and %llu faces: at least %llu bytes, "
                    "the file holds %llu after it", n[0], n[1], need, have - 1);
    return LUMO_OK;
}

static lumo_status off_face(mc *c, span *l, unsigned long long f, unsigned long long nv)
{
    span t;
    long long n, idx;
    if (!next_tok(l, &t) || tok_int(t, &n))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: face %llu: no vertex count", c->line, f);
    if (n < 3 || n > OFF_MAX_FACE_VERTS)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: face %llu has %lld vertices (3 to %d are read)", c->line,
                           f, n,
                    OFF_MAX_FACE_VERTS);
    for (long long k = 0; k < n; k++) {
        if (!next_tok(l, &t) || tok_int(t, &idx))
            return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: face %llu: index %lld is missing or not an integer",
                               c->line,
                        f, k);
        if (idx < 0 || (unsigned long long)idx >= nv)
            return srv_mc_fail(c, LUMO_ERR_RANGE, "line %u: face %llu: vertex index %lld is outside [0, %llu)",
                               c->line, f,
                        idx, nv);
    }
    return LUMO_OK;
}

/* nv vertex lines then nf face lines, skipping blank and comment lines. */
static lumo_status off_body(mc *c, const unsigned long long n[3])
{
    span l;
    lumo_status st = LUMO_OK;
    unsigned long long v = 0, f = 0;
    while (!st && v + f < n[0] + n[1] && next_line(c, &l)) {
        if (blank(l))
            continue;
        st = v < n[0] ? text_vertex(c, &l, v++) : off_face(c, &l, f++, n[0]);
    }
    if (!st && v + f < n[0] + n[1])
        return srv_mc_fail(c, LUMO_ERR_TRUNCATED, "the file ends after %llu of %llu vertices and %llu of %llu faces", v,
                    n[0], f, n[1]);
    return st;
}

static lumo_status check_off(mc *c)
{
    span l = {NULL, NULL}, t;
    unsigned long long n[3];
    lumo_status st = srv_mc_check_text(c, c->p, c->end);
    if (st)
        return st;
    if (!off_tok(c, &l, &t))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "no OFF header");
    if ((st = off_magic(c, t, &l)) || (st = off_counts(c, &l, n)) || (st = off_fits(c, n)))
        return st;
    return off_body(c, n);
}

/* ---- OBJ -------------------------------------------------------------------- */

typedef struct obj_counts {
    unsigned long long v, vt, vn;
} obj_counts;

/* One index of a corner: 1..n, or -1..-n counting back; empty allowed
 * where OBJ allows it (texture and normal slots). */
static lumo_status obj_index(mc *c, const char *s, const char *e, unsigned long long n, const char *kind,
                             int required)
{
    span t = {s, e};
    long long i;
    if (s == e && !required)
        return LUMO_OK;
    if (tok_int(t, &i))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: '%.*s' is not a %s index", c->line, (int)(e - s), s, kind);
    if (i == 0 || (i > 0 && (unsigned long long)i > n) || (i < 0 && (unsigned long long)-i > n))
        return srv_mc_fail(c, LUMO_ERR_RANGE, "line %u: %s index %lld: only %llu %ss so far", c->line, kind, i, n,
                           kind);
    return LUMO_OK;
}

/* "v", "v/t", "v//n", "v/t/n". */
static lumo_status obj_corner(mc *c, span t, const obj_counts *n)
{
    static const char *kind[3] = {"vertex", "texture coordinate", "normal"};
    const unsigned long long cnt[3] = {n->v, n->vt, n->vn};
    const char *s = t.s;
    for (int k = 0; k < 3 && s <= t.e; k++) {
        const char *e = memchr(s, '/', (size_t)(t.e - s));
        lumo_status st = obj_index(c, s, e ? e : t.e, cnt[k], kind[k], k == 0);
        if (st)
            return st;
        if (!e)
            return LUMO_OK;
        s = e + 1;
    }
    return s <= t.e ? srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: '%.*s' has more than three slots", c->line,
                           (int)(t.e - t.s), t.s)
                    : LUMO_OK;
}

/* f, l, p: min..SRV_MODEL_MAX_FACE_VERTS corners, each naming what exists. */
static lumo_status obj_element(mc *c, span *l, const obj_counts *n, unsigned min)
{
    span t;
    unsigned k = 0;
    while (next_tok(l, &t)) {
        lumo_status st;
        if (*t.s == '#')
            break;
        if (++k > SRV_MODEL_MAX_FACE_VERTS)
            return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: more than %u corners", c->line, SRV_MODEL_MAX_FACE_VERTS);
        if ((st = obj_corner(c, t, n)))
            return st;
    }
    if (k < min)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: %u corner(s), a face needs 3", c->line, k);
    return LUMO_OK;
}

static lumo_status obj_line(mc *c, span l, obj_counts *n)
{
    span t;
    if (!next_tok(&l, &t))
        return LUMO_OK;
    if (tok_is(t, "v"))
        return text_vertex(c, &l, ++n->v);
    if (tok_is(t, "vt"))
        return n->vt++, LUMO_OK;
    if (tok_is(t, "vn"))
        return n->vn++, LUMO_OK;
    if (tok_is(t, "f"))
        return obj_element(c, &l, n, 3);
    if (tok_is(t, "l") || tok_is(t, "p"))
        return obj_element(c, &l, n, 1);
    return LUMO_OK;   /* groups, materials, comments: assimp's business */
}

static lumo_status check_obj(mc *c)
{
    span l;
    obj_counts n = {0, 0, 0};
    lumo_status st = srv_mc_check_text(c, c->p, c->end);
    while (!st && next_line(c, &l))
        st = obj_line(c, l, &n);
    if (!st && n.v == 0)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "no vertex ('v' line)");
    return st;
}

/* ---- PLY -------------------------------------------------------------------- */

#define PLY_MAX_ELEMENTS 16
#define PLY_MAX_PROPS    32

typedef enum { PLY_ASCII, PLY_LE, PLY_BE } ply_format;

typedef struct ply_type {
    const char *name, *alias;
    unsigned    size;
    int         is_float, is_signed;
} ply_type;

static const ply_type k_types[] = {
    {"char", "int8", 1, 0, 1},   {"uchar", "uint8", 1, 0, 0},   {"short", "int16", 2, 0, 1},
    {"ushort", "uint16", 2, 0, 0}, {"int", "int32", 4, 0, 1},   {"uint", "uint32", 4, 0, 0},
    {"float", "float32", 4, 1, 1}, {"double", "float64", 8, 1, 1},
};

typedef struct ply_prop {
    const ply_type *type, *count;   /* count: list length type, NULL for a scalar */
    int             role;           /* PROP_* */
} ply_prop;

enum { PROP_OTHER, PROP_X, PROP_Y, PROP_Z, PROP_INDICES };

typedef struct ply_elem {
    char               name[32];
    unsigned long long count;
    ply_prop           prop[PLY_MAX_PROPS];
    unsigned           nprops;
} ply_elem;

typedef struct ply {
    ply_format         format;
    ply_elem           elem[PLY_MAX_ELEMENTS];
    unsigned           nelems;
    unsigned long long nverts;   /* the "vertex" element's count */
} ply;

static const ply_type *ply_type_of(span t)
{
    for (size_t i = 0; i < sizeof k_types / sizeof k_types[0]; i++)
        if (tok_is(t, k_types[i].name) || tok_is(t, k_types[i].alias))
            return &k_types[i];
    return NULL;
}

static lumo_status ply_format_line(mc *c, ply *y, span *l)
{
    span t;
    if (!next_tok(l, &t))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: format without a value", c->line);
    if (tok_is(t, "ascii"))
        y->format = PLY_ASCII;
    else if (tok_is(t, "binary_little_endian"))
        y->format = PLY_LE;
    else if (tok_is(t, "binary_big_endian"))
        y->format = PLY_BE;
    else
        return srv_mc_fail(c, LUMO_ERR_UNSUPPORTED, "line %u: unknown format '%.*s'", c->line, (int)(t.e - t.s), t.s);
    return LUMO_OK;
}

static lumo_status ply_element_line(mc *c, ply *y, span *l)
{
    span name, cnt;
    long long n;
    ply_elem *e;
    if (y->nelems == PLY_MAX_ELEMENTS)
        return srv_mc_fail(c, LUMO_ERR_LIMIT, "line %u: more than %d elements", c->line, PLY_MAX_ELEMENTS);
    if (!next_tok(l, &name) || !next_tok(l, &cnt) || tok_int(cnt, &n) || n < 0 || n > UINT32_MAX)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: an element needs a name and a count in [0, 2^32)", c->line);
    e = &y->elem[y->nelems++];
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%.*s", (int)(name.e - name.s), name.s);
    e->count = (unsigned long long)n;
    if (!strcmp(e->name, "vertex"))
        y->nverts = e->count;
    return LUMO_OK;
}

static int prop_role(const ply_elem *e, span name)
{
    if (!strcmp(e->name, "vertex"))
        return tok_is(name, "x") ? PROP_X : tok_is(name, "y") ? PROP_Y : tok_is(name, "z") ? PROP_Z : PROP_OTHER;
    if (!strcmp(e->name, "face") && (tok_is(name, "vertex_indices") || tok_is(name, "vertex_index")))
        return PROP_INDICES;
    return PROP_OTHER;
}

static lumo_status ply_property_line(mc *c, ply *y, span *l)
{
    span t, name;
    ply_elem *e = y->nelems ? &y->elem[y->nelems - 1] : NULL;
    ply_prop p = {NULL, NULL, PROP_OTHER};
    if (!e)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: a property before any element", c->line);
    if (e->nprops == PLY_MAX_PROPS)
        return srv_mc_fail(c, LUMO_ERR_LIMIT, "line %u: element '%s' has more than %d properties", c->line, e->name,
                    PLY_MAX_PROPS);
    if (next_tok(l, &t) && tok_is(t, "list")) {
        if (!next_tok(l, &t) || !(p.count = ply_type_of(t)) || p.count->is_float)
            return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: a list needs an integer count type", c->line);
        next_tok(l, &t);
    }
    if (!(p.type = ply_type_of(t)) || !next_tok(l, &name))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: a property needs a known type and a name", c->line);
    p.role = prop_role(e, name);
    if (p.role == PROP_INDICES && (!p.count || p.type->is_float))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: face indices must be a list of integers", c->line);
    e->prop[e->nprops++] = p;
    return LUMO_OK;
}

static lumo_status ply_header_line(mc *c, ply *y, span l, int *done)
{
    span t;
    if (!next_tok(&l, &t) || tok_is(t, "comment") || tok_is(t, "obj_info"))
        return LUMO_OK;
    if (tok_is(t, "format"))
        return ply_format_line(c, y, &l);
    if (tok_is(t, "element"))
        return ply_element_line(c, y, &l);
    if (tok_is(t, "property"))
        return ply_property_line(c, y, &l);
    if (tok_is(t, "end_header"))
        return *done = 1, LUMO_OK;
    return srv_mc_fail(c, LUMO_ERR_CORRUPT, "line %u: unknown header line '%.*s'", c->line, (int)(t.e - t.s), t.s);
}

static lumo_status ply_header(mc *c, ply *y)
{
    span l, t;
    int done = 0, have_format = 0;
    lumo_status st = LUMO_OK;
    memset(y, 0, sizeof *y);
    if (!next_line(c, &l) || !next_tok(&l, &t) || !tok_is(t, "ply"))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "no 'ply' magic on line 1");
    while (!st && !done && next_line(c, &l)) {
        const char *s = l.s;
        if ((st = srv_mc_check_text(c, (const uint8_t *)l.s, (const uint8_t *)l.e)))
            return st;
        have_format |= next_tok(&l, &t) && tok_is(t, "format");
        l.s = s;
        st = ply_header_line(c, y, l, &done);
    }
    if (!st && !done)
        return srv_mc_fail(c, LUMO_ERR_TRUNCATED, "the header has no end_header");
    if (!st && !have_format)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "the header has no format line");
    if (!st && y->nverts == 0)
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "the header declares no vertex");
    return st;
}

/* The fewest bytes one item of e takes: binary, its scalars and list
 * counts; ASCII, two characters per number. */
static unsigned long long ply_min_bytes(const ply *y, const ply_elem *e)
{
    unsigned long long b = 0;
    for (unsigned i = 0; i < e->nprops; i++)
        b += y->format == PLY_ASCII ? 2 : e->prop[i].count ? e->prop[i].count->size : e->prop[i].type->size;
    return b;
}

static lumo_status ply_fits(mc *c, const ply *y)
{
    unsigned long long have = (unsigned long long)(c->end - c->p) + (y->format == PLY_ASCII);
    unsigned long long need = 0;
    for (unsigned i = 0; i < y->nelems; i++) {
        need += y->elem[i].count * ply_min_bytes(y, &y->elem[i]);
        if (need > have)
            return srv_mc_fail(c, LUMO_ERR_TRUNCATED, "element '%s' declares %llu items: with those before it at least "
                        "%llu bytes, the file holds %llu after its header", y->elem[i].name, y->elem[i].count,
                        need, have);
    }
    return LUMO_OK;
}

/* One number of the body, whatever the encoding: LUMO_OK, TRUNCATED (the
 * data ends) or CORRUPT (ASCII: not a number; *bad gets the token). The
 * caller says which item it was. */
static lumo_status ply_read(mc *c, const ply *y, const ply_type *t, double *out, span *bad)
{
    uint8_t b[8];
    uint64_t u = 0;
    span l = {(const char *)c->p, (const char *)c->end};
    if (y->format == PLY_ASCII) {
        if (!next_tok(&l, bad))
            return LUMO_ERR_TRUNCATED;
        c->p = (const uint8_t *)bad->e;
        return tok_double(*bad, out) ? LUMO_ERR_CORRUPT : LUMO_OK;
    }
    if ((size_t)(c->end - c->p) < t->size)
        return LUMO_ERR_TRUNCATED;
    for (unsigned i = 0; i < t->size; i++)
        b[i] = c->p[y->format == PLY_LE ? i : t->size - 1 - i];
    c->p += t->size;
    for (unsigned i = t->size; i-- > 0;)
        u = u << 8 | b[i];
    if (t->is_float && t->size == 4) {
        float f;
        uint32_t w = (uint32_t)u;
        memcpy(&f, &w, 4);
        *out = f;
    } else if (t->is_float) {
        memcpy(out, &u, 8);
    } else if (t->is_signed) {
        int shift = 64 - 8 * (int)t->size;
        *out = (double)((int64_t)(u << shift) >> shift);
    } else {
        *out = (double)u;
    }
    return LUMO_OK;
}

/* Why ply_read refused, for item `item` of element e ("where" inside it). */
static lumo_status ply_unread(mc *c, lumo_status st, const ply_elem *e, unsigned long long item, const char *where,
                              span bad)
{
    if (st == LUMO_ERR_CORRUPT)
        return srv_mc_fail(c, st, "%s %llu: '%.*s' is not a number", e->name, item, (int)(bad.e - bad.s > 40 ? 40 :
                    bad.e - bad.s), bad.s);
    return srv_mc_fail(c, st, "%s %llu: the data ends %s", e->name, item, where);
}

static lumo_status ply_list(mc *c, const ply *y, const ply_elem *e, const ply_prop *p, unsigned long long item)
{
    double n, v;
    span bad = {NULL, NULL};
    lumo_status st = ply_read(c, y, p->count, &n, &bad);
    char where[64];
    if (st)
        return ply_unread(c, st, e, item, "before its list", bad);
    if (n != floor(n) || n < 0 || n > SRV_MODEL_MAX_FACE_VERTS || (p->role == PROP_INDICES && n < 3))
        return srv_mc_fail(c, LUMO_ERR_CORRUPT, "%s %llu: a list of %.0f items (%s)", e->name, item, n,
                    p->role == PROP_INDICES ? "a face has 3 to 1024 vertices" : "at most 1024");
    snprintf(where, sizeof where, "inside its list of %.0f items", n);
    for (unsigned k = 0; k < (unsigned)n; k++) {
        if ((st = ply_read(c, y, p->type, &v, &bad)))
            return ply_unread(c, st, e, item, where, bad);
        if (p->role == PROP_INDICES && (v < 0 || v >= (double)y->nverts || v != floor(v)))
            return srv_mc_fail(c, LUMO_ERR_RANGE, "face %llu: vertex index %.12g is outside [0, %llu)", item, v,
                               y->nverts);
    }
    return LUMO_OK;
}

static lumo_status ply_scalar(mc *c, const ply *y, const ply_elem *e, const ply_prop *p, unsigned long long item)
{
    double v;
    const char *why;
    span bad = {NULL, NULL};
    lumo_status st = ply_read(c, y, p->type, &v, &bad);
    if (st)
        return ply_unread(c, st, e, item, "inside it", bad);
    if (p->role >= PROP_X && p->role <= PROP_Z && (why = srv_mc_coord_problem(v)))
        return srv_mc_fail(c, srv_mc_coord_status(v), "vertex %llu: %c = %.9g %s", item, "xyz"[p->role - PROP_X], v,
                           why);
    return LUMO_OK;
}

static lumo_status ply_body(mc *c, const ply *y)
{
    for (unsigned i = 0; i < y->nelems; i++) {
        const ply_elem *e = &y->elem[i];
        for (unsigned long long item = 0; item < e->count; item++)
            for (unsigned k = 0; k < e->nprops; k++) {
                const ply_prop *p = &e->prop[k];
                lumo_status st = p->count ? ply_list(c, y, e, p, item) : ply_scalar(c, y, e, p, item);
                if (st)
                    return st;
            }
    }
    return LUMO_OK;
}

static lumo_status check_ply(mc *c)
{
    ply y;   /* 13 KB */
    lumo_status st = ply_header(c, &y);
    if (!st && y.format == PLY_ASCII)
        st = srv_mc_check_text(c, c->p, c->end);
    if (!st)
        st = ply_fits(c, &y);
    return st ? st : ply_body(c, &y);
}

/* ---- the entry points ------------------------------------------------------- */

/* Formats lumo does not check itself: assimp would read many of them
 * (Collada, 3DS, FBX, X, Blender, ...), trusting the counts they declare. */
static lumo_status refuse_format(mc *c)
{
    const char *dot = strrchr(c->name, '.');
    if (!dot || strchr(dot, '/'))
        dot = "";
    return srv_mc_fail(c, LUMO_ERR_UNSUPPORTED, "unknown model format (extension '%.16s'): lumo reads "
                       SRV_MODEL_FORMATS, dot);
}

lumo_status srv_model_check_bytes(const char *name, const uint8_t *data, size_t size, srv_model_format fmt,
                                  char *err, size_t errlen)
{
    mc c = {name, data, data, data + size, 0, err, errlen};
    if (size == 0)
        return srv_mc_fail(&c, LUMO_ERR_CORRUPT, "empty file");
    switch (fmt) {
    case SRV_MODEL_OBJ: return check_obj(&c);
    case SRV_MODEL_PLY: return check_ply(&c);
    case SRV_MODEL_OFF: return check_off(&c);
    case SRV_MODEL_STL: return srv_mc_check_stl(&c);
    case SRV_MODEL_GLTF: return srv_mc_check_gltf(&c, 0);
    case SRV_MODEL_GLB: return srv_mc_check_gltf(&c, 1);
    default: return refuse_format(&c);
    }
}

static lumo_status read_all(mc *c, FILE *f, uint8_t *buf, size_t size)
{
    return fread(buf, 1, size, f) == size ? LUMO_OK : srv_mc_fail(c, LUMO_ERR_IO, "cannot read it");
}

/* One name of an "mtllib" line: a regular file or nothing. */
static lumo_status mtllib_name(mc *c, const char *dir, span t)
{
    char lib[1280];
    struct stat st;
    int n = (int)(t.e - t.s);
    while (n > 0 && isspace((unsigned char)t.s[n - 1]))
        n--;
    if (*t.s == '/')
        snprintf(lib, sizeof lib, "%.*s", n, t.s);
    else
        snprintf(lib, sizeof lib, "%s/%.*s", dir, n, t.s);
    if (n > 0 && stat(lib, &st) == 0 && !S_ISREG(st.st_mode))
        return srv_mc_fail(c, LUMO_ERR_IO, "line %u: mtllib '%.*s' is not a regular file", c->line, n, t.s);
    return LUMO_OK;
}

/* The files an OBJ's "mtllib" lines name, which assimp opens and reads to
 * their end: each must be a regular file when it exists (a FIFO there
 * blocked the importer forever; missing ones assimp skips with a
 * warning). A name is a word, or the rest of the line as assimp takes it. */
static lumo_status obj_mtllibs(mc *c, const char *path)
{
    char dir[1024];
    const char *slash = strrchr(path, '/');
    span l, t, rest;
    lumo_status st = LUMO_OK;
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    while (!st && next_line(c, &l)) {
        if (!next_tok(&l, &t) || !tok_is(t, "mtllib"))
            continue;
        rest = l;
        while (rest.s < rest.e && isspace((unsigned char)*rest.s))
            rest.s++;
        if (rest.s < rest.e)
            st = mtllib_name(c, dir, rest);
        while (!st && next_tok(&l, &t))
            st = mtllib_name(c, dir, t);
    }
    return st;
}

/* The file, opened without blocking (a FIFO waits for no writer) and
 * checked on its descriptor, so the file checked is the file read. */
static lumo_status open_model(mc *c, const char *path, FILE **f, size_t *size)
{
    struct stat st;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    lumo_status rc = LUMO_OK;
    if (fd < 0 || fstat(fd, &st))
        rc = srv_mc_fail(c, LUMO_ERR_IO, errno == ENOENT ? "no such file" : "cannot open it");
    else if (!S_ISREG(st.st_mode))
        rc = srv_mc_fail(c, LUMO_ERR_IO, S_ISDIR(st.st_mode) ? "a directory, not a model file" : "not a regular file");
    else if (st.st_size == 0)
        rc = srv_mc_fail(c, LUMO_ERR_CORRUPT, "empty file");
    else if ((uint64_t)st.st_size > SRV_MODEL_MAX_BYTES)
        rc = srv_mc_fail(c, LUMO_ERR_LIMIT, "%lld bytes, models of at most 1 GiB are read", (long long)st.st_size);
    else if (fcntl(fd, F_SETFL, 0) || !(*f = fdopen(fd, "rb")))
        rc = srv_mc_fail(c, LUMO_ERR_IO, "cannot open it");
    if (rc && fd >= 0)
        close(fd);
    *size = rc ? 0 : (size_t)st.st_size;
    return rc;
}

lumo_status srv_model_check_file(const char *path, srv_model_format *fmt, char *err, size_t errlen)
{
    mc c = {path, NULL, NULL, NULL, 0, err, errlen};
    FILE *f = NULL;
    size_t size;
    uint8_t *buf;
    lumo_status rc = open_model(&c, path, &f, &size);
    if (rc)
        return rc;
    if (!(buf = malloc(size))) {
        fclose(f);
        return srv_mc_fail(&c, LUMO_ERR_NOMEM, "no memory to check %zu bytes", size);
    }
    rc = read_all(&c, f, buf, size);
    fclose(f);
    *fmt = srv_model_format_of(path, buf, size);
    if (!rc)
        rc = srv_model_check_bytes(path, buf, size, *fmt, err, errlen);
    if (!rc && *fmt == SRV_MODEL_OBJ) {
        mc o = {path, buf, buf, buf + size, 0, err, errlen};
        rc = obj_mtllibs(&o, path);
    }
    free(buf);
    return rc;
}

lumo_status srv_model_check_positions(const char *name, unsigned mesh, const float *xyz, uint32_t nverts,
                                      char *err, size_t errlen)
{
    mc c = {name, NULL, NULL, NULL, 0, err, errlen};
    for (uint32_t v = 0; v < nverts; v++)
        for (int k = 0; k < 3; k++) {
            const char *why = srv_mc_coord_problem(xyz[3 * (size_t)v + k]);
            if (why)
                return srv_mc_fail(&c, srv_mc_coord_status(xyz[3 * (size_t)v + k]),
                            "mesh %u, vertex %u: %c = %.9g %s", mesh, v, "xyz"[k], xyz[3 * (size_t)v + k], why);
        }
    return LUMO_OK;
}
