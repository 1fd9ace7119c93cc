/* progress.h — a progress bar with ETA on stderr, drawn only when stderr is
 * a terminal; the one-line summary is the caller's. */
#ifndef LUMO_SERVER_PROGRESS_H
#define LUMO_SERVER_PROGRESS_H

#include <stddef.h>

typedef struct lumo_progress {
    const char *label;
    size_t total;
    double start;
    int    enabled;
} lumo_progress;

double lumo_now(void);   /* monotonic seconds */
void lumo_progress_begin(lumo_progress *p, const char *label, size_t total, int want);
void lumo_progress_update(lumo_progress *p, size_t done);
void lumo_progress_end(lumo_progress *p);

#endif
