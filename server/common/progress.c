/* progress.c — terminal progress bar with an ETA from the average rate. */
#include <stdio.h>
#include <time.h>
#include <unistd.h>
#include "common/progress.h"

#define BAR_WIDTH 40

double srv_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void srv_progress_begin(srv_progress *p, const char *label, size_t total, int want)
{
    p->label = label;
    p->total = total ? total : 1;
    p->start = srv_now();
    p->enabled = !want ? 0 : isatty(STDERR_FILENO) ? 1 : 2;
    p->logged = p->start;
}

static void log_line(srv_progress *p, double f, double el, double eta)
{
    if (el - (p->logged - p->start) < SRV_PROGRESS_LOG_SECONDS)
        return;
    p->logged = p->start + el;
    fprintf(stderr, "%s: %.0f%% after %.0f s, about %.0f s left\n", p->label, 100.0 * f, el, eta);
}

void srv_progress_update(srv_progress *p, size_t done)
{
    if (!p->enabled)
        return;
    double f = (double)done / (double)p->total, el = srv_now() - p->start;
    double eta = done ? el * (1.0 / f - 1.0) : 0.0;
    if (p->enabled == 2) {
        log_line(p, f, el, eta);
        return;
    }
    int fill = (int)(f * BAR_WIDTH);
    char bar[BAR_WIDTH + 1];
    for (int i = 0; i < BAR_WIDTH; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[BAR_WIDTH] = 0;
    fprintf(stderr, "\r%s [%s] %5.1f%%  ETA %4.0fs ", p->label, bar, 100.0 * f, eta);
    fflush(stderr);
}

void srv_progress_end(srv_progress *p)
{
    if (p->enabled == 1)
        fprintf(stderr, "\r%*s\r", BAR_WIDTH + 40, "");
}
