/* tools/lumo-bake/main.c — lumo-bake: scene in, .lumo package (or reference PNG) out.
 * Usage in docs/server.md; every failure is one line on stderr, exit 1. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "lumo_host/options.h"
#include "lumo_host/png_io.h"
#include "bake/bake.h"
#include "scene/import.h"
#include "package/package_write.h"
#include "pm/pm_stream.h"
#include "common/progress.h"
#include "bake/budget.h"
#include "bake/reference.h"
#include "bake/cluster.h"
#include "scene/camera.h"
#include "scene/shapes.h"
#include "lumo_host/version_line.h"
#include "bake_prt.h"

#define DEFAULT_DRAGON "build/data/models/dragon_48k.ply"

/* How meshes go into the package: progressive PMSH streams (the default:
 * "the progressive stream replaces the raw mesh", seed 000 §4.2,
 * docs/progressive-mesh.md), raw MESH chunks, or both. */
enum { MESH_RAW = 1, MESH_PM = 2, MESH_BOTH = 3 };
/* A bake vertex is cheap (one per grid point): 256 paths keep the IVG's
 * noise low; a reference pixel needs far fewer for a preview. */
#define DEFAULT_BAKE_SPP 256
#define DEFAULT_REF_SPP 64

typedef struct {
    const char *scene, *out, *dragon, *checkpoint;
    int   use_default, dims[3], spp, threads, ref_w, ref_h, indirect_only, progress, allow_large;
    float cell, exposure;
    uint64_t seed;
    vec3  albedo;
    int   has_albedo, has_camera;
    int   mesh_mode;          /* MESH_RAW, MESH_PM or MESH_BOTH */
    srv_camera camera;
    const char *lights[LUMO_MAX_LIGHTS];
    int   nlights;
    const char *prt_spec;     /* --prt, parsed once threads are known */
    bake_prt prt;
} options;

static const char usage[] =
    "usage: lumo-bake SCENE|--default -o OUT.lumo [options]\n"
    "       lumo-bake SCENE|--default --reference WxH [--camera EYE:TARGET:UP:FOVY] -o OUT.png\n"
    "Bakes the indirect-light Irradiance Vector Grid of a scene (path tracing\n"
    "with Embree) into a .lumo package, or renders a path-traced reference image.\n"
    "  --default              the built-in Cornell box (dragon when available)\n"
    "  -o, --output FILE      package (.lumo) or, with --reference, PNG\n"
    "  --grid N|NX,NY,NZ      grid vertices per axis, 2..256 (default 16)\n"
    "  --cell SIZE            or: grid spacing in metres\n"
    "  --spp N                paths per grid vertex (default 256) / per pixel (default 64)\n"
    "  --seed S               random seed; same seed, same bytes (default 1)\n"
    "  --threads N            worker threads (per MPI rank; default: all cores)\n"
    "  --checkpoint DIR       keep finished chunks in DIR; a re-run resumes from them\n"
    "  --light SPEC           add a light (repeatable): point:X,Y,Z:R,G,B |\n"
    "                         spot:X,Y,Z:DX,DY,DZ:HALF_DEG:R,G,B |\n"
    "                         directional:DX,DY,DZ:R,G,B | area:X,Y,Z:U..:V..:R,G,B\n"
    "  --albedo R,G,B         override every material's albedo\n"
    "  --mesh pm|raw|both     mesh chunks: progressive PMSH (default), raw MESH, or both\n"
    "  --dragon FILE          model for --default (default " DEFAULT_DRAGON ",\n"
    "                         or LUMO_DRAGON); a named model that cannot be read is an error;\n"
    "                         'sphere': the server's generated sphere instead of a model\n"
    "  --reference WxH        render a reference image instead of baking\n"
    "  --camera E:T:U:FOVY    camera (default: the scene's, else one fitted to its bounds)\n"
    "  --indirect-only        reference image of the indirect light only\n"
    "  --exposure E           PNG exposure (default 1.0)\n"
    "  --prt N[,clusters=K,components=P,alpha=A,bounces=B,strata=S,registers=R]\n"
    "                         also PRT: SH order N (1..6) transfer per vertex, CPCA\n"
    "                         (defaults 64 clusters, 8 components, alpha 0, 1 bounce,\n"
    "                         32x32 directions, super-clusters of 256 float4 registers)\n"
    "                         into a PRTV chunk per mesh (docs/prt.md)\n"
    "  --prt-env FILE.png     with --prt: an equirectangular environment's SH lighting (PRTL)\n"
    "  --no-progress          never draw the progress bar\n"
    "  --allow-large          bake past the budget (64^3 vertices, 32^3 x 512 paths)\n"
    "  -h, --help             this text\n"
    "Conventions (units, lights, camera, tone mapping): docs/scene-format.md\n";

static int fail(const char *msg)
{
    fprintf(stderr, "lumo-bake: error: %s\n", msg);
    return 1;
}

/* --grid N or NX,NY,NZ, each 2..256; a refusal names the whole value and
 * the part. */
static int parse_grid(const char *t, int dims[3], char *err, size_t errlen)
{
    char part[64], why[320];
    const char *p = t;
    int d[3], n = 0;

    for (;;) {
        size_t len = strcspn(p, ",");
        snprintf(part, sizeof part, "%.*s", (int)(len < sizeof part ? len : sizeof part - 1), p);
        if (n == 3 || len >= sizeof part || host_opt_int("--grid", part, 2, 256, &d[n], why, sizeof why)) {
            const char *r = strstr(why, ": ");
            char which[24] = "";
            if (strchr(t, ','))
                snprintf(which, sizeof which, "value %d ", n + 1);
            snprintf(err, errlen, "--grid %.64s: %s%s (N or NX,NY,NZ)", t, n == 3 ? "more than 3 values" : which,
                     n == 3 ? "" : len >= sizeof part ? "too long" : r ? r + 2 : why);
            return -1;
        }
        n++;
        if (!p[len])
            break;
        p += len + 1;
    }
    if (n == 2) {
        snprintf(err, errlen, "--grid %.64s: 1 or 3 values wanted, 2 given (N or NX,NY,NZ)", t);
        return -1;
    }
    dims[0] = d[0];
    dims[1] = n == 1 ? d[0] : d[1];
    dims[2] = n == 1 ? d[0] : d[2];
    return 0;
}

enum { O_DEFAULT = 256, O_GRID, O_CELL, O_SPP, O_SEED, O_THREADS, O_LIGHT, O_ALBEDO, O_DRAGON,
       O_REF, O_CAMERA, O_INDIRECT, O_EXPOSURE, O_NOPROGRESS, O_MESH, O_ALLOW_LARGE, O_PRT, O_PRT_ENV, O_CHECKPOINT };

static const struct option k_long[] = {
    {"default", no_argument, 0, O_DEFAULT}, {"output", required_argument, 0, 'o'},
    {"grid", required_argument, 0, O_GRID}, {"cell", required_argument, 0, O_CELL},
    {"spp", required_argument, 0, O_SPP}, {"seed", required_argument, 0, O_SEED},
    {"threads", required_argument, 0, O_THREADS}, {"light", required_argument, 0, O_LIGHT},
    {"albedo", required_argument, 0, O_ALBEDO}, {"dragon", required_argument, 0, O_DRAGON},
    {"reference", required_argument, 0, O_REF}, {"camera", required_argument, 0, O_CAMERA},
    {"indirect-only", no_argument, 0, O_INDIRECT}, {"exposure", required_argument, 0, O_EXPOSURE},
    {"no-progress", no_argument, 0, O_NOPROGRESS}, {"mesh", required_argument, 0, O_MESH},
    {"allow-large", no_argument, 0, O_ALLOW_LARGE},
    {"prt", required_argument, 0, O_PRT}, {"prt-env", required_argument, 0, O_PRT_ENV},
    {"checkpoint", required_argument, 0, O_CHECKPOINT},
    {"help", no_argument, 0, 'h'}, {0, 0, 0, 0}};

/* The options that take a number; 0, or -1 with the refusal in err. */
static int take_number(options *o, int c, const char *arg, char *err, size_t errlen)
{
    double d, v[3];
    uint32_t w, h;

    switch (c) {
    case O_GRID: return parse_grid(arg, o->dims, err, errlen);
    case O_CELL:
        if (host_opt_positive("--cell", arg, 1e6, &d, err, errlen))
            return -1;
        o->cell = (float)d;
        return 0;
    case O_SPP: return host_opt_int("--spp", arg, 1, 1 << 24, &o->spp, err, errlen);
    case O_SEED: return host_opt_u64("--seed", arg, &o->seed, err, errlen);
    case O_THREADS: return host_opt_int("--threads", arg, 1, 256, &o->threads, err, errlen);
    case O_ALBEDO:
        if (host_opt_vec("--albedo", arg, 3, 0, 1, v, err, errlen))
            return -1;
        o->albedo = v3(fminf((float)v[0], 0.98f), fminf((float)v[1], 0.98f), fminf((float)v[2], 0.98f));
        o->has_albedo = 1;
        return 0;
    case O_REF:
        if (host_opt_size("--reference", arg, 16384, 16384, &w, &h, err, errlen))
            return -1;
        o->ref_w = (int)w;
        o->ref_h = (int)h;
        return 0;
    case O_EXPOSURE:
        if (host_opt_double("--exposure", arg, 0, 65535, &d, err, errlen))
            return -1;
        o->exposure = (float)d;
        return 0;
    default: snprintf(err, errlen, "unhandled option %d", c); return -1;
    }
}

/* One option; returns 0, 1 for --help, or -1 with a message in err. */
static int take_option(options *o, int c, const char *arg, char *err, size_t errlen)
{
    static const char *const k_meshes[] = {"raw", "pm", "both"};   /* MESH_RAW - 1, ... */
    char why[200];
    srv_light light;

    switch (c) {
    case O_DEFAULT: o->use_default = 1; return 0;
    case 'o': o->out = arg; return 0;
    case O_LIGHT:
        if (o->nlights == LUMO_MAX_LIGHTS) {
            snprintf(err, errlen, "--light %.64s: more than %d lights; a scene holds at most %d "
                     "(LUMO_MAX_LIGHTS, lumo/config.h)", arg, LUMO_MAX_LIGHTS, LUMO_MAX_LIGHTS);
            return -1;
        }
        if (srv_light_parse_as("--light", arg, &light, err, errlen))
            return -1;
        o->lights[o->nlights++] = arg;
        return 0;
    case O_DRAGON: o->dragon = arg; return 0;
    case O_CAMERA:
        if (srv_camera_parse_why(arg, &o->camera, why, sizeof why)) {
            snprintf(err, errlen, "--camera %.128s: %s (docs/scene-format.md)", arg, why);
            return -1;
        }
        o->has_camera = 1;
        return 0;
    case O_INDIRECT: o->indirect_only = 1; return 0;
    case O_NOPROGRESS: o->progress = 0; return 0;
    case O_ALLOW_LARGE: o->allow_large = 1; return 0;
    case O_CHECKPOINT: o->checkpoint = arg; return 0;
    case O_MESH:
        if (host_opt_choice("--mesh", arg, k_meshes, 3, &o->mesh_mode, err, errlen))
            return -1;
        o->mesh_mode += 1;
        return 0;
    case O_PRT: o->prt_spec = arg; return 0;
    case O_PRT_ENV: o->prt.env = arg; return 0;
    case 'h': return 1;
    default: return take_number(o, c, arg, err, errlen);
    }
}

static int parse_args(options *o, int argc, char **argv, char *err, size_t errlen)
{
    int c;
    memset(o, 0, sizeof *o);
    o->dims[0] = o->dims[1] = o->dims[2] = 16;
    o->spp = 0;   /* 0: the default of the mode, set after parsing */
    o->seed = 1;
    o->exposure = 1.0f;
    o->progress = 1;
    o->mesh_mode = MESH_PM;
    o->threads = (int)sysconf(_SC_NPROCESSORS_ONLN);
    o->threads = o->threads < 1 ? 1 : o->threads > 256 ? 256 : o->threads;
    opterr = 0;
    while ((c = host_getopt(argc, argv, ":o:h", k_long)) != -1) {
        if (c == '?' || c == ':')
            return host_opt_getopt_error(c, argv[optind - 1], optopt, err, errlen);
        int rc = take_option(o, c, optarg, err, errlen);
        if (rc)
            return rc;
    }
    if (optind < argc)
        o->scene = argv[optind++];
    if (optind < argc) {
        snprintf(err, errlen, "unexpected argument '%s'", argv[optind]);
        return -1;
    }
    if (!o->scene == !o->use_default) {
        snprintf(err, errlen, "give exactly one of SCENE or --default (try --help)");
        return -1;
    }
    if (!o->out) {
        snprintf(err, errlen, "no output file: give -o OUT.lumo, or -o OUT.png with --reference (try --help)");
        return -1;
    }
    if (o->dragon && !o->use_default) {
        snprintf(err, errlen, "--dragon %.128s: only with --default (a SCENE names its own models)", o->dragon);
        return -1;
    }
    if (o->spp == 0)
        o->spp = o->ref_w ? DEFAULT_REF_SPP : DEFAULT_BAKE_SPP;
    if (o->prt_spec && bake_prt_parse(&o->prt, o->prt_spec, o->threads, o->progress, err, errlen))
        return -1;
    if (o->prt.env && !o->prt.on) {
        snprintf(err, errlen, "--prt-env needs --prt");
        return -1;
    }
    return 0;
}

/* A scene description ends in .txt or .scene; any other file is a mesh
 * for assimp (docs/server.md). */
static int is_description(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && (!strcmp(dot, ".txt") || !strcmp(dot, ".scene"));
}

static lumo_status load_file(const char *path, srv_scene *s, char *err, size_t errlen)
{
    srv_xform x = srv_xform_identity();
    if (is_description(path))
        return srv_scene_load(s, path, err, errlen);
    return srv_import_file(s, path, &x, NULL, err, errlen);
}

/* A scene with no camera of its own (a model, a scene file without a
 * camera line) gets one that frames it, and the user is told where the
 * scene is, so lights and cameras can be placed (docs/scene-format.md). */
static lumo_status fit_camera(srv_scene *s, char *err, size_t errlen)
{
    vec3 lo, hi;
    char text[256];

    srv_scene_bounds(s, &lo, &hi);
    if (srv_camera_fit(lo, hi, &s->camera)) {
        snprintf(err, errlen, "the scene spans %g,%g,%g .. %g,%g,%g: clients hold coordinates below "
                 "32768 m (Q16.16); scale the model down", (double)lo.x, (double)lo.y, (double)lo.z,
                 (double)hi.x, (double)hi.y, (double)hi.z);
        return LUMO_ERR_RANGE;
    }
    srv_camera_format(&s->camera, text, sizeof text);
    fprintf(stderr, "lumo-bake: scene bounds %g,%g,%g .. %g,%g,%g; no camera given, fitted: --camera %s\n",
            (double)lo.x, (double)lo.y, (double)lo.z, (double)hi.x, (double)hi.y, (double)hi.z, text);
    return LUMO_OK;
}

/* The model of --default: --dragon, else LUMO_DRAGON, else the dragon;
 * "sphere" asks for the server's generated sphere (*model NULL). A file
 * the user named is used or refused; only the built-in dragon, when
 * tools/setup.sh has not fetched it, gives way to the sphere (said on
 * stderr). 0, or -1 with err set. */
static int default_model(const options *o, const char **model, char *err, size_t errlen)
{
    const char *env = getenv("LUMO_DRAGON");

    *model = o->dragon ? o->dragon : env;
    if (*model && !strcmp(*model, "sphere")) {
        *model = NULL;
        return 0;
    }
    if (o->dragon)
        return host_opt_file("--dragon", o->dragon, "model file", err, errlen);
    if (env)
        return host_opt_file("LUMO_DRAGON", env, "model file", err, errlen);
    if (access(DEFAULT_DRAGON, R_OK))
        fprintf(stderr, "lumo-bake: note: %s missing (tools/setup.sh fetches it): a sphere in its place\n",
                DEFAULT_DRAGON);
    *model = DEFAULT_DRAGON;
    return 0;
}

/* SCENE or --default with its model, checked as files first (a directory
 * or an empty file is named as such, not handed to a reader). */
static lumo_status load_base(const options *o, srv_scene *s, char *err, size_t errlen)
{
    const char *dragon;

    if (!o->use_default)
        return host_opt_file(NULL, o->scene, "scene or model file", err, errlen) ? LUMO_ERR_ARG
                                                                                 : load_file(o->scene, s, err, errlen);
    if (default_model(o, &dragon, err, errlen))
        return LUMO_ERR_ARG;
    return srv_default_scene(s, dragon, err, errlen);
}

static lumo_status load_scene(const options *o, srv_scene *s, char *err, size_t errlen)
{
    lumo_status st = load_base(o, s, err, errlen);
    for (int i = 0; !st && i < o->nlights; i++) {
        srv_light l;
        st = srv_light_parse_as("--light", o->lights[i], &l, err, errlen);
        if (!st)
            st = l.kind == LUMO_LIGHT_AREA ? srv_add_area_light(s, &l) : srv_scene_add_light(s, &l);
    }
    if (st)
        return st;
    if (o->has_albedo)
        srv_scene_override_albedo(s, o->albedo);
    if (o->has_camera)
        s->camera = o->camera;
    if ((st = srv_scene_validate(s, err, errlen)) || o->has_camera || s->has_camera)
        return st;
    return fit_camera(s, err, errlen);
}

/* "2 threads", or "3 ranks x 2 threads" under MPI. */
static const char *workers_text(const srv_work_report *rep, int threads, char *buf, size_t len)
{
    if (rep->ranks > 1)
        snprintf(buf, len, "%d ranks x %d threads", rep->ranks, threads);
    else
        snprintf(buf, len, "%d threads", threads);
    return buf;
}

/* Under MPI, what each rank did (chunks, bytes exchanged with rank 0);
 * with a checkpoint, what was resumed. */
static void report_work(const options *o, const srv_work *w, const srv_work_report *rep)
{
    if (o->checkpoint)
        fprintf(stderr, "lumo-bake: checkpoint %s/%s.ckpt: %zu of %zu chunks resumed\n", o->checkpoint, w->name,
                rep->resumed, rep->chunks);
    if (rep->ranks < 2)
        return;
    fprintf(stderr, "lumo-bake: %s over %d ranks, chunks (bytes) per rank:", w->name, rep->ranks);
    for (int r = 0; r < rep->ranks; r++)
        fprintf(stderr, " %zu (%llu)", rep->rank_chunks[r], (unsigned long long)rep->rank_bytes[r]);
    fputc('\n', stderr);
}

static int run_reference(const options *o, const srv_cluster *cl, const srv_scene *s, const srv_tracer *t)
{
    char err[512], workers[64];
    srv_image img = {0, 0, NULL};
    srv_render_task k;
    srv_work_report rep;
    srv_render_opts ro = {o->spp, o->seed, o->threads, o->indirect_only, o->progress};
    if (srv_render_task_init(&k, t, &s->camera, o->ref_w, o->ref_h, &ro) ||
        (cl->rank == 0 && srv_image_alloc(&img, o->ref_w, o->ref_h))) {
        srv_render_task_free(&k);
        return fail("cannot render (out of memory)");
    }
    lumo_status st = srv_cluster_run(cl, &k.work, o->checkpoint, (uint8_t *)(void *)img.rgb, &rep, err, sizeof err);
    if (!st && cl->rank == 0) {
        report_work(o, &k.work, &rep);
        st = host_png_write_radiance(o->out, img.rgb, img.w, img.h, o->exposure, err, sizeof err);
    }
    srv_render_task_free(&k);
    srv_image_free(&img);
    if (st)
        return fail(err);
    if (cl->rank == 0)
        fprintf(stderr, "lumo-bake: %dx%d %s reference, %d spp, %.2f M rays in %.2f s (%.2f M rays/s, %s) -> %s\n",
                o->ref_w, o->ref_h, o->indirect_only ? "indirect-only" : "full", o->spp, (double)rep.rays * 1e-6,
                rep.seconds, (double)rep.rays * 1e-6 / (rep.seconds > 0 ? rep.seconds : 1e-9),
                workers_text(&rep, o->threads, workers, sizeof workers), o->out);
    return 0;
}

/* The grid (--grid, or --cell over the bounds), said before anything is
 * traced, and refused past the budget without --allow-large (bake/budget.h). */
static lumo_status plan_bake(options *o, const srv_scene *s, char *err, size_t errlen)
{
    vec3 lo, hi;
    char what[160];
    lumo_status st;
    srv_scene_bounds(s, &lo, &hi);
    if (o->cell > 0 && (st = srv_bake_dims_for_cell(lo, hi, o->cell, o->dims, err, errlen)))
        return st;
    srv_bake_plan p = srv_bake_plan_of(o->dims, o->spp);
    if ((st = srv_bake_budget_check(&p, o->allow_large, err, errlen)))
        return st;
    /* Said before a bake of seconds or more, and always for --cell, whose
     * grid the user did not write; the summary line repeats it at the end. */
    srv_bake_plan_describe(&p, what, sizeof what);
    if (o->cell > 0 || p.paths >= SRV_BAKE_SAY_PATHS)
        fprintf(stderr, "lumo-bake: %s\n", what);
    return LUMO_OK;
}

/* INFO, then the meshes as --mesh asks: raw chunks and/or one progressive
 * stream per mesh (srv_pm_pack, server/pm/pm_pack.c), in mesh order. */
_Static_assert(sizeof(vec3) == 3 * sizeof(float), "positions are passed as a float xyz array");

static int pack_meshes(const options *o, srv_pkg_writer *w, const srv_scene *s, char *err, size_t errlen)
{
    if (srv_pack_scene(w, s, o->mesh_mode & MESH_RAW)) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (size_t i = 0; (o->mesh_mode & MESH_PM) && i < s->nmeshes; i++) {
        const srv_mesh *m = &s->meshes[i];
        uint8_t *albedo = malloc(3u * (m->nverts ? m->nverts : 1));
        if (!albedo) {
            snprintf(err, errlen, "out of memory");
            return -1;
        }
        for (uint32_t v = 0; v < m->nverts; v++)   /* the stream's albedo is 8-bit linear */
            for (int c = 0; c < 3; c++)
                albedo[3 * v + (uint32_t)c] = (uint8_t)lrintf(255.0f * v3_get(m->albedo[v], c));
        int rc = srv_pm_pack(w, &m->pos[0].x, albedo, m->nverts, m->tris, m->ntris, NULL, err, errlen);
        if (!rc)
            rc = bake_prt_mesh(&o->prt, w, &m->pos[0].x, albedo, m->nverts, m->tris, m->ntris, err, errlen);
        free(albedo);
        if (rc)
            return -1;
    }
    return 0;
}

/* The IVG across the ranks (cluster.h); rank 0 gets it in *res. */
static lumo_status bake_ivg(const options *o, const srv_cluster *cl, const srv_tracer *t, const srv_grid *g,
                            srv_bake_result *res, int *ranks, char *err, size_t errlen)
{
    srv_bake_opts bo = {o->spp, o->seed, o->threads, o->progress, 0.25f};
    srv_bake_task k;
    srv_work_report rep;
    uint8_t *records = NULL;
    memset(res, 0, sizeof *res);
    lumo_status st = srv_bake_task_init(&k, t, g, &bo, err, errlen);
    if (st)
        return st;
    if (cl->rank == 0 && !(records = malloc(k.work.items * k.work.item_bytes))) {
        srv_bake_task_free(&k);
        snprintf(err, errlen, "out of memory for a %zu-vertex grid", k.work.items);
        return LUMO_ERR_NOMEM;
    }
    st = srv_cluster_run(cl, &k.work, o->checkpoint, records, &rep, err, errlen);
    if (!st && cl->rank == 0) {
        report_work(o, &k.work, &rep);
        st = srv_bake_task_result(&k, records, res, err, errlen);
        res->rays = rep.rays;
        res->seconds = rep.seconds;
        *ranks = rep.ranks;
    }
    free(records);
    srv_bake_task_free(&k);
    return st;
}

static int run_bake(options *o, const srv_cluster *cl, const srv_scene *s, const srv_tracer *t)
{
    char err[512], workers[64];
    srv_bake_result res;
    srv_pkg_writer w;
    srv_grid g = srv_grid_over(s, o->dims);
    int ranks = 1;
    if (bake_ivg(o, cl, t, &g, &res, &ranks, err, sizeof err))
        return fail(err);
    if (cl->rank)
        return 0;   /* rank 0 alone writes the package */
    srv_pkgw_init(&w);
    int rc = pack_meshes(o, &w, s, err, sizeof err);
    if (!rc)
        rc = bake_prt_env(&o->prt, &w, err, sizeof err);
    if (!rc)
        rc = srv_pack_ivg(&w, &res, (uint32_t)o->spp, o->seed, err, sizeof err);
    if (!rc && (rc = srv_pack_order(&w)))
        snprintf(err, sizeof err, "cannot write the streaming order: %s", lumo_strerror((lumo_status)rc));
    if (!rc)
        rc = srv_pkgw_write_file(&w, o->out, err, sizeof err);
    srv_pkgw_free(&w);
    size_t solid = 0;
    for (size_t v = 0; v < res.nverts; v++)
        solid += !res.valid[v];
    srv_work_report shown = {.ranks = ranks};
    if (!rc)
        fprintf(stderr, "lumo-bake: %dx%dx%d grid, %zu vertices (%zu solid), %d spp, %.2f M rays in %.2f s "
                        "(%.2f M rays/s, %s) -> %s\n",
                g.dims[0], g.dims[1], g.dims[2], res.nverts, solid, o->spp, (double)res.rays * 1e-6,
                res.seconds, (double)res.rays * 1e-6 / (res.seconds > 0 ? res.seconds : 1e-9),
                workers_text(&shown, o->threads, workers, sizeof workers), o->out);
    srv_bake_result_free(&res);
    return rc ? fail(err) : 0;
}

static int run(options *o, const srv_cluster *cl)
{
    srv_scene s;
    char err[512];
    srv_scene_init(&s);
    if (load_scene(o, &s, err, sizeof err) || (!o->ref_w && plan_bake(o, &s, err, sizeof err))) {
        srv_scene_free(&s);
        return fail(err);
    }
    srv_rt *rt = srv_rt_create(&s, o->threads, err, sizeof err);
    if (!rt) {
        srv_scene_free(&s);
        return fail(err);
    }
    srv_tracer t;
    srv_tracer_init(&t, &s, rt);
    int rc = o->ref_w ? run_reference(o, cl, &s, &t) : run_bake(o, cl, &s, &t);
    srv_rt_free(rt);
    srv_scene_free(&s);
    return rc;
}

int main(int argc, char **argv)
{
    if (host_version_option(argc, argv, "lumo-bake"))
        return 0;
    options o;
    srv_cluster cl;
    char err[512];
    if (srv_cluster_init(&cl, &argc, &argv, err, sizeof err))
        return srv_cluster_end(&cl, fail(err));
    int rc = parse_args(&o, argc, argv, err, sizeof err);
    if (rc == 1) {
        if (cl.rank == 0)
            fputs(usage, stdout);
        return srv_cluster_end(&cl, 0);
    }
    if (rc)
        return srv_cluster_end(&cl, fail(err));
    return srv_cluster_end(&cl, run(&o, &cl));
}
