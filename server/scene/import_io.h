/*
 * import_io.h — the only way assimp reaches the file system from lumo
 * (server/scene/import.c): regular files, opened read-only and without
 * blocking, of at most SRV_MODEL_MAX_BYTES each. A model names other files
 * (an OBJ's mtllib, a glTF's buffers and images) and assimp reads each to
 * its end: a FIFO or a device there blocked the importer forever or fed it
 * without end. What is refused looks to assimp like a missing file.
 */
#ifndef SRV_IMPORT_IO_H
#define SRV_IMPORT_IO_H

struct aiFileIO;

/* The file system assimp gets (static; valid for the program's life). */
struct aiFileIO *srv_import_io(void);

#endif
