/* progress.h — a progress bar with ETA on stderr when stderr is a
 * terminal; otherwise (a log, a pipe) one line "LABEL: 40% after 12 s,
 * about 18 s left" at most every SRV_PROGRESS_LOG_SECONDS, so a long job
 * says where it is wherever its stderr goes. The one-line summary is the
 * caller's. */
#ifndef SRV_PROGRESS_H
#define SRV_PROGRESS_H

#include <stddef.h>

typedef struct srv_progress {
    const char *label;
    size_t total;
    double start;
    int    enabled;   /* 0 off, 1 bar (terminal), 2 log lines */
    double logged;    /* when the last log line was written */
} srv_progress;

#define SRV_PROGRESS_LOG_SECONDS 10.0

double srv_now(void);    /* monotonic seconds */
void srv_progress_begin(srv_progress *p, const char *label, size_t total, int want);
void srv_progress_update(srv_progress *p, size_t done);
void srv_progress_end(srv_progress *p);

#endif
