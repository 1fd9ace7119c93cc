/*
 * corpus.h — writing the hostile corpus of tests/hostile (gen_hostile.c,
 * gen_formats.c): each case a file in the corpus directory and a line
 * "KIND<TAB>FILE<TAB>EXPECTED" in its manifest (hostile.sh runs every file
 * through the tools that read its KIND and looks for EXPECTED in the
 * refusal; "OK" for a file that must be accepted). A failed write ends the
 * program: a corpus with a case missing would test less than it says.
 */
#ifndef LUMO_TESTS_CORPUS_H
#define LUMO_TESTS_CORPUS_H

#include <stddef.h>
#include <stdint.h>

/* Open DIR/manifest, fresh ("w") or appended to ("a"); `tool` names the
 * generator in messages. 0, or -1 with a message on stderr. */
int corpus_open(const char *dir, const char *mode, const char *tool);
/* The manifest closed; the number of cases written, said on stderr. */
unsigned corpus_close(void);
/* DIR/name holding n bytes; a manifest line when kind is not NULL (NULL:
 * a file other cases refer to). */
void corpus_put(const char *kind, const char *name, const void *bytes, size_t n, const char *expect);
/* A text case from a printf format (at most 64 KiB). */
void corpus_text(const char *kind, const char *name, const char *expect, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* DIR/name as a path (for files a generator writes itself), and the
 * manifest line of such a file. */
const char *corpus_path(const char *name);
void corpus_note(const char *kind, const char *name, const char *expect);
/* A little-endian IEEE binary32 at p. */
void corpus_put_f32(uint8_t *p, float f);

#endif
