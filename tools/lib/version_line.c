/*
 * version_line.c — see version_line.h. The numbers come from the linked
 * library (lumo_version_string, lumo_version_formats_get) and the codec's
 * header, so a tool reports what it was built with.
 */
#include <stdio.h>
#include <string.h>
#include "lumo/net.h"
#include "lumo/version.h"
#include "lumo_host/version_line.h"

int host_version_option(int argc, char **argv, const char *prog)
{
    lumo_version_formats f;

    if (argc < 2 || strcmp(argv[1], "--version"))
        return 0;
    lumo_version_formats_get(&f);
    printf("%s lumo %s (package format %u.%u, progressive mesh %u, IVG bundle %u, protocol %u)\n", prog,
           lumo_version_string(), f.package_major, f.package_minor, f.pmesh, f.ivg_bundle,
           (unsigned)LUMO_NET_VERSION);
    return 1;
}
