/*
 * serve/index.h — a .lumo package as lumo-server serves it
 * (docs/protocol.md, docs/server.md "lumo-server").
 *
 * The file is mapped once, read-only, and shared by every client: every
 * DATA frame's bytes are sent straight from the mapping (zero copy). Opening
 * validates the whole package with lumo_package_open (every chunk's CRC),
 * every progressive stream's header and record walk, and the IVG's round
 * table, then builds what a request needs in O(1) or O(log n):
 *
 *  - per mesh: its PMSH chunk, the stream header (base and batch vertex
 *    counts) and the byte offset of every batch record;
 *  - the IVG: the round table (first record and byte offset of every round
 *    in each form's bundle) and the records of IVGQ and IVGF;
 *  - the WELCOME frame (docs/protocol.md §2), encoded once and sent to every
 *    client of the package as it is.
 */
#ifndef SRV_SERVE_INDEX_H
#define SRV_SERVE_INDEX_H

#include <stddef.h>
#include <stdint.h>
#include "lumo/net.h"
#include "lumo/package.h"
#include "lumo/pmesh.h"
#include "lumo/status.h"

/* Bytes of a bundle's header before its records (docs/ivg-format.md §2.1). */
#define SRV_IVG_BUNDLE_HEAD 16u

typedef struct srv_mesh_index {
    const uint8_t    *stream;   /* the PMSH chunk's payload, in the mapping */
    uint32_t          len;
    lumo_pmesh_header h;
    uint32_t         *rec;      /* batch_count + 1 offsets into stream: record b
                                   is stream[rec[b] .. rec[b + 1]) */
    uint32_t          max_record;
    /* PRT (docs/protocol.md §10): the mesh's PRTV chunk, NULL without */
    const uint8_t    *prt;
    uint32_t          prt_len;     /* the whole chunk */
    uint32_t          prt_fixed;   /* header, clusters and pass table */
    uint32_t          prt_cbytes;  /* one cluster record */
    uint32_t          prt_vbytes;  /* one vertex record */
} srv_mesh_index;

/* The stratified lighting order (docs/protocol.md §4, the package's IVGS):
 * round r holds records first[r] .. first[r + 1] - 1 of both bundles, bytes
 * off[f][r] .. off[f][r + 1] - 1 of form f's bundle payload (f:
 * LUMO_IVG_FORM_FLOAT = 0 is IVGF, LUMO_IVG_FORM_QUANTIZED = 1 is IVGQ;
 * off[f][0] is SRV_IVG_BUNDLE_HEAD, the records start after the header). */
typedef struct srv_ivg_index {
    int            present;
    uint32_t       rounds, records;
    uint32_t      *first;       /* rounds + 1 */
    uint32_t      *off[2];      /* rounds + 1 each, into bundle[f] */
    const uint8_t *bundle[2];   /* the IVGF and IVGQ payloads, in the mapping */
    uint32_t       bundle_len[2];
} srv_ivg_index;

typedef struct srv_pkg {
    char           *path;
    const char     *name;       /* the path's last component, for logs */
    const uint8_t  *map;        /* the whole file, PROT_READ */
    size_t          size;
    lumo_package    pkg;
    uint32_t        id;         /* the package header's CRC field (bytes 20..23) */
    uint32_t        mesh_count;
    srv_mesh_index *mesh;
    srv_ivg_index   ivg;
    uint32_t        arena_need; /* what WELCOME states */
    uint8_t        *welcome;    /* the whole WELCOME frame */
    size_t          welcome_len;
    /* PRT (§10): for a HELLO with LUMO_NET_FLAG_PRT, the WELCOME with each
     * mesh's PRTV header and the PRTL, and its arena need; has_prt is 0
     * (and these the plain ones) for a package without PRTV chunks. */
    int             has_prt;
    uint32_t        arena_need_prt;
    uint8_t        *welcome_prt;
    size_t          welcome_prt_len;
} srv_pkg;

/* Map, validate and index the package at path. LUMO_ERR_IO (cannot open or
 * map), the SDK reader's status for a damaged or foreign file (a version-1
 * package is LUMO_ERR_VERSION: "re-bake it"), a bad IVG order (IVGS), LUMO_ERR_UNSUPPORTED (raw
 * meshes only: nothing to stream), LUMO_ERR_NOMEM; a message naming the
 * path in err. *p is zeroed on failure. */
lumo_status srv_pkg_open(srv_pkg *p, const char *path, char *err, size_t errlen);
void srv_pkg_close(srv_pkg *p);

/* The WELCOME frame of docs/protocol.md §2 from its descriptors (INFO, each
 * stream's header, IVGD, IVGS, ORDR, in that order): p->welcome
 * (allocated), p->welcome_len and p->arena_need (every descriptor's
 * lumo_session_message_need plus LUMO_ARENA_SLACK). p->id and p->path are
 * read. Also what lumo-client --http (tools/lumo-client/link_http.c) builds
 * from descriptors fetched with Range requests. */
lumo_status srv_welcome_build(srv_pkg *p, const lumo_net_msg *msgs, uint32_t count, char *err, size_t errlen);


#endif
