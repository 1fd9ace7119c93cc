/*
 * version_line.h — `--version` for every desktop program: one line with the
 * SDK's version and the formats it speaks (lumo/version.h, lumo/net.h).
 */
#ifndef HOST_VERSION_LINE_H
#define HOST_VERSION_LINE_H

/* When argv[1] is "--version": print "PROG lumo X.Y.Z (package format A.B,
 * progressive mesh N, IVG bundle N, protocol N)" on stdout and return 1
 * (the caller exits 0); else 0 and nothing printed. */
int host_version_option(int argc, char **argv, const char *prog);

#endif
