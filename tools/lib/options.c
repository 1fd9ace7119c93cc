/*
 * options.c — see lumo_host/options.h. Integers are read digit by digit
 * into a uint64_t with an overflow test (strtoul would accept blanks, '+',
 * and wrap "-1" to ULONG_MAX); numbers through strtod, then checked whole
 * and finite. Every refusal is "OPT VALUE: why".
 */
#include "lumo_host/options.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The longest value shown whole in a message; longer ones are cut.
 * File names get more room. */
#define SHOWN_MAX 48
#define PATH_SHOWN_MAX 240

/* The value as the message shows it: verbatim when at most max bytes,
 * non-empty and printable; otherwise quoted, bytes outside printable ASCII
 * as \xNN and cut after max characters. */
static void show_value(const char *text, size_t max, char *out, size_t len)
{
    size_t i, o = 0;
    int plain = text[0] != 0 && strlen(text) <= max;

    for (i = 0; plain && text[i]; i++)
        plain = text[i] > ' ' && text[i] < 127 && text[i] != '\'';
    if (plain) {
        snprintf(out, len, "%s", text);
        return;
    }
    out[o++] = '\'';
    for (i = 0; text[i] && i < max && o + 6 < len; i++) {
        unsigned char c = (unsigned char)text[i];
        if (c >= ' ' && c < 127 && c != '\'' && c != '\\')
            out[o++] = (char)c;
        else
            o += (size_t)snprintf(out + o, len - o, "\\x%02x", c);
    }
    if (text[i] && o + 4 < len) {
        memcpy(out + o, "...", 3);
        o += 3;
    }
    out[o++] = '\'';
    out[o] = 0;
}

/* "OPT VALUE: why", always -1. */
__attribute__((format(printf, 5, 6))) static int refuse(const char *opt, const char *text, char *err,
                                                         size_t errlen, const char *why, ...)
{
    char shown[4 * SHOWN_MAX + 8], reason[160];
    va_list ap;

    va_start(ap, why);
    vsnprintf(reason, sizeof reason, why, ap);
    va_end(ap);
    show_value(text, SHOWN_MAX, shown, sizeof shown);
    if (errlen)
        snprintf(err, errlen, "%s %s: %s", opt, shown, reason);
    return -1;
}

/* Digits [s, end) as a magnitude; -1 when there are none, another byte
 * or the value passes UINT64_MAX. */
static int read_digits(const char *s, const char *end, uint64_t *out)
{
    uint64_t v = 0;

    if (s == end)
        return -1;
    for (; s < end; s++) {
        unsigned d = (unsigned)(*s - '0');
        if (d > 9)
            return -1;
        if (v > (UINT64_MAX - d) / 10)
            return -2;
        v = v * 10 + d;
    }
    *out = v;
    return 0;
}

/* An integer over [s, end): sign and magnitude. -1 not an integer, -2 too
 * large for 64 bits (out of any range a caller can ask). */
static int read_integer(const char *s, const char *end, int *neg, uint64_t *mag)
{
    *neg = s < end && *s == '-';
    return read_digits(s + *neg, end, mag);
}

/* Whether sign/magnitude lies in [lo, hi]. */
static int in_i64(int neg, uint64_t mag, int64_t lo, int64_t hi, int64_t *out)
{
    int64_t v;

    if (neg && mag > (uint64_t)INT64_MAX + 1)
        return 0;
    if (!neg && mag > (uint64_t)INT64_MAX)
        return 0;
    v = neg ? (mag == (uint64_t)INT64_MAX + 1 ? INT64_MIN : -(int64_t)mag) : (int64_t)mag;
    if (v < lo || v > hi)
        return 0;
    *out = v;
    return 1;
}

/* The integer in [s, end) in [lo, hi]; `what` names the part ("width")
 * or is NULL for the whole value. */
static int integer_part(const char *opt, const char *text, const char *s, const char *end, int64_t lo, int64_t hi,
                        const char *what, int64_t *out, char *err, size_t errlen)
{
    uint64_t mag = 0;
    int neg, rc = read_integer(s, end, &neg, &mag);

    if (rc == -1)
        return refuse(opt, text, err, errlen, "%s%snot an integer", what ? what : "", what ? " is " : "");
    if (rc == -2 || !in_i64(neg, mag, lo, hi, out))
        return refuse(opt, text, err, errlen, "%s%smust be %lld..%lld", what ? what : "", what ? " " : "",
                      (long long)lo, (long long)hi);
    return 0;
}

int host_opt_i64(const char *opt, const char *text, int64_t lo, int64_t hi, int64_t *out, char *err,
                 size_t errlen)
{
    return integer_part(opt, text, text, text + strlen(text), lo, hi, NULL, out, err, errlen);
}

int host_opt_int(const char *opt, const char *text, int lo, int hi, int *out, char *err, size_t errlen)
{
    int64_t v;

    if (host_opt_i64(opt, text, lo, hi, &v, err, errlen))
        return -1;
    *out = (int)v;
    return 0;
}

int host_opt_u32(const char *opt, const char *text, uint32_t lo, uint32_t hi, uint32_t *out, char *err,
                 size_t errlen)
{
    int64_t v;

    if (host_opt_i64(opt, text, lo, hi, &v, err, errlen))
        return -1;
    *out = (uint32_t)v;
    return 0;
}

int host_opt_u64(const char *opt, const char *text, uint64_t *out, char *err, size_t errlen)
{
    uint64_t v;
    int rc = read_digits(text, text + strlen(text), &v);

    if (rc == -2 || (rc == -1 && text[0] == '-' && read_digits(text + 1, text + strlen(text), &v) == 0))
        return refuse(opt, text, err, errlen, "must be 0..%llu", (unsigned long long)UINT64_MAX);
    if (rc)
        return refuse(opt, text, err, errlen, "not an integer");
    *out = v;
    return 0;
}

/* The number over [s, end): 0, or -1 with *why set. */
static int read_number(const char *s, const char *end, double *out, const char **why)
{
    char buf[128], *stop;
    size_t n = (size_t)(end - s);
    double v;

    *why = "not a number";
    if (n == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, s, n);
    buf[n] = 0;
    /* strtod skips leading blanks; a value with any is not taken whole. */
    if (buf[0] == ' ' || (buf[0] >= '\t' && buf[0] <= '\r'))
        return -1;
    errno = 0;
    v = strtod(buf, &stop);
    if (stop == buf || *stop)
        return -1;
    if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1.0)) {
        *why = "not a finite number";
        return -1;
    }
    *out = v;
    return 0;
}

/* The number over [s, end) in [lo, hi] (lo excluded when lo_open). */
static int number_part(const char *opt, const char *text, const char *s, const char *end, double lo, int lo_open,
                       double hi, double *out, char *err, size_t errlen)
{
    const char *why;
    double v;

    if (read_number(s, end, &v, &why))
        return refuse(opt, text, err, errlen, "%s", why);
    if (lo_open ? !(v > lo && v <= hi) : !(v >= lo && v <= hi))
        return lo_open ? refuse(opt, text, err, errlen, "must be above %g and at most %g", lo, hi)
                       : refuse(opt, text, err, errlen, "must be %g..%g", lo, hi);
    *out = v;
    return 0;
}

int host_opt_double(const char *opt, const char *text, double lo, double hi, double *out, char *err,
                    size_t errlen)
{
    return number_part(opt, text, text, text + strlen(text), lo, 0, hi, out, err, errlen);
}

int host_opt_positive(const char *opt, const char *text, double hi, double *out, char *err, size_t errlen)
{
    return number_part(opt, text, text, text + strlen(text), 0.0, 1, hi, out, err, errlen);
}

int host_opt_size(const char *opt, const char *text, uint32_t max_w, uint32_t max_h, uint32_t *w, uint32_t *h,
                  char *err, size_t errlen)
{
    const char *x = strchr(text, 'x'), *end = text + strlen(text);
    int64_t a, b;

    if (!x || strchr(x + 1, 'x'))
        return refuse(opt, text, err, errlen, "not WxH (e.g. 320x240)");
    if (integer_part(opt, text, text, x, 1, max_w, "width", &a, err, errlen) ||
        integer_part(opt, text, x + 1, end, 1, max_h, "height", &b, err, errlen))
        return -1;
    *w = (uint32_t)a;
    *h = (uint32_t)b;
    return 0;
}

/* Up to max numbers separated by commas; their count, or -1 (message
 * written) when a part is not a number in [lo, hi] or there are more. */
static int read_list(const char *opt, const char *text, double lo, double hi, double *out, int max, char *err,
                     size_t errlen)
{
    const char *s = text;
    int n = 0;

    for (;;) {
        const char *comma = strchr(s, ','), *end = comma ? comma : s + strlen(s);
        double v;
        char what[32];
        const char *why;
        if (n == max)
            return refuse(opt, text, err, errlen, "more than %d values", max);
        snprintf(what, sizeof what, "value %d", n + 1);
        if (read_number(s, end, &v, &why))
            return refuse(opt, text, err, errlen, "%s: %s", what, why);
        if (!(v >= lo && v <= hi))
            return refuse(opt, text, err, errlen, "%s must be %g..%g", what, lo, hi);
        out[n++] = v;
        if (!comma)
            return n;
        s = comma + 1;
    }
}

int host_opt_vec(const char *opt, const char *text, int n, double lo, double hi, double *out, char *err,
                 size_t errlen)
{
    double v[16];
    int got;

    if (n < 1 || n > 16)
        return refuse(opt, text, err, errlen, "internal: %d values asked", n);
    got = read_list(opt, text, lo, hi, v, n, err, errlen);
    if (got < 0)
        return -1;
    if (got != n)
        return refuse(opt, text, err, errlen, "%d values separated by commas wanted, %d given", n, got);
    memcpy(out, v, sizeof *v * (size_t)n);
    return 0;
}

int host_opt_list(const char *opt, const char *text, double lo, double hi, int increasing, double *out, int max,
                  int *n, char *err, size_t errlen)
{
    double v[256];
    int got, i;

    if (max < 1 || max > 256)
        return refuse(opt, text, err, errlen, "internal: %d values asked", max);
    got = read_list(opt, text, lo, hi, v, max, err, errlen);
    if (got < 0)
        return -1;
    for (i = 1; increasing && i < got; i++)
        if (!(v[i] > v[i - 1]))
            return refuse(opt, text, err, errlen, "values must increase (value %d is %g after %g)", i + 1, v[i],
                          v[i - 1]);
    memcpy(out, v, sizeof *v * (size_t)got);
    *n = got;
    return 0;
}

int host_opt_choice(const char *opt, const char *text, const char *const *names, int count, int *out, char *err,
                    size_t errlen)
{
    char list[256];
    size_t o = 0;
    int i;

    for (i = 0; i < count; i++)
        if (!strcmp(text, names[i])) {
            *out = i;
            return 0;
        }
    list[0] = 0;
    for (i = 0; i < count && o < sizeof list; i++)
        o += (size_t)snprintf(list + o, sizeof list - o, "%s%s", i ? ", " : "", names[i]);
    return refuse(opt, text, err, errlen, "must be one of %s", list);
}

int host_getopt(int argc, char *const argv[], const char *shorts, const struct option *longs)
{
    int idx = -1, c = getopt_long(argc, argv, shorts, longs, &idx);
    if (c == -1 || c == '?' || c == ':' || idx < 0)
        return c;
    int at = optind - 1;   /* the word that named the option */
    if (optarg && at > 0 && argv[at] == optarg)
        at--;
    const char *w = argv[at];
    size_t len = strlen(longs[idx].name);
    if (w[0] == '-' && w[1] == '-' && (strncmp(w + 2, longs[idx].name, len) || (w[2 + len] && w[2 + len] != '='))) {
        optind = at + 1;
        optopt = 0;
        return '?';
    }
    return c;
}

int host_opt_getopt_error(int c, const char *arg, int optopt_, char *err, size_t errlen)
{
    char shown[4 * SHOWN_MAX + 8], opt[8];

    /* getopt_long sets optopt to a long option's value too ("--help=3"
     * gives 'h'): the word typed names it better. */
    if (optopt_ > ' ' && optopt_ < 127 && !(arg && arg[0] == '-' && arg[1] == '-')) {
        snprintf(opt, sizeof opt, "-%c", optopt_);
        arg = opt;
    }
    show_value(arg ? arg : "", SHOWN_MAX, shown, sizeof shown);
    if (c == ':')
        snprintf(err, errlen, "%s needs a value (try --help)", shown);
    else if (strchr(shown, '='))
        snprintf(err, errlen, "%s: unknown option, or one that takes no value (try --help)", shown);
    else
        snprintf(err, errlen, "%s: unknown option (try --help)", shown);
    return -1;
}

int host_opt_file(const char *opt, const char *path, const char *kind, char *err, size_t errlen)
{
    struct stat st;
    const char *o = opt ? opt : "", *sep = opt ? " " : "";
    char shown[4 * PATH_SHOWN_MAX + 8];

    show_value(path, PATH_SHOWN_MAX, shown, sizeof shown);
    if (stat(path, &st) || access(path, R_OK))
        snprintf(err, errlen, "%s%s%s: cannot read: %s", o, sep, shown, strerror(errno));
    else if (S_ISDIR(st.st_mode))
        snprintf(err, errlen, "%s%s%s: a directory, not a %s", o, sep, shown, kind);
    else if (!S_ISREG(st.st_mode))
        snprintf(err, errlen, "%s%s%s: not a regular file (a %s is read whole)", o, sep, shown, kind);
    else if (st.st_size == 0)
        snprintf(err, errlen, "%s%s%s: empty file, not a %s", o, sep, shown, kind);
    else
        return 0;
    return -1;
}
