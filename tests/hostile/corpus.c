/*
 * corpus.c — the hostile corpus's files and manifest (corpus.h).
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lumo/wire.h"
#include "corpus.h"

static const char *g_dir, *g_tool;
static FILE *g_manifest;
static unsigned g_count;

int corpus_open(const char *dir, const char *mode, const char *tool)
{
    g_dir = dir, g_tool = tool, g_count = 0;
    if (!(g_manifest = fopen(corpus_path("manifest"), mode))) {
        fprintf(stderr, "%s: cannot write %s\n", tool, corpus_path("manifest"));
        return -1;
    }
    return 0;
}

unsigned corpus_close(void)
{
    if (fclose(g_manifest)) {
        fprintf(stderr, "%s: cannot write %s\n", g_tool, corpus_path("manifest"));
        exit(1);
    }
    fprintf(stderr, "%s: %u cases in %s\n", g_tool, g_count, g_dir);
    return g_count;
}

const char *corpus_path(const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", g_dir, name);
    return path;
}

void corpus_put(const char *kind, const char *name, const void *bytes, size_t n, const char *expect)
{
    const char *path = corpus_path(name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(bytes, 1, n, f) != n || fclose(f)) {
        fprintf(stderr, "%s: cannot write %s\n", g_tool, path);
        exit(1);
    }
    if (kind)
        corpus_note(kind, name, expect);
}

void corpus_note(const char *kind, const char *name, const char *expect)
{
    fprintf(g_manifest, "%s\t%s\t%s\n", kind, corpus_path(name), expect);
    g_count++;
}

void corpus_text(const char *kind, const char *name, const char *expect, const char *fmt, ...)
{
    static char buf[1 << 16];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= sizeof buf) {
        fprintf(stderr, "%s: case %s is longer than %zu bytes\n", g_tool, name, sizeof buf - 1);
        exit(1);
    }
    corpus_put(kind, name, buf, (size_t)n, expect);
}

void corpus_put_f32(uint8_t *p, float f)
{
    uint32_t w;
    memcpy(&w, &f, 4);
    lumo_wire_put_le32(p, w);
}
