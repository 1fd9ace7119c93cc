/* progress.h — a progress bar with ETA on stderr, drawn only when stderr is
 * a terminal; the one-line summary is the caller's. */
#ifndef SRV_PROGRESS_H
#define SRV_PROGRESS_H

#include <stddef.h>

typedef struct srv_progress {
    const char *label;
    size_t total;
    double start;
    int    enabled;
} srv_progress;

double srv_now(void);    /* monotonic seconds */
void srv_progress_begin(srv_progress *p, const char *label, size_t total, int want);
void srv_progress_update(srv_progress *p, size_t done);
void srv_progress_end(srv_progress *p);

#endif
