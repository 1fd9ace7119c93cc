/*
 * lumo/config.h — every tunable limit of lumo in one place (as Lua's
 * luaconf.h). Each can be overridden on the compiler's command line
 * (-DLUMO_MAX_LIGHTS=8); the cost of each is stated. Every layer uses the
 * same macro: the server refuses to write what the client would refuse to
 * read, the package reader and the session refuse what the rasterizer could
 * not draw, so nothing is ever dropped silently between layers.
 */
#ifndef LUMO_CONFIG_H
#define LUMO_CONFIG_H

/* Lights of one scene: the server refuses a scene with more, the package's
 * INFO chunk holds at most this many, the client session's light table and
 * one frame of the rasterizer (soft and GL: the GL shaders size their
 * uniform arrays with it; 16 keeps them inside GLES 3.0's guaranteed 224
 * fragment uniform vectors). Cost: the session holds a lumo_pkg_light (88
 * bytes) per light; the rasterizer's per-vertex or per-pixel loop runs over
 * every light. */
#ifndef LUMO_MAX_LIGHTS
#define LUMO_MAX_LIGHTS 16
#endif

/* Meshes of one scene held by a client session. Cost: about 40 bytes of
 * session struct per mesh, plus each mesh's arena share. */
#ifndef LUMO_MAX_MESHES
#define LUMO_MAX_MESHES 64
#endif

/* Chunks of one package (docs/package-format.md). Cost: opening a package
 * walks the table once. */
#ifndef LUMO_MAX_CHUNKS
#define LUMO_MAX_CHUNKS 256
#endif

/* Largest frame the rasterizer draws, per axis. It bounds the edge-function
 * ranges (docs/rasterizer.md, "ranges"): raising it needs that analysis
 * redone, not only this number. */
#ifndef LUMO_MAX_FRAME_DIM
#define LUMO_MAX_FRAME_DIM 2048
#endif

/* PRT (lumo/prt.h, docs/prt.md): clusters and principal components of a
 * PRTV chunk. Cost: the per-frame table lumo_prt_frame fills holds
 * 12 * clusters * (components + 1) bytes (64 clusters, 8 components:
 * 6.9 KiB), and its computation is clusters * (components + 1) * 3 dot
 * products of order^2 terms. */
#ifndef LUMO_PRT_MAX_CLUSTERS
#define LUMO_PRT_MAX_CLUSTERS 4096
#endif
#ifndef LUMO_PRT_MAX_COMPONENTS
#define LUMO_PRT_MAX_COMPONENTS 36   /* order 6's 36 coefficients: all of them */
#endif

#endif /* LUMO_CONFIG_H */
