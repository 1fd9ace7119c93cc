/*
 * draw.c — lumo-client's pictures: a PNG frame each time the scene passes a
 * threshold (--frames-at), frame-first.png as soon as every base mesh and the
 * grid's corners are in, and a row of progress.csv per frame. Everything but
 * the ms column follows from the frames taken, so a replay of a recording
 * writes the same files byte for byte.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "lumo_host/png_io.h"
#include "../../net/host/net_socket.h"
#include "client.h"
#include "../lumo-render/scene_convert.h"

int draws_open(client *c)
{
    char path[1024];

    mkdir(c->o.out, 0777);
    snprintf(path, sizeof path, "%s/progress.csv", c->o.out);
    if (!(c->csv = fopen(path, "w"))) {
        fprintf(stderr, "lumo-client: error: %s: cannot write\n", path);
        return -1;
    }
    fprintf(c->csv, "percent,bytes_in,data_bytes,vertices,full_vertices,triangles,rounds,full_rounds,ms,frame\n");
    return 0;
}

void draws_close(client *c)
{
    if (c->csv)
        fclose(c->csv);
    c->csv = NULL;
    host_scene_free(&c->scene);
}

/* The share of the scene held, in percent: geometry and lighting half each
 * (all geometry when there is no IVG). */
static double held_percent(const lumo_net_progress *p)
{
    double g = p->full_vertices ? (double)p->vertices / p->full_vertices : 1.0;
    double l = p->full_rounds ? (double)p->rounds / p->full_rounds : -1.0;

    return 100.0 * (l < 0 ? g : (g + l) / 2);
}

/* The first picture: every mesh has its base and the grid its corners (or
 * there is no grid): what seed 000 shows after a few percent of the bytes. */
static int first_picture_ready(const client *c)
{
    uint32_t m;

    if (c->drv.state != LUMO_NET_READY && c->drv.state != LUMO_NET_DONE)
        return 0;
    for (m = 0; m < c->drv.mesh_count; m++)
        if (c->drv.held[m] == 0)
            return 0;
    return !c->drv.has_ivg || c->drv.rounds_held > 0;
}

/* A row of progress.csv for the frame just written. */
static void progress_row(client *c, double percent, const lumo_net_progress *p, uint32_t tris, const char *name)
{
    if (!c->csv)
        return;
    fprintf(c->csv, "%.2f,%llu,%llu,%u,%u,%u,%u,%u,%u,%s\n", percent, (unsigned long long)c->taken_bytes,
            (unsigned long long)p->bytes, p->vertices, p->full_vertices, tris, p->rounds, p->full_rounds,
            host_net_clock_ms(NULL) - c->t0, name);
    fflush(c->csv);
}

static int draw_frame(client *c, double percent, const lumo_net_progress *p, const char *tag)
{
    const lumo_ivg *ivg = lumo_session_ivg(&c->ses);
    lumo_raster_mesh mesh;
    lumo_raster_scene rs;
    host_renderer *r;
    host_load_stats st;
    char err[256], name[1024];
    uint8_t *rgb;
    uint32_t t;
    int rc;

    if (host_scene_from_session(&c->ses, &c->scene, &st))
        return -1;
    if (host_scene_aim(&c->scene, c->o.camera ? &c->o.view : NULL, c->o.fit, c->o.ro.width, c->o.ro.height, err, sizeof err)) {
        fprintf(stderr, "lumo-client: error: %s\n", err);
        return -1;
    }
    mesh = host_mesh_raster(&c->scene.mesh);
    memset(&rs, 0, sizeof rs);
    rs.lights = c->scene.lights;
    rs.light_count = c->scene.light_count;
    rs.exposure = LUMO_Q16_ONE;
    rs.flags = c->o.per_vertex ? 0 : LUMO_RASTER_PER_PIXEL;
    if (ivg && p->rounds) {
        rs.indirect = lumo_raster_ivg_irradiance;
        rs.indirect_ctx = ivg;
    }
    if (!(r = host_renderer_open(c->o.backend, &mesh, ivg, &c->o.ro, err, sizeof err))) {
        fprintf(stderr, "lumo-client: error: %s\n", err);
        return -1;
    }
    rgb = malloc((size_t)c->o.ro.width * c->o.ro.height * 3);
    t = host_net_clock_ms(NULL);
    rc = !rgb || host_renderer_draw(r, &c->scene.camera, &rs, rgb);
    c->last_fps = 1000.0 / ((host_net_clock_ms(NULL) - t) + 0.5);
    if (tag)
        snprintf(name, sizeof name, "%s/frame-%s.png", c->o.out, tag);
    else
        snprintf(name, sizeof name, "%s/frame-%06.2f.png", c->o.out, percent);
    if (!rc && host_png_write_rgb8(name, rgb, c->o.ro.width, c->o.ro.height, err, sizeof err)) {
        fprintf(stderr, "lumo-client: error: %s\n", err);
        rc = 1;
    }
    if (!rc) {
        progress_row(c, percent, p, mesh.tri_count, name);
        c->frames_drawn++;
    }
    free(rgb);
    host_renderer_close(r);
    return rc ? -1 : 0;
}

int draw_update_frame(client *c, uint32_t n, double seconds, uint32_t records)
{
    lumo_net_progress p;
    char tag[32];

    lumo_net_client_progress(&c->drv, &p);
    snprintf(tag, sizeof tag, "update-%03u", n);
    if (!c->o.quiet)
        fprintf(stderr, "\rlumo-client: updates: %6.2f s, %u records  ", seconds, records);
    return draw_frame(c, 100.0, &p, tag);
}

static void progress_line(const client *c, const lumo_net_progress *p)
{
    if (c->o.quiet)
        return;
    fprintf(stderr, "\rlumo-client: %8.1f KB  %u/%u vertices  IVG %5.1f%%  %.0f fps  ",
            c->l.bytes_in / 1024.0, p->vertices, p->full_vertices,
            p->full_rounds ? 100.0 * p->rounds / p->full_rounds : 0.0, c->last_fps);
}

int frames_due(client *c)
{
    lumo_net_progress p;
    double have;

    lumo_net_client_progress(&c->drv, &p);
    have = p.done ? 100.0 : held_percent(&p);
    if (!c->first_done && first_picture_ready(c)) {
        c->first_done = 1;
        c->first_ms = host_net_clock_ms(NULL) - c->t0;
        c->first_bytes = c->taken_bytes;
        if (draw_frame(c, have, &p, "first"))
            return -1;
    }
    while (c->next_at < c->o.nat && have >= c->o.at[c->next_at] - 1e-9) {
        if (draw_frame(c, c->o.at[c->next_at], &p, NULL))
            return -1;
        c->next_at++;
    }
    progress_line(c, &p);
    return 0;
}
