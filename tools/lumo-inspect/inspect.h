/*
 * inspect.h — lumo-inspect's subcommands. Each lives in its own .c file in
 * tools/lumo-inspect/ (every one is linked by lumo-inspect.mk) and
 * registers itself with INSPECT_COMMAND. lumo-inspect runs the first
 * registered command whose flag appears among its arguments, else the
 * summary. Example, in tools/lumo-inspect/stream.c:
 *
 *   static int run_stream(int argc, char **argv) { ... return 0; }
 *   INSPECT_COMMAND(stream_cmd, "--stream", "--stream FILE.lumo  print the mesh stream", run_stream)
 */
#ifndef INSPECT_H
#define INSPECT_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/package.h"

typedef struct inspect_cmd {
    const char *flag;                    /* argument that selects it, e.g. "--ivg" */
    const char *usage;                   /* one line for --help */
    int (*run)(int argc, char **argv);   /* lumo-inspect's own argv; returns the exit status */
} inspect_cmd;

void inspect_register(const inspect_cmd *cmd);

#define INSPECT_COMMAND(var, flag_, usage_, run_)                              \
    static const inspect_cmd var = {flag_, usage_, run_};                      \
    __attribute__((constructor)) static void var##_register(void)              \
    {                                                                          \
        inspect_register(&var);                                                \
    }

/* Read a whole package file and open it (lumo_package_open). On failure
 * prints "lumo-inspect: error: FILE: reason" and returns -1. *data is
 * malloc'ed; free it after use. */
int inspect_load(const char *path, uint8_t **data, size_t *len, lumo_package *pkg);

/* The last argument that is not an option (the package path), or NULL. */
const char *inspect_file_arg(int argc, char **argv);

#endif
