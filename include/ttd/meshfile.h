/* SPDX-License-Identifier: MIT */
/* Reading triangle meshes from files: OBJ, STL (ASCII and binary), PLY (ASCII, binary
 * little- and big-endian), OFF, glTF 2.0 (GLB, and .gltf with its buffers) and 3MF into one indexed mesh, the public reader of the library that `ttd mesh`,
 * `ttd scene` and the Python package use. The
 * format is recognised by content, never by the file name; docs/mesh-files.md has the rules
 * (what is accepted, merged, skipped, and the error messages).
 *
 * One read gives double coordinates always and, when asked, float coordinates that are
 * correctly rounded from the file's text (strtof on the token, not double then float) or exact
 * from binary float32 (binary double: rounded once to float).
 *
 * Triangles: 0-based indices in file order, polygons fan-triangulated (v0 v1 v2), (v0 v2 v3),
 * .... Every index is below nv; nv and nt are at least 1 on success.
 *
 * Errors: -1 and a message "NAME:LINE: problem" (text) or "NAME: byte OFFSET: problem"
 * (binary) or "NAME: problem" in err; *out is then empty (ttd_meshfile_free on it is
 * harmless). No input makes the reader crash, hang or read outside the buffer; counts larger
 * than the file can hold are refused before anything of that size is allocated. Numbers are
 * read with strtod/strtof, so the C locale (the default of a program that never calls
 * setlocale) is assumed. */
#ifndef TTD_MESHFILE_H
#define TTD_MESHFILE_H

#include <stddef.h>
#include <stdint.h>

#include "ttd/ttd.h" /* TTD_API */

#ifdef __cplusplus
extern "C" {
#endif

/// The format a mesh was read as.
typedef enum ttd_meshfile_format {
    TTD_MESHFILE_OBJ = 0,
    TTD_MESHFILE_STL_ASCII,
    TTD_MESHFILE_STL_BINARY,
    TTD_MESHFILE_PLY_ASCII,
    TTD_MESHFILE_PLY_BINARY,
    TTD_MESHFILE_OFF,  ///< OFF text ([ST][C][N]OFF)
    TTD_MESHFILE_GLB,  ///< binary glTF 2.0
    TTD_MESHFILE_GLTF, ///< glTF 2.0 JSON, its buffers data: URIs or files beside it
    TTD_MESHFILE_3MF,  ///< 3MF: a zip archive of an XML model
    TTD_MESHFILE_FORMAT_COUNT
} ttd_meshfile_format;

/// Flags of ttd_meshfile_read / ttd_meshfile_parse (bits; 0 for none).
enum {
    TTD_MESHFILE_FLOAT = 1,  ///< also fill verts_f
    TTD_MESHFILE_STRICT = 2  ///< refuse OBJ lines that are not statements instead of skipping them
};

/// An indexed mesh read from a file.
typedef struct ttd_meshfile {
    double *verts;              ///< 3 nv coordinates (x y z per vertex)
    float *verts_f;             ///< 3 nv float coordinates when asked for, else NULL
    size_t nv;
    uint32_t *tris;             ///< 3 nt vertex indices, each below nv
    size_t nt;
    ttd_meshfile_format format; ///< what the content was recognised as
    size_t skipped_lines;       ///< OBJ: lines that are not OBJ statements (not starting with a
                                ///< keyword, such as FCL's "6540 2180"), skipped; 0 otherwise
    size_t first_skipped_line;  ///< the first of them (1-based), when skipped_lines > 0
} ttd_meshfile;

/// Reads the file at path ("-": standard input, named "<stdin>" in messages). flags:
/// TTD_MESHFILE_FLOAT also fills verts_f; TTD_MESHFILE_STRICT refuses an OBJ line that is not
/// a statement (it is skipped and counted in skipped_lines otherwise). Returns 0, or -1 with a
/// message in err (errsize bytes, always NUL-terminated when errsize > 0; err may be NULL). A
/// file taken for a binary STL because of bytes that text does not hold has the reason at the
/// end of every message: " (read as a binary STL: byte K is 0xNN, which text does not hold)".
TTD_API int ttd_meshfile_read(const char *path, int flags, ttd_meshfile *out, char *err, size_t errsize);

/// The same on size bytes in memory (data need not be NUL-terminated); name is used in
/// messages only (NULL: "<input>").
TTD_API int ttd_meshfile_parse(const char *name, const unsigned char *data, size_t size, int flags,
                               ttd_meshfile *out, char *err, size_t errsize);

/// Frees the arrays and zeroes *m (NULL is allowed).
TTD_API void ttd_meshfile_free(ttd_meshfile *m);

/// Welds a mesh read from a file in place (include/ttd/ttd.h, ttd_mesh_weld_d, says what is
/// merged, which vertex is kept and which triangles are dropped): the classes are decided on
/// the double coordinates, and verts_f, when present, takes the float of the vertex kept.
/// *dropped (may be NULL) receives the number of collapsed triangles dropped. Returns 0, or -1
/// with a message in err and *m unchanged: a tolerance that is negative, NaN or infinite, out of
/// memory, or every triangle collapsing (the mesh would have none).
TTD_API int ttd_meshfile_weld(ttd_meshfile *m, double tolerance, size_t *dropped, char *err, size_t errsize);

/// "obj", "stl-ascii", "stl-binary", "ply-ascii", "ply-binary", "off", "glb", "gltf", "3mf"; NULL
/// when out of range.
TTD_API const char *ttd_meshfile_format_name(ttd_meshfile_format f);

#ifdef __cplusplus
}
#endif
#endif /* TTD_MESHFILE_H */
