/* tools/lumo-pm/main.c — lumo-pm: build a progressive-mesh stream from a mesh file
 * (docs/progressive-mesh.md), and the pm benchmark driver (bench.c).
 *
 *   lumo-pm build IN.ply -o OUT.lumo [--batch N] [--bits B] [--raw]
 *   lumo-pm clean IN.ply -o OUT.ply      the welded, cleaned input mesh
 *   lumo-pm apply STREAM [N]             apply the first N records (a bare
 *                                        stream or a package) with the
 *                                        client (for callgrind in the bench)
 *   lumo-pm bench ...                    see bench.c
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/package.h"
#include "lumo_host/file_io.h"
#include "lumo_host/options.h"
#include "package/package_write.h"
#include "pm/pm_client.h"
#include "pm/pm_load.h"
#include "lumo/pmesh.h"
#include "pm/pm_stream.h"

int bench_main(int argc, char **argv);

typedef struct {
    const char *in, *out;
    const char *ctx_stats;   /* --context-stats FILE, or NULL */
    srv_pm_stream_options so;
    srv_pm_options po;
    int raw, albedo;
} args;

static const char k_usage[] =
    "usage: lumo-pm build IN -o OUT.lumo [--batch N] [--bits B] [--min-vertices N] [--rounds F] [--lattice auto|on|off] [--albedo] [--no-seed] [--raw]\n"
    "                     [--context-stats FILE]\n"
    "       lumo-pm clean IN -o OUT.ply\n"
    "       lumo-pm apply STREAM|PACKAGE [RECORDS]\n"
    "       lumo-pm bench --out SECTION.md MODEL...\n"
    "  --batch N          vertices per batch record, 1..1048576 (default: per mesh, 250 doubled up to 2000 for large meshes)\n"
    "  --bits B           position quantization bits, 1..20 (default: per mesh, from its median edge)\n"
    "  --min-vertices N   stop simplifying at N vertices, 3.. (default 3)\n"
    "  --rounds F         fraction of candidates per independent-set round, 0..1 (0.1; 0: one\n"
    "                     collapse at a time)\n"
    "  --lattice M        coordinates copied from the ring (meshes from voxel grids): auto (default:\n"
    "                     built both ways, the smaller kept), on or off\n"
    "  --albedo           stream the per-vertex albedo too\n"
    "  --no-seed          stop simplifying at the base mesh (default: on to a seed mesh, whose\n"
    "                     splits up to the base mesh the base record codes; same levels shown)\n"
    "  --context-stats F  write the adaptive bits coded per range-code context to F, one line\n"
    "                     each: context, zeros, ones (tools/pm_priors.py fits the priors from them)\n"
    "  --raw              write the bare stream, not a package (no INFO: lumo-render needs a scene\n"
    "                     from lumo-bake; lumo-inspect --stream / --lod read both)\n";

static int usage(void)
{
    fputs(k_usage, stderr);
    return 2;
}

/* An option that takes a value: 0, or -1 with the refusal in err. */
static int take_value(args *a, const char *opt, const char *v, char *err, size_t errlen)
{
    if (!strcmp(opt, "-o")) {
        a->out = v;
        return 0;
    }
    if (!strcmp(opt, "--context-stats")) {
        a->ctx_stats = v;
        return 0;
    }
    if (!strcmp(opt, "--batch"))
        return host_opt_u32(opt, v, 1, 1u << 20, &a->so.batch_vertices, err, errlen);
    if (!strcmp(opt, "--bits"))
        return host_opt_int(opt, v, 1, (int)LUMO_PMESH_MAX_QBITS, &a->so.quant_bits, err, errlen);
    if (!strcmp(opt, "--min-vertices"))
        return host_opt_u32(opt, v, 3, UINT32_MAX, &a->po.min_vertices, err, errlen);
    if (!strcmp(opt, "--rounds"))
        return host_opt_double(opt, v, 0, 1, &a->po.round_fraction, err, errlen);
    if (!strcmp(opt, "--lattice")) {
        static const char *const modes[] = {"auto", "off", "on"};
        for (int m = 0; m < 3; m++)
            if (!strcmp(v, modes[m]))
                return a->so.lattice = m - 1, 0;
        snprintf(err, errlen, "--lattice: '%.32s' is not auto, on or off", v);
        return -1;
    }
    snprintf(err, errlen, "%.64s: unknown option (try --help)", opt);
    return -1;
}

/* build / clean: 0, or -1 with the refusal in err. */
static int parse(int argc, char **argv, args *a, char *err, size_t errlen)
{
    memset(a, 0, sizeof *a);
    srv_pm_stream_default_options(&a->so);
    srv_pm_default_options(&a->po);
    for (int i = 2; i < argc; i++) {
        const char *o = argv[i];
        if (!strcmp(o, "--raw"))
            a->raw = 1;
        else if (!strcmp(o, "--albedo"))
            a->albedo = 1;  /* stream the per-vertex albedo too */
        else if (!strcmp(o, "--no-seed"))
            a->po.seed = 0;  /* the base record as plain bits only */
        else if (o[0] != '-' && !a->in)
            a->in = o;
        else if (o[0] != '-') {
            snprintf(err, errlen, "unexpected argument '%.128s' (one input mesh)", o);
            return -1;
        } else if (i + 1 == argc) {
            take_value(a, o, "", err, errlen);   /* names an unknown option */
            if (!strstr(err, "unknown option"))
                snprintf(err, errlen, "%.64s needs a value (try --help)", o);
            return -1;
        } else if (take_value(a, o, argv[++i], err, errlen))
            return -1;
    }
    if (!a->in || !a->out) {
        snprintf(err, errlen, "%s (try --help)", a->in ? "no output file: give -o OUT" : "no input mesh");
        return -1;
    }
    return host_opt_file(NULL, a->in, "mesh file", err, errlen);
}

static int write_file(const char *path, const uint8_t *d, size_t n)
{
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(d, 1, n, f) == n;
    if (f && fclose(f))
        ok = 0;
    if (!ok)
        fprintf(stderr, "lumo-pm: error: %s: cannot write: %s\n", path, strerror(errno));
    return ok ? 0 : -1;
}

static int write_output(const args *a, const uint8_t *s, size_t n)
{
    if (a->raw)
        return write_file(a->out, s, n);
    srv_pkg_writer w;
    char err[256];
    srv_pkgw_init(&w);
    int rc = srv_pkgw_add(&w, LUMO_PKG_PMSH, s, n) || srv_pkgw_write_file(&w, a->out, err, sizeof err);
    if (rc)
        fprintf(stderr, "lumo-pm: error: %s\n", err);
    srv_pkgw_free(&w);
    return rc ? -1 : 0;
}

/* Per context with any bits: "context zeros ones". */
static int write_ctx_stats(const char *path, const srv_pm_stream_stats *st)
{
    FILE *f = fopen(path, "w");
    for (uint32_t c = 0; f && c < LUMO_PMESH_CONTEXTS; c++)
        if (st->ctx_bits[c][0] + st->ctx_bits[c][1])
            fprintf(f, "%u %llu %llu\n", c, (unsigned long long)st->ctx_bits[c][0],
                    (unsigned long long)st->ctx_bits[c][1]);
    if (!f || fclose(f)) {
        fprintf(stderr, "lumo-pm: error: %s: cannot write: %s\n", path, strerror(errno));
        return -1;
    }
    return 0;
}

static int cmd_build(const args *a, int clean_only)
{
    float *xyz;
    uint8_t *rgb = NULL;
    uint32_t *tris, nv, nf, nb;
    char err[256];
    srv_pm pm;
    uint8_t *s = NULL;
    size_t n = 0;
    if (srv_pm_load(a->in, &xyz, a->albedo ? &rgb : NULL, &nv, &tris, &nf, err, sizeof err)) {
        fprintf(stderr, "lumo-pm: error: %s\n", err);
        return 1;
    }
    int rc = 1;
    if (srv_pm_build_albedo(xyz, rgb, nv, tris, nf, &a->po, &pm)) {
        fprintf(stderr, "lumo-pm: error: %s: cannot simplify (bad indices or out of memory)\n", a->in);
        goto done;
    }
    if (clean_only) {
        errno = 0;
        rc = srv_pm_write_ply(a->out, pm.xyz, pm.vertices, pm.tris, pm.faces) ? 1 : 0;
        if (rc)
            fprintf(stderr, "lumo-pm: error: %s: cannot write: %s\n", a->out,
                    errno ? strerror(errno) : "write failed");
        goto done;
    }
    srv_pm_stream_stats st;
    srv_pm_stream_options so = a->so;
    so.stats = &st;
    if (srv_pm_stream_build(&pm, &so, &s, &n, NULL, &nb)) {
        fprintf(stderr, "lumo-pm: error: %s: cannot build the stream (out of memory or a mesh the stream "
                        "cannot hold)\n", a->in);
        goto done;
    }
    if (write_output(a, s, n) || (a->ctx_stats && write_ctx_stats(a->ctx_stats, &st)))
        goto done;
    lumo_pmesh_header h;
    (void)lumo_pmesh_read_header(s, n, &h);  /* what the per-mesh choices made */
    printf("%s: %u vertices (%u welded), %u faces (%u dropped), base %u vertices / %u faces "
           "(seed %u / %u), %u batches of %u, %u-bit positions%s, %zu bytes, %.2f bits/triangle\n",
           a->out, pm.vertices, pm.welded, pm.faces, pm.dropped_faces, pm.base_vertices,
           pm.base_faces, h.position_coding == LUMO_PMESH_POS_CODED ? pm.seed_vertices : pm.base_vertices,
           h.position_coding == LUMO_PMESH_POS_CODED ? pm.seed_faces : pm.base_faces, nb, h.batch_vertices, h.quant_bits,
           h.flags & LUMO_PMESH_LATTICE ? " (lattice copies)" : "", n, pm.faces ? 8.0 * n / pm.faces : 0.0);
    double sv = st.splits ? (double)st.splits : 1.0;
    printf("bits per split vertex: parent %.2f, kind %.2f, fan %.2f, mask %.2f, positions %.2f, "
           "albedo %.2f, other %.2f, draco payload %.2f, record heads %.2f\n",
           st.parent_bits / sv, st.kind_bits / sv, st.fan_bits / sv, st.mask_bits / sv,
           st.pos_bits / sv, st.albedo_bits / sv, st.other_bits / sv, 8.0 * st.draco_bytes / sv, 8.0 * st.frame_bytes / sv);
    printf("fan splits: %llu (%.1f%% of splits), %.1f%% of them coded by rank\n",
           (unsigned long long)st.fans, 100.0 * st.fans / sv,
           st.fans ? 100.0 * st.arc_ranked / st.fans : 0.0);
    rc = 0;
done:
    free(s);
    srv_pm_free(&pm);
    free(xyz);
    free(rgb);
    free(tris);
    return rc;
}

static int cmd_apply(int argc, char **argv)
{
    size_t len = 0;
    uint32_t records = UINT32_MAX;
    char err[400];
    uint8_t *d;
    if (argc < 3 || argc > 4)
        return usage();
    if ((argc > 3 && host_opt_u32("RECORDS", argv[3], 0, UINT32_MAX, &records, err, sizeof err)) ||
        host_opt_file(NULL, argv[2], "stream", err, sizeof err) || !(d = host_read_file(argv[2], &len))) {
        fprintf(stderr, "lumo-pm: error: %s\n", err);
        return 1;
    }
    srv_pm_client c;
    unsigned long done = 0;
    const uint8_t *stream = NULL;
    size_t stream_len = 0;
    /* a bare stream or a package's first PMSH chunk (lumo-pm build writes a package) */
    lumo_status st = srv_pm_find_stream(d, len, 0, &stream, &stream_len);
    if (st) {
        printf("0 records, 0 vertices, 0 faces: %s (neither a stream nor a package with one)\n",
               lumo_strerror(st));
        free(d);
        return 1;
    }
    st = srv_pm_client_open(&c, stream, stream_len);
    while (!st && done < records && !lumo_pmesh_complete(&c.pm))
        st = srv_pm_client_step(&c), done++;
    lumo_pmesh_view v;
    lumo_pmesh_get_view(&c.pm, &v);
    printf("%lu records, %u vertices, %u faces: %s\n", done, v.vertex_count, v.face_count,
           lumo_strerror(st));
    srv_pm_client_close(&c);
    free(d);
    return st ? 1 : 0;
}

int main(int argc, char **argv)
{
    args a;
    char err[400];
    if (argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        fputs(k_usage, stdout);
        return 0;
    }
    if (argc >= 2 && !strcmp(argv[1], "apply"))
        return cmd_apply(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "bench"))
        return bench_main(argc - 1, argv + 1);
    if (argc < 2 || (strcmp(argv[1], "build") && strcmp(argv[1], "clean")))
        return usage();
    if (parse(argc, argv, &a, err, sizeof err)) {
        fprintf(stderr, "lumo-pm: error: %s\n", err);
        return 2;
    }
    return cmd_build(&a, !strcmp(argv[1], "clean"));
}
