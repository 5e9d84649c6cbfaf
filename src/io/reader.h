/* SPDX-License-Identifier: MIT */
/* What the mesh-file readers share (io/meshfile.c holds the reader and the text formats,
 * io/gltf.c glTF, io/threemf.c 3MF): the context of one read, its messages and the mesh being built. */
#ifndef TTD_IO_READER_H
#define TTD_IO_READER_H

#include <stddef.h>
#include <stdint.h>

typedef unsigned char uchar;

typedef struct ctx {
    const char *name;
    const char *dir;   /* the file's folder for a glTF's external buffers; NULL: from memory */
    char *err;
    size_t errsize;
    int want_float;
    double *v;
    float *vf;
    size_t nv, cap_v;
    uint32_t *t;
    size_t nt, cap_t;
    uint32_t *merge;   /* STL only: open-addressing table of vertex indices, UINT32_MAX empty */
    size_t merge_mask; /* table size - 1 */
    int strict;        /* TTD_MESHFILE_STRICT */
    size_t skipped, first_skipped; /* OBJ: lines that are not statements, and the first's number */
    char why[96];      /* appended to every message: why the format was assumed, or "" */
} ctx;

/// "NAME: message" in the context's err; returns -1.
int ttd_io_fail(ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/// "NAME: byte OFFSET: message"; returns -1.
int ttd_io_fail_at(ctx *c, size_t off, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/// Appends a vertex (x: 3 doubles; f: 3 floats, read when want_float); 0 or -1 (message set).
int ttd_io_push_v(ctx *c, const double *x, const float *f);
/// Appends a triangle; 0 or -1 (message set).
int ttd_io_push_t(ctx *c, uint32_t a, uint32_t b, uint32_t d);
/// The out-of-memory message; returns -1.
int ttd_io_oom(ctx *c);

/// glTF 2.0: a GLB container (glb != 0) or a .gltf JSON text (io/gltf.c).
int ttd_io_parse_gltf(ctx *c, const uchar *data, size_t size, int glb);

/// 3MF: a zip archive holding a 3D model part (io/threemf.c).
int ttd_io_parse_3mf(ctx *c, const uchar *data, size_t size);

#endif
