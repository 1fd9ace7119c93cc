/*
 * lumo-draco-decode — decode a Draco file with lumo's client decoder.
 *
 *   lumo-draco-decode IN.drc OUT.ply   ASCII PLY, libdraco's point/face order,
 *                                      values dequantized from fixed point
 *   lumo-draco-decode --info IN.drc    modes per attribute, memory use
 *   lumo-draco-decode --dump IN.drc OUT.txt   portable integers + faces, the
 *                                      format of tests/draco/draco_oracle.cc
 *   lumo-draco-decode --bench N IN.drc decode N times (benchmarks)
 *
 * A first argument --lean decodes with LUMO_DRACO_LEAN (same output, a
 * smaller arena, more instructions).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "lumo/draco.h"
#include "lumo_host/file_io.h"
#include "lumo_host/options.h"

static unsigned g_flags;  /* --lean */

/* Decode into an arena of exactly lumo_draco_arena_need() bytes, computed
 * before decoding: the figure is part of the API, so a decode that does
 * not fit in it, or (when the figure is exact) needs fewer bytes or still
 * fits one byte below, is reported as a failure. `check`: also decode in
 * one byte less (not in --bench, whose instruction counts are per decode). */
static lumo_status decode(const uint8_t *data, size_t size, lumo_draco_mesh *m, void **mem,
                          lumo_draco_need *need, int check)
{
    lumo_arena a;
    lumo_status st = lumo_draco_arena_need_ex(data, size, g_flags, need);
    size_t used;
    if (st)
        return st;
    if (!(*mem = malloc(need->bytes ? need->bytes : 1)))
        return LUMO_ERR_NOMEM;
    if (check && need->exact && need->bytes) {  /* first: it overwrites the buffer */
        lumo_arena_init(&a, *mem, need->bytes - 1u);
        if (lumo_draco_decode_ex(data, size, g_flags, &a, m) != LUMO_ERR_NOMEM) {
            fprintf(stderr, "lumo-draco-decode: decode fits in %zu bytes, 1 below the exact need\n",
                    need->bytes - 1u);
            return LUMO_ERR_STATE;
        }
    }
    lumo_arena_init(&a, *mem, need->bytes);  /* malloc'd: aligned, no slack */
    st = lumo_draco_decode_ex(data, size, g_flags, &a, m);
    if (st == LUMO_ERR_NOMEM)
        fprintf(stderr, "lumo-draco-decode: decode needs more than lumo_draco_arena_need() = %zu bytes\n",
                need->bytes);
    if (st || !check)
        return st;
    used = m->arena_bytes + m->work_bytes;
    if (used > need->bytes || used < need->bytes_min || (need->exact && used != need->bytes)) {
        fprintf(stderr, "lumo-draco-decode: need %zu..%zu bytes (exact %u), decode used %zu\n",
                need->bytes_min, need->bytes, need->exact, used);
        return LUMO_ERR_STATE;
    }
    return LUMO_OK;
}

static void write_dump(FILE *f, const lumo_draco_mesh *m)
{
    uint32_t i, p;
    fprintf(f, "points %u\n", m->num_points);
    if (m->geometry == LUMO_DRACO_MESH) {
        fprintf(f, "faces %u\n", m->num_faces);
        for (i = 0; i < m->num_faces; ++i)
            fprintf(f, "%u %u %u\n", m->faces[3 * i], m->faces[3 * i + 1], m->faces[3 * i + 2]);
    }
    fprintf(f, "attributes %u\n", m->num_attributes);
    for (i = 0; i < m->num_attributes; ++i) {
        const lumo_draco_attribute *a = &m->attributes[i];
        unsigned c;
        fprintf(f, "attribute %u type %u components %u\n", i, a->type, a->num_portable);
        for (p = 0; p < m->num_points; ++p) {
            for (c = 0; c < a->num_portable; ++c)
                fprintf(f, c ? " %d" : "%d", lumo_draco_value(a, p, c));
            fputc('\n', f);
        }
    }
}

static const char *type_name(unsigned t)
{
    static const char *names[] = {"position", "normal", "color", "tex_coord", "generic"};
    return t < 5 ? names[t] : "?";
}

static void write_info(const lumo_draco_mesh *m, const lumo_draco_need *need, size_t in_size,
                       uint16_t flags)
{
    static const char *pred[] = {"delta", "parallelogram", "multi-parallelogram",
                                 "tex-coords(deprecated)", "constrained-multi-parallelogram",
                                 "tex-coords-portable", "geometric-normal"};
    static const char *seq[] = {"generic", "integer", "quantization", "normals"};
    uint32_t i;
    printf("geometry: %s\n", m->geometry ? "mesh" : "point cloud");
    if (m->geometry == LUMO_DRACO_MESH && m->method == 0)
        printf("connectivity: sequential (%s indices)\n", m->connectivity ? "raw" : "compressed");
    else if (m->geometry == LUMO_DRACO_MESH)
        printf("connectivity: edgebreaker %s\n", m->connectivity == 2 ? "valence" : "standard");
    else
        printf("encoding: %s\n", m->method ? "kd-tree" : "sequential");
    printf("points: %u  faces: %u  input: %zu bytes%s\n", m->num_points, m->num_faces, in_size,
           (flags & 0x8000u) ? "  (metadata present, skipped)" : "");
    printf("arena: %zu output bytes + %zu peak work bytes\n", m->arena_bytes, m->work_bytes);
    printf("arena need before decoding: %zu bytes (%s%zu)\n", need->bytes,
           need->exact ? "exact, " : "bound, at least ", need->exact ? need->bytes : need->bytes_min);
    for (i = 0; i < m->num_attributes; ++i) {
        const lumo_draco_attribute *a = &m->attributes[i];
        const lumo_draco_attr_modes *md = &a->modes;
        if (m->geometry == LUMO_DRACO_MESH && m->method == LUMO_DRACO_METHOD_EDGEBREAKER)
            printf("attribute %u: %s, %u components (%u portable), decoder %u, %s, %s traversal\n",
                   i, type_name(a->type), a->num_components, a->num_portable, md->decoder_id,
                   md->vertex_attribute ? "per vertex" : "per corner",
                   md->traversal ? "prediction-degree" : "depth-first");
        else
            printf("attribute %u: %s, %u components (%u portable), decoder %u, point order\n",
                   i, type_name(a->type), a->num_components, a->num_portable, md->decoder_id);
        printf("  sequential decoder: %s; prediction: %s; transform: %s\n",
               md->seq_type < 4 ? seq[md->seq_type] : "?",
               md->prediction >= 0 && md->prediction < 7 ? pred[md->prediction] : "none",
               md->transform == 1 ? "wrap" : md->transform == 3 ? "octahedron-canonicalized"
               : md->transform == 2 ? "octahedron" : "none");
        printf("  values: %s; %s bits %u\n",
               !md->compressed ? "raw bytes" : md->symbol_coding ? "raw rANS" : "tagged rANS",
               a->xform == LUMO_DRACO_XFORM_QUANTIZED ? "quantized"
               : a->xform == LUMO_DRACO_XFORM_OCTAHEDRAL ? "octahedral" : "integer",
               a->quant_bits);
    }
}

/* Octahedral (s, t) to a unit vector, libdraco's convention: s -> y,
 * t -> z, scaled by 2 / (2^bits - 2), the lower half folded (desktop
 * floats; the client keeps the integers). */
static void octa_to_vec(int32_t s, int32_t t, unsigned bits, double out[3])
{
    double scale = 2.0 / (double)((1 << bits) - 2);
    double y = s * scale - 1.0, z = t * scale - 1.0;
    double x = 1.0 - fabs(y) - fabs(z), off = x < 0 ? -x : 0, n2;
    y += y < 0 ? off : -off;
    z += z < 0 ? off : -off;
    n2 = x * x + y * y + z * z;
    if (n2 < 1e-6) {
        out[0] = out[1] = out[2] = 0;
        return;
    }
    n2 = sqrt(n2);
    out[0] = x / n2; out[1] = y / n2; out[2] = z / n2;
}

static double value_of(const lumo_draco_attribute *a, uint32_t p, unsigned c)
{
    int32_t q = lumo_draco_value(a, p, c);
    if (a->xform == LUMO_DRACO_XFORM_QUANTIZED)
        return ldexp((double)lumo_draco_dequantize(a, c, q), -(int)a->frac_bits);
    return (double)q;
}

static int write_ply(const char *path, const lumo_draco_mesh *m)
{
    static const char *axis[] = {"x", "y", "z"}, *naxis[] = {"nx", "ny", "nz"};
    static const char *rgba[] = {"red", "green", "blue", "alpha"}, *uv[] = {"u", "v"};
    FILE *f = fopen(path, "w");
    uint32_t i, p;
    if (!f)
        return 1;
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex %u\n", m->num_points);
    for (i = 0; i < m->num_attributes; ++i) {
        const lumo_draco_attribute *a = &m->attributes[i];
        unsigned c;
        for (c = 0; c < a->num_components; ++c) {
            if (a->type == LUMO_DRACO_POSITION && c < 3)
                fprintf(f, "property float %s\n", axis[c]);
            else if (a->type == LUMO_DRACO_NORMAL && c < 3)
                fprintf(f, "property float %s\n", naxis[c]);
            else if (a->type == LUMO_DRACO_COLOR && c < 4)
                fprintf(f, "property uchar %s\n", rgba[c]);
            else if (a->type == LUMO_DRACO_TEX_COORD && c < 2)
                fprintf(f, "property float %s\n", uv[c]);
            else
                fprintf(f, "property float a%u_%u\n", i, c);
        }
    }
    if (m->geometry == LUMO_DRACO_MESH)
        fprintf(f, "element face %u\nproperty list uchar int vertex_indices\n", m->num_faces);
    fprintf(f, "end_header\n");
    for (p = 0; p < m->num_points; ++p) {
        for (i = 0; i < m->num_attributes; ++i) {
            const lumo_draco_attribute *a = &m->attributes[i];
            unsigned c;
            if (a->xform == LUMO_DRACO_XFORM_OCTAHEDRAL) {
                double n[3];
                octa_to_vec(lumo_draco_value(a, p, 0), lumo_draco_value(a, p, 1), a->quant_bits, n);
                fprintf(f, "%.9g %.9g %.9g ", n[0], n[1], n[2]);
                continue;
            }
            for (c = 0; c < a->num_components; ++c)
                fprintf(f, a->xform == LUMO_DRACO_XFORM_QUANTIZED ? "%.9g " : "%.0f ",
                        value_of(a, p, c));
        }
        fputc('\n', f);
    }
    for (i = 0; i < m->num_faces; ++i)
        fprintf(f, "3 %u %u %u\n", m->faces[3 * i], m->faces[3 * i + 1], m->faces[3 * i + 2]);
    return fclose(f) ? 1 : 0;
}

int main(int argc, char **argv)
{
    const char *mode = "ply", *in, *out = NULL;
    int reps = 1;
    uint8_t *data;
    size_t size = 0;
    lumo_draco_mesh m;
    lumo_draco_need need;
    void *mem = NULL;
    lumo_status st;
    int i, rc = 0;
    if (argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        printf("usage: lumo-draco-decode [--lean] IN.drc OUT.ply | --info IN.drc | --dump IN.drc OUT.txt | "
               "--bench N IN.drc\n  --bench N   decode N times, 1..1000000\n");
        return 0;
    }
    if (argc > 1 && !strcmp(argv[1], "--lean")) {
        g_flags = LUMO_DRACO_LEAN;
        argv++;
        argc--;
    }
    if (argc == 3 && !strcmp(argv[1], "--info")) {
        mode = "info"; in = argv[2];
    } else if (argc == 4 && !strcmp(argv[1], "--dump")) {
        mode = "dump"; in = argv[2]; out = argv[3];
    } else if (argc == 4 && !strcmp(argv[1], "--bench")) {
        char err[320];
        mode = "bench"; in = argv[3];
        if (host_opt_int("--bench", argv[2], 1, 1000000, &reps, err, sizeof err)) {
            fprintf(stderr, "lumo-draco-decode: error: %s\n", err);
            return 2;
        }
    } else if (argc == 3 && argv[1][0] != '-') {
        in = argv[1]; out = argv[2];
    } else {
        fprintf(stderr, "usage: lumo-draco-decode [--lean] IN.drc OUT.ply | --info IN.drc | "
                        "--dump IN.drc OUT.txt | --bench N IN.drc\n");
        return 2;
    }
    {
        char err[600] = "";
        if (host_opt_file(NULL, in, "Draco file", err, sizeof err) || !(data = host_read_file(in, &size))) {
            fprintf(stderr, "lumo-draco-decode: error: %s\n", err[0] ? err : "cannot read");
            return 1;
        }
    }
    for (i = 0; i < reps; ++i) {
        if (mem)
            free(mem);
        mem = NULL;
        st = decode(data, size, &m, &mem, &need, strcmp(mode, "bench") != 0);
        if (st) {
            fprintf(stderr, "lumo-draco-decode: error: %s: %s\n", in, lumo_strerror(st));
            free(mem);
            free(data);
            return 1;
        }
    }
    if (!strcmp(mode, "info")) {
        lumo_draco_info info;
        write_info(&m, &need, size, lumo_draco_peek(data, size, &info) ? 0 : info.flags);
    } else if (!strcmp(mode, "dump")) {
        FILE *f;
        errno = 0;
        if (!(f = fopen(out, "w")))
            rc = 1;
        else {
            write_dump(f, &m);
            rc = fclose(f) ? 1 : 0;
        }
    } else if (!strcmp(mode, "ply")) {
        errno = 0;
        rc = write_ply(out, &m);
    }
    if (rc)
        fprintf(stderr, "lumo-draco-decode: error: %s: cannot write: %s\n", out,
                errno ? strerror(errno) : "short write");
    free(mem);
    free(data);
    return rc;
}
