/*
 * options.h — the one strict parser of command-line values for every
 * desktop tool (lumo-render, lumo-bake, lumo-pm, lumo-inspect, lumo-server,
 * lumo-client, lumo-compare, lumo-draco-decode, the benchmarks): integers
 * with range checks that never wrap, finite floating-point numbers, sizes
 * WxH, vectors "x,y,z", lists and named choices (docs/tools.md, "Options").
 *
 * Every command-line byte is hostile (issue 24): a value is taken whole or
 * refused. Each function returns 0 with the value stored, or -1 with the
 * output untouched and one line in err (at most errlen bytes, always
 * terminated) naming the option, the value and why, e.g.
 *
 *   --size 4294967312x16: width must be 1..4096
 *   --max-mean-de nan: not a finite number
 *
 * The tool prefixes its own name ("lumo-render: error: "). `opt` is the
 * option as the user typed it ("--size"); a value that is empty, long or
 * holds unprintable bytes is quoted and escaped in the message, so the
 * line stays one line. No function allocates; all are reentrant.
 *
 * Syntax accepted (nothing else, no leading or trailing blanks):
 *  - integer: an optional '-' and decimal digits ("007" is 7);
 *  - number: what strtod reads in the C locale ("1", "-2.5", "1e-3",
 *    "0x1p4"), finite: "nan", "inf", "1e999" are refused;
 *  - size: integer 'x' integer ("320x240");
 *  - vector, list: numbers separated by single commas ("0,1,0").
 */
#ifndef HOST_OPTIONS_H
#define HOST_OPTIONS_H

#include <getopt.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {   /* the C++ benchmarks (bench/draco_bench_libdraco.cc) parse their numbers here too */
#endif

/* Integers in [lo, hi] (inclusive). */
int host_opt_i64(const char *opt, const char *text, int64_t lo, int64_t hi, int64_t *out, char *err,
                 size_t errlen);
int host_opt_int(const char *opt, const char *text, int lo, int hi, int *out, char *err, size_t errlen);
int host_opt_u32(const char *opt, const char *text, uint32_t lo, uint32_t hi, uint32_t *out, char *err,
                 size_t errlen);
/* Any integer 0..UINT64_MAX (random seeds). */
int host_opt_u64(const char *opt, const char *text, uint64_t *out, char *err, size_t errlen);

/* A finite number in [lo, hi]. */
int host_opt_double(const char *opt, const char *text, double lo, double hi, double *out, char *err,
                    size_t errlen);
/* A finite number in (0, hi]: spacings, rates, scales that must not be 0. */
int host_opt_positive(const char *opt, const char *text, double hi, double *out, char *err, size_t errlen);

/* "WxH", each side 1..max_w and 1..max_h. */
int host_opt_size(const char *opt, const char *text, uint32_t max_w, uint32_t max_h, uint32_t *w, uint32_t *h,
                  char *err, size_t errlen);

/* Exactly n numbers "a,b,c", each finite and in [lo, hi]. */
int host_opt_vec(const char *opt, const char *text, int n, double lo, double hi, double *out, char *err,
                 size_t errlen);

/* 1..max numbers "a,b,...", each in [lo, hi]; `increasing`: each above
 * the one before. The count goes to *n. */
int host_opt_list(const char *opt, const char *text, double lo, double hi, int increasing, double *out, int max,
                  int *n, char *err, size_t errlen);

/* One of `count` names; *out is its index ("--mesh pmx: must be one of
 * pm, raw, both"). */
int host_opt_choice(const char *opt, const char *text, const char *const *names, int count, int *out, char *err,
                    size_t errlen);

/* A file the user named, before any reader sees it: it must exist, be a
 * regular file (not a directory, pipe or device), be readable and hold at
 * least one byte. `opt` is the option that named it, or NULL for a
 * positional argument; `kind` says what the tool wanted ("model file"):
 *   --model /tmp/m: a directory, not a model file
 *   scene.txt: cannot read: No such file or directory */
int host_opt_file(const char *opt, const char *path, const char *kind, char *err, size_t errlen);

/* getopt_long without abbreviations: a long option is taken only when
 * typed whole ("--port 7791" is refused, not read as --port-file), because
 * a prefix that happens to be unique does something the user did not ask
 * for. An abbreviation is returned as '?' with optind set so that
 * argv[optind - 1] is the word typed, as host_opt_getopt_error wants it. */
int host_getopt(int argc, char *const argv[], const char *shorts, const struct option *longs);

/* The line for an option getopt_long refused (opterr = 0 and an optstring
 * starting with ':'): c is what getopt_long returned (':' for a missing
 * value, '?' otherwise), `arg` the word it stopped at (argv[optind - 1]),
 * optopt_ the short option it names (0 for long ones). Always -1. */
int host_opt_getopt_error(int c, const char *arg, int optopt_, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
