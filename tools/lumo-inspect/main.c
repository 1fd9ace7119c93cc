/* tools/lumo-inspect/main.c — lumo-inspect: dispatch to the registered subcommands
 * (inspect.h), the package summary by default. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo_host/file_io.h"
#include "lumo_host/options.h"
#include "lumo_host/package_msg.h"
#include "inspect.h"

#define MAX_COMMANDS 16

static const inspect_cmd *g_cmds[MAX_COMMANDS];
static int g_ncmds;

void inspect_register(const inspect_cmd *cmd)
{
    if (g_ncmds < MAX_COMMANDS)
        g_cmds[g_ncmds++] = cmd;
}

int inspect_load(const char *path, uint8_t **data, size_t *len, lumo_package *pkg)
{
    char err[600] = "";
    *data = NULL;
    if (host_opt_file(NULL, path, "package", err, sizeof err) || !(*data = host_read_file(path, len))) {
        fprintf(stderr, "lumo-inspect: error: %s\n", err[0] ? err : "cannot read");
        return -1;
    }
    lumo_status st = lumo_package_open(pkg, *data, *len);
    if (st) {
        char why[160];
        fprintf(stderr, "lumo-inspect: error: %s: %s\n", path, host_package_strerror(*data, *len, st, why, sizeof why));
        free(*data);
        *data = NULL;
        return -1;
    }
    return 0;
}

const char *inspect_file_arg(int argc, char **argv)
{
    return argc > 1 && argv[argc - 1][0] != '-' ? argv[argc - 1] : NULL;
}

int inspect_summary(int argc, char **argv);

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: lumo-inspect FILE.lumo            summary of a package\n");
            for (int c = 0; c < g_ncmds; c++)
                printf("       lumo-inspect %s\n", g_cmds[c]->usage);
            printf("Package format: docs/package-format.md\n");
            return 0;
        }
    for (int i = 1; i < argc; i++)
        for (int c = 0; c < g_ncmds; c++)
            if (!strcmp(argv[i], g_cmds[c]->flag))
                return g_cmds[c]->run(argc, argv);
    for (int i = 1; i < argc; i++)
        if (argv[i][0] == '-') {
            fprintf(stderr, "lumo-inspect: error: unknown option '%s' (try --help)\n", argv[i]);
            return 1;
        }
    return inspect_summary(argc, argv);
}
