/* tools/lumo-server/dynamic.h — lumo-server --dynamic (dynamic.c,
 * docs/dynamic.md). */
#ifndef LUMO_SERVER_DYNAMIC_H
#define LUMO_SERVER_DYNAMIC_H

#include <stddef.h>
#include "serve/index.h"
#include "serve/server.h"

/* Start the lighting engine from spec "SCENE_FILE[,key=value...]" on pkg's
 * IVG grid and point opt->updates at its log. NULL with a reason. */
struct dynamic *dynamic_start(const char *spec, const srv_pkg *pkg, srv_serve_options *opt, char *err,
                              size_t errlen);
/* Stop it, print the latency summary, free (NULL: nothing). */
void dynamic_stop(struct dynamic *d);

#endif
