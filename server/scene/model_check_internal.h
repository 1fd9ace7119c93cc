/*
 * model_check_internal.h — what the model checks of each format share
 * (model_check.c: OBJ, PLY, OFF and the entry points; stl_check.c;
 * gltf_check.c). Not for callers outside server/scene: they use
 * model_check.h.
 */
#ifndef SRV_MODEL_CHECK_INTERNAL_H
#define SRV_MODEL_CHECK_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/status.h"

/* What every check carries: the bytes, where it is, where to say why. */
typedef struct srv_mc {
    const char    *name;      /* the file as the user named it; its directory resolves what it names */
    const uint8_t *base;      /* the file's first byte */
    const uint8_t *p, *end;   /* the unread rest */
    uint32_t       line;      /* of the last line taken (text formats) */
    char          *err;
    size_t         errlen;
} srv_mc;

/* "NAME: why" into c->err; returns st. */
lumo_status srv_mc_fail(srv_mc *c, lumo_status st, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* [p, end) holds no NUL and no control byte but tab, CR, LF, FF, VT. */
lumo_status srv_mc_check_text(srv_mc *c, const uint8_t *p, const uint8_t *end);

/* Why a coordinate cannot be used (not finite, beyond SRV_MODEL_MAX_COORD),
 * or NULL; and the status that goes with it. */
const char *srv_mc_coord_problem(double v);
lumo_status srv_mc_coord_status(double v);

/* STL, ASCII or binary (stl_check.c). */
lumo_status srv_mc_check_stl(srv_mc *c);
/* glTF 2.0: JSON (glb 0) or binary container (glb 1) (gltf_check.c). */
lumo_status srv_mc_check_gltf(srv_mc *c, int glb);

#endif
