/*
 * lumo/status.h — the one error enum of the lumo client SDK.
 *
 * Every SDK function that can fail returns a lumo_status. LUMO_OK is zero, so
 * `if (st) return st;` propagates errors. A function that fails leaves every
 * object it was given exactly as it was before the call (no partial updates),
 * unless its documentation says otherwise.
 */
#ifndef LUMO_STATUS_H
#define LUMO_STATUS_H

/* What went wrong; LUMO_OK (0) when nothing did. */
typedef enum lumo_status {
    LUMO_OK = 0,           /* success */
    LUMO_ERR_ARG,          /* a NULL pointer or a nonsensical argument */
    LUMO_ERR_NOMEM,        /* the caller-given arena is too small */
    LUMO_ERR_TRUNCATED,    /* input ended before the structure it announced */
    LUMO_ERR_CORRUPT,      /* input is structurally invalid */
    LUMO_ERR_RANGE,        /* a value or index is outside its allowed range */
    LUMO_ERR_NONFINITE,    /* an IEEE-754 NaN or infinity where a number was due */
    LUMO_ERR_UNSUPPORTED,  /* valid input using a feature lumo does not decode */
    LUMO_ERR_CHECKSUM,     /* a checksum did not match */
    LUMO_ERR_VERSION,      /* unknown format or protocol version */
    LUMO_ERR_STATE,        /* call not valid in the object's current state */
    LUMO_ERR_OVERFLOW,     /* a size or count computation would overflow */
    LUMO_ERR_IO,           /* a transport or file operation failed */
    LUMO_ERR_LIMIT,        /* input exceeds a configured work or size limit */
    LUMO_STATUS_COUNT      /* the number of codes (not a status) */
} lumo_status;

/* A short, static, human-readable description ("arena too small", ...).
 * Never NULL; unknown codes give "unknown error". */
const char *lumo_strerror(lumo_status st);

#endif /* LUMO_STATUS_H */
