/* SPDX-License-Identifier: MIT */
/* The mesh-file reader (ttd/meshfile.h): every format and variant is written here, by this
 * test's own small writers, from a generator mesh (gen/meshes.h) into a temporary directory,
 * read back, and compared with the mesh it was written from: coordinates bit for bit (or
 * their float32 rounding where the format stores floats), triangles in order. Malformed and
 * truncated variants must fail with a message naming the file and the right line or byte
 * offset. Float coordinates must be correctly rounded from the text, not double then float. */
#define _POSIX_C_SOURCE 200809L

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <unistd.h>

#include "meshes.h"
#include <ttd/meshfile.h>
#include "test_macros.h"

/* ---- a byte buffer and the temporary directory ----------------------------------------- */

typedef struct buf {
    unsigned char *p;
    size_t n, cap;
} buf;

static void put(buf *b, const void *data, size_t n)
{
    if (n == 0)
        return;
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->n + n) cap *= 2;
        unsigned char *np = realloc(b->p, cap);
        if (!np) { fprintf(stderr, "out of memory\n"); exit(2); }
        b->p = np;
        b->cap = cap;
    }
    memcpy(b->p + b->n, data, n);
    b->n += n;
}

static void putf(buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void putf(buf *b, const char *fmt, ...)
{
    char s[1024];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(s, sizeof s, fmt, ap);
    va_end(ap);
    put(b, s, (size_t)n);
}

/* The byte order of the put_* writers below: 0 little-endian (STL, PLY's default here), 1 big. */
static int big_endian;

static void put_ordered(buf *b, unsigned char *s, int n)
{
    for (int k = 0; big_endian && k < n / 2; ++k) {
        const unsigned char t = s[k];
        s[k] = s[n - 1 - k];
        s[n - 1 - k] = t;
    }
    put(b, s, (size_t)n);
}

static void put_u32(buf *b, uint32_t v)
{
    unsigned char s[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16), (unsigned char)(v >> 24)};
    put_ordered(b, s, 4);
}

static void put_u16(buf *b, uint16_t v)
{
    unsigned char s[2] = {(unsigned char)v, (unsigned char)(v >> 8)};
    put_ordered(b, s, 2);
}

static void put_f32(buf *b, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put_u32(b, u);
}

static void put_f64(buf *b, double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    unsigned char s[8];
    for (int k = 0; k < 8; ++k)
        s[k] = (unsigned char)(u >> (8 * k));
    put_ordered(b, s, 8);
}

static char tmpdir[256];

/// Writes b to tmpdir/name; the path in path.
static int write_file(const char *name, const buf *b, char *path, size_t pathsize)
{
    snprintf(path, pathsize, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    size_t w = b->n ? fwrite(b->p, 1, b->n, f) : 0;
    return fclose(f) == 0 && w == b->n ? 0 : -1;
}

static char err[1024];

/// Writes b as name and reads it back; 0 on success.
static int roundtrip(const char *name, const buf *b, int want_float, ttd_meshfile *m)
{
    char path[512];
    if (write_file(name, b, path, sizeof path) != 0) {
        snprintf(err, sizeof err, "cannot write %s", path);
        return -1;
    }
    return ttd_meshfile_read(path, want_float, m, err, sizeof err);
}

/// Parses b in memory as name; 0 on success (the message in err otherwise).
static int parse(const char *name, const buf *b, int want_float, ttd_meshfile *m)
{
    return ttd_meshfile_parse(name, b->p, b->n, want_float, m, err, sizeof err);
}

/* ---- comparisons ------------------------------------------------------------------------ */

/// The file's mesh has ref's vertices and triangles, in order; fl: coordinates stored as
/// float32 in the file (then the doubles are the floats' values).
static int same_mesh(const ttd_meshfile *m, const ttd_gen_mesh *ref, int fl)
{
    ENSURE_MSG(m->nv == ref->nv && m->nt == ref->nt, "%zu/%zu vertices, %zu/%zu triangles", m->nv, ref->nv, m->nt, ref->nt);
    for (size_t k = 0; k < 3 * m->nv; ++k) {
        double want = fl ? (double)(float)ref->verts[k] : ref->verts[k];
        ENSURE_MSG(m->verts[k] == want, "coordinate %zu: %.17g, expected %.17g", k, m->verts[k], want);
        if (m->verts_f)
            ENSURE_MSG(m->verts_f[k] == (float)ref->verts[k], "float coordinate %zu", k);
    }
    ENSURE(memcmp(m->tris, ref->tris, 3 * m->nt * sizeof(uint32_t)) == 0);
    return 0;
}

/// Same triangles geometrically, vertex by vertex (for STL, whose vertex numbering is the
/// order of first appearance).
static int same_triangles(const ttd_meshfile *m, const ttd_gen_mesh *ref, int fl)
{
    ENSURE_MSG(m->nt == ref->nt, "%zu/%zu triangles", m->nt, ref->nt);
    for (size_t t = 0; t < 3 * m->nt; ++t) {
        ENSURE(m->tris[t] < m->nv);
        for (int d = 0; d < 3; ++d) {
            double r = ref->verts[3 * ref->tris[t] + (size_t)d];
            ENSURE(m->verts[3 * m->tris[t] + (size_t)d] == (fl ? (double)(float)r : r));
            if (m->verts_f)
                ENSURE(m->verts_f[3 * m->tris[t] + (size_t)d] == (float)r);
        }
    }
    return 0;
}

/// The call failed and its message contains want.
#define ENSURE_ERROR(call, want)                                                          \
    do {                                                                                  \
        ttd_meshfile bad_;                                                                \
        err[0] = '\0';                                                                    \
        int rc_ = (call);                                                                 \
        ENSURE_MSG(rc_ == -1, "accepted; expected an error containing \"%s\"", want);     \
        ENSURE_MSG(strstr(err, want) != NULL, "message \"%s\" lacks \"%s\"", err, want);  \
        (void)bad_;                                                                       \
    } while (0)

/* ---- writers ------------------------------------------------------------------------------ */

static void obj_vertices(buf *b, const ttd_gen_mesh *m, const char *eol)
{
    for (size_t k = 0; k < m->nv; ++k)
        putf(b, "v %.17g %.17g %.17g%s", m->verts[3 * k], m->verts[3 * k + 1], m->verts[3 * k + 2], eol);
}

static void stl_ascii(buf *b, const ttd_gen_mesh *m, size_t first, size_t last, int upper)
{
    putf(b, upper ? "SOLID part %zu\n" : "solid part %zu\n", first);
    for (size_t t = first; t < last; ++t) {
        putf(b, upper ? "  FACET NORMAL 0 0 1\n    OUTER LOOP\n" : "  facet normal 0 0 1\n    outer loop\n");
        for (int k = 0; k < 3; ++k) {
            const double *p = m->verts + 3 * m->tris[3 * t + (size_t)k];
            putf(b, upper ? "      VERTEX %.17g %.17g %.17g\n" : "      vertex %.17g %.17g %.17g\n", p[0], p[1], p[2]);
        }
        putf(b, upper ? "    ENDLOOP\n  ENDFACET\n" : "    endloop\n  endfacet\n");
    }
    putf(b, upper ? "ENDSOLID part\n" : "endsolid part\n");
}

static void stl_binary(buf *b, const ttd_gen_mesh *m, const char *header)
{
    char h[80];
    memset(h, ' ', sizeof h);
    memcpy(h, header, strlen(header));
    put(b, h, 80);
    put_u32(b, (uint32_t)m->nt);
    for (size_t t = 0; t < m->nt; ++t) {
        for (int k = 0; k < 3; ++k) put_f32(b, 0.0f); /* normal */
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d)
                put_f32(b, (float)m->verts[3 * m->tris[3 * t + (size_t)k] + (size_t)d]);
        put_u16(b, 0);
    }
}

/* ---- OBJ ---------------------------------------------------------------------------------- */

static int obj_plain_and_float(void)
{
    ttd_gen_mesh ref;
    ENSURE(ttd_gen_icosphere(2, &ref) == 0);
    buf b = {0};
    putf(&b, "# an icosphere\nmtllib x.mtl\no sphere\n");
    obj_vertices(&b, &ref, "\n");
    putf(&b, "g faces\nusemtl red\ns 1\n");
    for (size_t t = 0; t < ref.nt; ++t)
        putf(&b, "f %u %u %u\n", ref.tris[3 * t] + 1, ref.tris[3 * t + 1] + 1, ref.tris[3 * t + 2] + 1);
    ttd_meshfile m;
    ENSURE_MSG(roundtrip("sphere.obj", &b, 1, &m) == 0, "%s", err);
    ENSURE(m.format == TTD_MESHFILE_OBJ);
    if (same_mesh(&m, &ref, 0)) return 1;
    ttd_meshfile_free(&m);
    ENSURE(roundtrip("sphere.obj", &b, 0, &m) == 0 && m.verts_f == NULL);
    if (same_mesh(&m, &ref, 0)) return 1;
    ttd_meshfile_free(&m);
    free(b.p);
    ttd_gen_mesh_free(&ref);
    return 0;
}

static int obj_variants(void)
{
    /* The grid written as quads: fan triangulation (a b c d) -> (a b c) (a c d) is exactly
     * the generator's split, so the triangles must match the generator's. */
    ttd_gen_mesh ref;
    ENSURE(ttd_gen_grid(5, &ref) == 0);
    for (int variant = 0; variant < 4; ++variant) {
        buf b = {0};
        const char *eol = variant & 1 ? "\r\n" : "\n";
        if (variant & 2)
            put(&b, "\xEF\xBB\xBF", 3); /* UTF-8 byte-order mark */
        putf(&b, "# variant %d%s%s", variant, eol, eol);
        for (size_t k = 0; k < ref.nv; ++k) /* w, or colours: extra numbers ignored */
            putf(&b, k % 2 ? "v %.17g %.17g %.17g 1.0%s" : "v  %.17g\t%.17g %.17g 0.5 0.25 0.125%s",
                 ref.verts[3 * k], ref.verts[3 * k + 1], ref.verts[3 * k + 2], eol);
        putf(&b, "vt 0 0%svn 0 0 1%svp 0.5%sl 1 2 3%s", eol, eol, eol, eol);
        const char *forms[4] = {"%ld", "%ld/1", "%ld//1", "%ld/1/1"};
        for (size_t t = 0; t < ref.nt; t += 2) {
            const uint32_t *q = ref.tris + 3 * t; /* (a b c) (a c d) */
            long idx[4] = {(long)q[0] + 1, (long)q[1] + 1, (long)q[2] + 1, (long)q[5] + 1};
            putf(&b, "f");
            for (int k = 0; k < 4; ++k) {
                long i = (t / 2) % 3 == 1 ? idx[k] - (long)ref.nv - 1 : idx[k]; /* negative: relative to the end */
                putf(&b, " ");
                putf(&b, forms[(t / 2 + (size_t)k) % 4], i);
            }
            putf(&b, "%s%s", t == 0 ? "  # a comment" : "", eol);
        }
        ttd_meshfile m;
        char name[32];
        snprintf(name, sizeof name, "grid%d.obj", variant);
        ENSURE_MSG(roundtrip(name, &b, 1, &m) == 0, "%s", err);
        if (same_mesh(&m, &ref, 0)) return 1;
        ttd_meshfile_free(&m);
        free(b.p);
    }
    ttd_gen_mesh_free(&ref);

    /* a pentagon and a hexagon fan out from their first vertex */
    buf b = {0};
    putf(&b, "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nv -1 1 0\nf 1 2 3 4 5\nf -1 -6 -5 -4 -3 -2\n");
    ttd_meshfile m;
    ENSURE_MSG(parse("poly.obj", &b, 0, &m) == 0, "%s", err);
    const uint32_t want[] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 5, 0, 1, 5, 1, 2, 5, 2, 3, 5, 3, 4};
    ENSURE(m.nt == 7 && m.nv == 6 && memcmp(m.tris, want, sizeof want) == 0);
    ttd_meshfile_free(&m);
    free(b.p);
    return 0;
}

static int obj_errors(void)
{
    struct { const char *text, *want; int want_float; } cases[] = {
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", "bad.obj:5: face index 4 out of range (the file has 3 vertices so far)", 0},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "bad.obj:4: face index -4 out of range (the file has 3 vertices so far)", 0},
        {"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "bad.obj:1: face index 1 out of range (the file has 0 vertices so far)", 0},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "bad.obj:4: face index 0 is invalid", 0},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "bad.obj:4: face has 2 vertices, at least 3 needed", 0},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/4/5/6\n", "bad.obj:4: bad vertex reference '3/4/5/6'", 0},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "bad.obj:4: bad vertex reference 'x'", 0},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/x\n", "bad.obj:4: bad vertex reference '3/x'", 0},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n", "bad.obj:4: bad vertex reference", 0},
        {"v 0 0 0\nv 1 0\n", "bad.obj:2: vertex has 2 coordinates, 3 needed", 0},
        {"v 0 0 0\n# c\nv 1 nan 0\n", "bad.obj:3: coordinate 'nan' is not finite", 0},
        {"v 0 0 0\r\nv inf 0 0\r\n", "bad.obj:2: coordinate 'inf' is not finite", 0},
        {"v 0 0 0\nv 1e999 0 0\n", "bad.obj:2: coordinate '1e999' is out of range", 0},
        {"v 0 0 0\nv 1e39 0 0\n", "bad.obj:2: coordinate '1e39' is out of range for float", 1},
        {"v 0 0 0\nv 1,5 0 0\n", "bad.obj:2: '1,5' is not a number", 0},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\n", "bad.obj: no triangles (read as obj)", 0},
        {"v 0 0 0\n@@ 1 2\n", "bad.obj:2: unexpected '@@' (not an OBJ statement)", TTD_MESHFILE_STRICT},
        {"6540 2180\nv 0 0 0\n", "bad.obj:1: unexpected '6540' (not an OBJ statement)", TTD_MESHFILE_STRICT | TTD_MESHFILE_FLOAT},
        {"", "bad.obj: empty file", 0},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        buf b = {0};
        put(&b, cases[k].text, strlen(cases[k].text));
        ENSURE_ERROR(roundtrip("bad.obj", &b, cases[k].want_float, &bad_), cases[k].want);
        free(b.p);
    }
    /* Lines that are not statements (FCL's env.obj begins with "6540 2180") are skipped and
     * counted, the first one's number kept; without them the mesh is the same. */
    {
        buf with = {0}, without = {0};
        putf(&with, "6540 2180\nv 0 0 0\nv 1 0 0\n@@ 1 2\nv 0 1 0\n-3 x\nf 1 2 3\nvt 0 0\n");
        putf(&without, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nvt 0 0\n");
        ttd_meshfile m1, m2;
        ENSURE_MSG(roundtrip("env.obj", &with, TTD_MESHFILE_FLOAT, &m1) == 0, "%s", err);
        ENSURE(m1.skipped_lines == 3 && m1.first_skipped_line == 1 && m1.format == TTD_MESHFILE_OBJ);
        ENSURE(parse("plain.obj", &without, 0, &m2) == 0 && m2.skipped_lines == 0 && m2.first_skipped_line == 0);
        ENSURE(m1.nv == 3 && m2.nv == 3 && m1.nt == 1 && m2.nt == 1 && m1.verts_f != NULL);
        ENSURE(memcmp(m1.verts, m2.verts, 9 * sizeof *m1.verts) == 0 && memcmp(m1.tris, m2.tris, 3 * sizeof *m1.tris) == 0);
        ttd_meshfile_free(&m1);
        ttd_meshfile_free(&m2);
        putf(&without, "12\n"); /* the skipped line's number is the first one's */
        ENSURE(parse("late.obj", &without, 0, &m2) == 0 && m2.skipped_lines == 1 && m2.first_skipped_line == 6);
        ttd_meshfile_free(&m2);
        free(with.p);
        free(without.p);
    }
    /* 1e39 is a fine double */
    buf b = {0};
    putf(&b, "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n");
    ttd_meshfile m;
    ENSURE(parse("ok.obj", &b, 0, &m) == 0 && m.verts[3] == 1e39);
    ttd_meshfile_free(&m);
    free(b.p);
    return 0;
}

/* ---- float rounding -------------------------------------------------------------------- */

static int float_correctly_rounded(void)
{
    /* Just above the midpoint between 1 and the next float 1 + 2^-23: the float is 1 + 2^-23.
     * Rounded to double first it would be the midpoint 1 + 2^-24 exactly, and then 1.0f. */
    const char *x = "1.00000005960464477539062500000001";
    const float up = 1.0f + FLT_EPSILON;
    ENSURE(strtod(x, NULL) == 1.0 + 0x1p-24 && (float)strtod(x, NULL) == 1.0f); /* the trap is real */
    buf b[3] = {{0}, {0}, {0}};
    putf(&b[0], "v %s 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", x);
    putf(&b[1], "solid t\nfacet normal 0 0 0\nouter loop\nvertex %s 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid t\n", x);
    putf(&b[2], "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty float z\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n%s 0 0\n0 1 0\n0 0 1\n3 0 1 2\n", x);
    const char *names[3] = {"r.obj", "r.stl", "r.ply"};
    for (int k = 0; k < 3; ++k) {
        ttd_meshfile m;
        ENSURE_MSG(parse(names[k], &b[k], 1, &m) == 0, "%s", err);
        ENSURE_MSG(m.verts_f[0] == up && m.verts[0] == 1.0 + 0x1p-24, "%s: %.9g", names[k], (double)m.verts_f[0]);
        ttd_meshfile_free(&m);
        free(b[k].p);
    }
    /* binary double: rounded once to float (ties to even at the exact midpoint) */
    const double vals[3] = {1.0 + 0x1p-24 + 0x1p-52, 1.0 + 0x1p-24, 1.0 + 3 * 0x1p-24};
    const float expect[3] = {up, 1.0f, 1.0f + 2 * FLT_EPSILON};
    buf p = {0};
    putf(&p, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
             "element face 1\nproperty list uchar uint vertex_indices\nend_header\n");
    for (int k = 0; k < 3; ++k) {
        put_f64(&p, vals[k]);
        put_f64(&p, 0.0);
        put_f64(&p, (double)k);
    }
    unsigned char three = 3;
    put(&p, &three, 1);
    for (uint32_t k = 0; k < 3; ++k) put_u32(&p, k);
    ttd_meshfile m;
    ENSURE_MSG(parse("d.ply", &p, 1, &m) == 0, "%s", err);
    for (int k = 0; k < 3; ++k)
        ENSURE_MSG(m.verts[3 * k] == vals[k] && m.verts_f[3 * k] == expect[k], "value %d", k);
    ttd_meshfile_free(&m);
    free(p.p);
    return 0;
}

/* ---- STL ---------------------------------------------------------------------------------- */

static int stl_ascii_variants(void)
{
    ttd_gen_mesh ref; /* 642 vertices: the merge table grows on the way */
    ENSURE(ttd_gen_icosphere(3, &ref) == 0);
    for (int variant = 0; variant < 3; ++variant) {
        buf b = {0};
        if (variant == 0)
            stl_ascii(&b, &ref, 0, ref.nt, 0);
        else if (variant == 1)
            stl_ascii(&b, &ref, 0, ref.nt, 1); /* keywords in capitals */
        else {                                 /* two solids, the second in capitals */
            stl_ascii(&b, &ref, 0, 300, 0);
            stl_ascii(&b, &ref, 300, ref.nt, 1);
        }
        ttd_meshfile m;
        ENSURE_MSG(roundtrip("sphere.stl", &b, variant == 2, &m) == 0, "%s", err);
        ENSURE(m.format == TTD_MESHFILE_STL_ASCII);
        if (same_triangles(&m, &ref, 0)) return 1;
        /* the icosphere's vertices are distinct: merged back to exactly its vertex count */
        ENSURE_MSG(m.nv == ref.nv, "%zu vertices after merging, %zu expected", m.nv, ref.nv);
        ttd_meshfile_free(&m);
        free(b.p);
    }
    /* bitwise merging only: -0 and +0 stay apart */
    buf b = {0};
    putf(&b, "solid z\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
             "facet normal 0 0 0\nouter loop\nvertex -0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid z\n");
    ttd_meshfile m;
    ENSURE_MSG(parse("z.stl", &b, 0, &m) == 0, "%s", err);
    const uint32_t want[] = {0, 1, 2, 3, 2, 1};
    ENSURE(m.nv == 4 && m.nt == 2 && memcmp(m.tris, want, sizeof want) == 0);
    ttd_meshfile_free(&m);
    free(b.p);
    ttd_gen_mesh_free(&ref);
    return 0;
}

static int stl_binary_variants(void)
{
    ttd_gen_mesh ref;
    ENSURE(ttd_gen_torus(2.0, 0.5, 12, 8, &ref) == 0);
    const char *headers[3] = {"binary STL from ttd's test", "solid but binary: facet normal vertex", "solid"};
    for (int variant = 0; variant < 3; ++variant) {
        buf b = {0};
        stl_binary(&b, &ref, headers[variant]);
        ttd_meshfile m;
        ENSURE_MSG(roundtrip("torus.stl", &b, variant != 1, &m) == 0, "%s", err);
        ENSURE_MSG(m.format == TTD_MESHFILE_STL_BINARY, "variant %d read as %s", variant, ttd_meshfile_format_name(m.format));
        if (same_triangles(&m, &ref, 1)) return 1;
        ENSURE(m.nv == ref.nv); /* float32 torus vertices stay distinct */
        ttd_meshfile_free(&m);
        free(b.p);
    }
    ttd_gen_mesh_free(&ref);
    return 0;
}

static int stl_errors(void)
{
    ttd_gen_mesh tet;
    ENSURE(ttd_gen_mesh_tetrahedron(&tet) == 0);
    buf b = {0};
    stl_binary(&b, &tet, "solid tet"); /* 84 + 4 * 50 = 284 bytes */
    buf t = b;
    t.n = 200;
    ENSURE_ERROR(parse("mesh.stl", &t, 0, &bad_), "mesh.stl: truncated: 4 facets declared, file ends at byte 200");
    t.n = 82; /* the count's first bytes say binary */
    ENSURE_ERROR(parse("mesh.stl", &t, 0, &bad_), "mesh.stl: truncated: file ends at byte 82 inside the 84-byte binary STL header");
    put(&b, "xx", 2);
    ENSURE_ERROR(parse("mesh.stl", &b, 0, &bad_), "mesh.stl: 4 facets declared take 284 bytes, but the file has 286");
    b.n = 284;
    float nan = (float)NAN;
    memcpy(b.p + 84 + 50 * 2 + 12 + 12 * 1 + 4 * 2, &nan, 4); /* facet 2, vertex 2, z */
    ENSURE_ERROR(parse("mesh.stl", &b, 0, &bad_), "mesh.stl: byte 216: facet 2: vertex 2: coordinate is not finite");
    /* a count the file cannot hold: refused without allocating for it */
    b.p[80] = b.p[81] = b.p[82] = b.p[83] = 0xff;
    ENSURE_ERROR(parse("mesh.stl", &b, 0, &bad_), "mesh.stl: truncated: 4294967295 facets declared, file ends at byte 284");
    b.p[80] = b.p[81] = b.p[82] = b.p[83] = 0;
    b.n = 84;
    ENSURE_ERROR(parse("mesh.stl", &b, 0, &bad_), "mesh.stl: binary STL with 0 facets");
    free(b.p);

    struct { const char *text, *want; } cases[] = {
        {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n", "a.stl:5: truncated: file ends inside a facet"},
        {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\n", "a.stl:7: facet has more than 3 vertices"},
        {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n", "a.stl:6: facet has 2 vertices, 3 needed"},
        {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\n", "a.stl:7: expected 'endloop', found 'endfacet'"},
        {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\n", "a.stl:5: coordinate 'nan' is not finite"},
        {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n", "a.stl:8: truncated: file ends before 'endsolid'"},
        {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\ngarbage\n", "a.stl:10: expected 'solid' or the end of the file after 'endsolid', found 'garbage'"},
        {"solid x\nfacet normal 0 0\nouter loop\n", "a.stl:3: facet normal component 'outer' is not a number"},
        {"solid x\nfacet\n", "a.stl:2: truncated: file ends where 'normal' was expected"},
        {"solid x\nendsolid x\n", "a.stl: no triangles (read as stl-ascii)"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        buf c = {0};
        put(&c, cases[k].text, strlen(cases[k].text));
        ENSURE_ERROR(roundtrip("a.stl", &c, 0, &bad_), cases[k].want);
        free(c.p);
    }
    ttd_gen_mesh_free(&tet);
    return 0;
}

/* ---- PLY ---------------------------------------------------------------------------------- */

/// A binary PLY of m with an extra element before the vertices, extra vertex properties
/// (a double, a uchar colour, a list), faces written as the types asked, an extra element with
/// a list between vertices and faces, and one after the faces.
static void ply_binary(buf *b, const ttd_gen_mesh *m, const char *coord_type, const char *count_type,
                       const char *index_type, const char *index_name, int faces_first)
{
    putf(b, "ply\nformat %s 1.0\ncomment written by ttd's test\nobj_info nothing\n",
         big_endian ? "binary_big_endian" : "binary_little_endian");
    putf(b, "element material 2\nproperty float shine\nproperty uchar id\n");
    const char *vertex_header_fmt = "element vertex %zu\nproperty double quality\nproperty %s x\nproperty %s y\n"
                                    "property uchar red\nproperty list uchar int16 tags\nproperty %s z\n";
    const char *face_header_fmt = "element face %zu\nproperty uchar flags\nproperty list %s %s %s\nproperty float weight\n";
    if (faces_first)
        putf(b, face_header_fmt, m->nt, count_type, index_type, index_name);
    else
        putf(b, vertex_header_fmt, m->nv, coord_type, coord_type, coord_type);
    putf(b, "element edge 2\nproperty list ushort uint32 ends\nproperty int8 crease\n");
    if (faces_first)
        putf(b, vertex_header_fmt, m->nv, coord_type, coord_type, coord_type);
    else
        putf(b, face_header_fmt, m->nt, count_type, index_type, index_name);
    putf(b, "element trailer 1\nproperty list uint8 float64 stuff\nend_header\n");
    /* material */
    for (int k = 0; k < 2; ++k) { put_f32(b, 0.5f); unsigned char id = (unsigned char)k; put(b, &id, 1); }
    for (int pass = 0; pass < 3; ++pass) {
        int what = faces_first ? (pass == 0 ? 2 : pass == 1 ? 1 : 0) : pass; /* 0 vertices, 1 edges, 2 faces */
        if (what == 0) {
            for (size_t k = 0; k < m->nv; ++k) {
                put_f64(b, 1.5);
                for (int d = 0; d < 3; ++d) {
                    if (d == 2) { /* after red and tags */
                        unsigned char red = 200, n = (unsigned char)(k % 3);
                        put(b, &red, 1);
                        put(b, &n, 1);
                        for (unsigned i = 0; i < n; ++i) put_u16(b, 7);
                    }
                    double x = m->verts[3 * k + (size_t)d];
                    if (!strcmp(coord_type, "float") || !strcmp(coord_type, "float32")) put_f32(b, (float)x);
                    else if (!strcmp(coord_type, "int16")) put_u16(b, (uint16_t)(int16_t)x);
                    else put_f64(b, x);
                }
            }
        } else if (what == 1) {
            for (int k = 0; k < 2; ++k) {
                put_u16(b, 2);
                put_u32(b, 0);
                put_u32(b, 1);
                signed char c = -1;
                put(b, &c, 1);
            }
        } else {
            for (size_t t = 0; t < m->nt; ++t) {
                unsigned char flags = 1;
                put(b, &flags, 1);
                if (!strcmp(count_type, "uchar")) { unsigned char n = 3; put(b, &n, 1); }
                else put_u32(b, 3);
                for (int k = 0; k < 3; ++k) {
                    uint32_t i = m->tris[3 * t + (size_t)k];
                    if (!strcmp(index_type, "int16") || !strcmp(index_type, "ushort")) put_u16(b, (uint16_t)i);
                    else put_u32(b, i);
                }
                put_f32(b, 0.25f);
            }
        }
    }
    unsigned char two = 2;
    put(b, &two, 1);
    put_f64(b, 1.0);
    put_f64(b, 2.0);
}

static int ply_binary_variants(void)
{
    ttd_gen_mesh ref, grid;
    ENSURE(ttd_gen_icosphere(2, &ref) == 0);
    ENSURE(ttd_gen_grid(4, &grid) == 0);
    for (size_t k = 0; k < 3 * grid.nv; ++k) grid.verts[k] = round(grid.verts[k] * 4) - 3; /* small integers */
    struct { const char *coord, *count, *index, *name; int faces_first, fl, use_grid; } v[] = {
        {"float", "uchar", "int", "vertex_indices", 0, 1, 0},
        {"double", "uchar", "uint", "vertex_indices", 0, 0, 0},
        {"float64", "uint32", "int32", "vertex_index", 1, 0, 0},
        {"float32", "uchar", "ushort", "vertex_index", 1, 1, 0},
        {"int16", "uint", "int16", "vertex_indices", 0, 0, 1},
    };
    for (size_t k = 0; k < 2 * (sizeof v / sizeof v[0]); ++k) {
        big_endian = k >= sizeof v / sizeof v[0]; /* every variant in both byte orders */
        const size_t j = k % (sizeof v / sizeof v[0]);
        const ttd_gen_mesh *m = v[j].use_grid ? &grid : &ref;
        buf b = {0};
        ply_binary(&b, m, v[j].coord, v[j].count, v[j].index, v[j].name, v[j].faces_first);
        big_endian = 0;
        ttd_meshfile mf;
        ENSURE_MSG(roundtrip("b.ply", &b, 1, &mf) == 0, "variant %zu: %s", k, err);
        ENSURE(mf.format == TTD_MESHFILE_PLY_BINARY);
        if (same_mesh(&mf, m, v[j].fl)) { fprintf(stderr, "  variant %zu\n", k); return 1; }
        ttd_meshfile_free(&mf);
        free(b.p);
    }
    ttd_gen_mesh_free(&ref);
    ttd_gen_mesh_free(&grid);
    return 0;
}

static int ply_ascii_variants(void)
{
    ttd_gen_mesh ref;
    ENSURE(ttd_gen_grid(3, &ref) == 0);
    for (int crlf = 0; crlf < 2; ++crlf) {
        const char *eol = crlf ? "\r\n" : "\n";
        buf b = {0};
        putf(&b, "ply%sformat ascii 1.0%scomment made by hand%selement vertex %zu%sproperty float x%sproperty float y%s"
                 "property float z%sproperty float nx%sproperty list uchar int ids%sproperty uchar red%s",
             eol, eol, eol, ref.nv, eol, eol, eol, eol, eol, eol, eol);
        putf(&b, "element face %zu%sproperty list uchar int vertex_indices%selement edge 1%sproperty int a%sproperty int b%send_header%s",
             ref.nt / 2, eol, eol, eol, eol, eol, eol);
        for (size_t k = 0; k < ref.nv; ++k) /* NaN normals are skipped, not read */
            putf(&b, "%.17g %.17g %.17g nan %d 1 2 255%s", ref.verts[3 * k], ref.verts[3 * k + 1], ref.verts[3 * k + 2], 2, eol);
        for (size_t t = 0; t < ref.nt; t += 2) /* quads */
            putf(&b, "4 %u %u %u %u%s", ref.tris[3 * t], ref.tris[3 * t + 1], ref.tris[3 * t + 2], ref.tris[3 * t + 5], eol);
        putf(&b, "0 1%s", eol);
        ttd_meshfile m;
        ENSURE_MSG(roundtrip("a.ply", &b, 0, &m) == 0, "%s", err);
        ENSURE(m.format == TTD_MESHFILE_PLY_ASCII);
        if (same_mesh(&m, &ref, 0)) return 1;
        ttd_meshfile_free(&m);
        free(b.p);
    }
    ttd_gen_mesh_free(&ref);
    return 0;
}

static int ply_errors(void)
{
    const char *head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const char *face = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const char *verts = "0 0 0\n1 0 0\n0 1 0\n";
    struct { const char *a, *b, *c, *d, *want; } cases[] = {
        {"ply\nformat binary_middle_endian 1.0\n", "", "", "", "a.ply:2: unknown format 'binary_middle_endian'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty list float int n\n",
         "", "", "", "a.ply:7: property list count type 'float' is not an integer type"},
        {head, "element face 1\nproperty list uchar float vertex_indices\n", "", "", "a.ply:8: face index type 'float' is not an integer type"},
        {head, "property quad w\n", "", "", "a.ply:7: unknown property type 'quad'"},
        {"ply\nformat ascii 1.0\nproperty float x\n", "", "", "", "a.ply:3: property before any element"},
        {head, face, verts, "3 0 1 3\n", "a.ply:13: face 0: vertex index 3 out of range (the file has 3 vertices)"},
        {head, face, verts, "2 0 1\n", "a.ply:13: face 0 has 2 vertices, at least 3 needed"},
        {head, "element face 1\nproperty list int int vertex_indices\nend_header\n", verts, "-3 0 1 2\n", "a.ply:13: face 0: negative list count -3"},
        {head, face, "0 0 0\n1 nan 0\n0 1 0\n", "3 0 1 2\n", "a.ply:11: coordinate 'nan' is not finite"},
        {head, face, "0    0    0\n1    0    0\n", "", "a.ply:11: truncated: file ends inside vertex 2 of 3"},
        {head, face, verts, "3 0 1 2\n7\n", "a.ply:14: data after the last element: '7'"},
        {head, face, verts, "300 0 1 2\n", "a.ply:13: '300' is not a whole number in the range of 'uchar' (face 0)"},
        {head, "element face 1\nproperty list uchar int vertex_indices\n", "", "", "a.ply:8: truncated: the header has no 'end_header' line"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n", face, verts, "3 0 1 2\n", "a.ply:3: element 'vertex' has no property 'z'"},
        {head, "end_header\n", verts, "", "a.ply: no 'face' element in the PLY header"},
        {head, "element vertex 2\n", "", "", "a.ply:7: a second 'vertex' element"},
        {head, "element junk 1000000000000000\nproperty float a\n", face, "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         "a.ply:7: element 'junk' declares 1000000000000000 elements of at least 2 bytes each, but only 26 bytes follow the header"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float y\n", face, verts, "3 0 1 2\n",
         "a.ply:7: element 'vertex' has a second property 'y'"},
        {"ply\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n", face, verts, "3 0 1 2\n", "a.ply:8: no 'format' line before 'end_header'"},
        {"ply\nformat ascii 1.0\nhello\n", "", "", "", "a.ply:3: unexpected header line starting with 'hello'"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        buf b = {0};
        putf(&b, "%s%s%s%s", cases[k].a, cases[k].b, cases[k].c, cases[k].d);
        ENSURE_ERROR(roundtrip("a.ply", &b, 0, &bad_), cases[k].want);
        free(b.p);
    }

    /* binary: offsets */
    ttd_gen_mesh tet;
    ENSURE(ttd_gen_mesh_tetrahedron(&tet) == 0);
    buf b = {0};
    ply_binary(&b, &tet, "float", "uchar", "int", "vertex_indices", 0);
    /* find the data start: after "end_header\n" */
    const char *eh = strstr((const char *)b.p, "end_header\n");
    ENSURE(eh != NULL);
    size_t data = (size_t)(eh - (const char *)b.p) + 11;
    /* material: 2 x 5 bytes; vertex k: 8 + 4 + 4 + 1 + 1 + 2 (k % 3) + 4 */
    size_t vstart = data + 10, v1 = vstart + 22, v2 = v1 + 24;
    float nan = (float)NAN;
    memcpy(b.p + v2 + 8 + 4, &nan, 4); /* vertex 2's y */
    ENSURE_ERROR(parse("b.ply", &b, 0, &bad_), "b.ply: byte ");
    char want[128];
    snprintf(want, sizeof want, "b.ply: byte %zu: vertex 2: coordinate y is not finite", v2 + 12);
    ENSURE_MSG(strstr(err, want), "%s (wanted %s)", err, want);
    float one = 1.0f;
    memcpy(b.p + v2 + 12, &one, 4);
    /* faces after the edges: vertex 3 ends at v2 + 26 + 22 (4 verts: 22, 24, 26, 22 bytes); edges 2 x 11 */
    size_t fstart = v2 + 26 + 22 + 22;
    ENSURE(b.p[fstart] == 1 && b.p[fstart + 1] == 3); /* flags, count: the layout is as computed */
    unsigned char le[4] = {4, 0, 0, 0};
    memcpy(b.p + fstart + 1 + 1 + 4, le, 4); /* face 0's second index */
    snprintf(want, sizeof want, "b.ply: byte %zu: face 0: vertex index 4 out of range (the file has 4 vertices)", fstart + 6);
    ENSURE_ERROR(parse("b.ply", &b, 0, &bad_), want);
    le[0] = 1;
    memcpy(b.p + fstart + 6, le, 4);
    b.p[fstart + 1] = 2; /* a face with 2 vertices */
    snprintf(want, sizeof want, "b.ply: byte %zu: face 0 has 2 vertices, at least 3 needed", fstart + 1);
    ENSURE_ERROR(parse("b.ply", &b, 0, &bad_), want);
    b.p[fstart + 1] = 3;
    ttd_meshfile m;
    ENSURE_MSG(parse("b.ply", &b, 0, &m) == 0, "%s", err); /* repaired */
    ttd_meshfile_free(&m);
    buf t = b;
    t.n = fstart + 20;
    snprintf(want, sizeof want, "b.ply: byte %zu: truncated: file ends inside face 1 of 4", fstart + 20);
    ENSURE_ERROR(parse("b.ply", &t, 0, &bad_), want);
    put(&b, "z", 1);
    snprintf(want, sizeof want, "b.ply: byte %zu: 1 byte of data after the last element", b.n - 1);
    ENSURE_ERROR(parse("b.ply", &b, 0, &bad_), want);
    free(b.p);
    ttd_gen_mesh_free(&tet);

    /* a huge list count in a skipped binary element, and a huge element count */
    b = (buf){0};
    putf(&b, "ply\nformat binary_little_endian 1.0\nelement junk 1\nproperty list uint int x\n%s%s", head + strlen("ply\nformat ascii 1.0\n"), face);
    put_u32(&b, 0xffffffffu);
    for (int k = 0; k < 49; ++k) /* room for the vertices and the face, so the header passes */
        put(&b, "", 1);
    ENSURE_ERROR(parse("c.ply", &b, 0, &bad_), "c.ply: byte ");
    ENSURE_MSG(strstr(err, "truncated: file ends inside junk 0 of 1 (a list of 4294967295)"), "%s", err);
    free(b.p);
    b = (buf){0};
    putf(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 5000000000\nproperty float x\nproperty float y\nproperty float z\n%s", face);
    ENSURE_ERROR(parse("c.ply", &b, 0, &bad_), "c.ply:3: 5000000000 vertices: indices would not fit in 32 bits");
    free(b.p);
    b = (buf){0};
    putf(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 400000000\nproperty float x\nproperty float y\nproperty float z\n%s", face);
    ENSURE_ERROR(parse("c.ply", &b, 0, &bad_), "c.ply:3: element 'vertex' declares 400000000 elements of at least 12 bytes each, but only 0 bytes follow the header");
    free(b.p);
    return 0;
}

/* ---- detection, files, arguments ---------------------------------------------------------- */

static int io_and_arguments(void)
{
    ttd_meshfile m;
    char path[512];
    ENSURE_ERROR(ttd_meshfile_read("/nonexistent/dir/x.obj", 0, &bad_, err, sizeof err), "/nonexistent/dir/x.obj: cannot open: ");
    ENSURE_ERROR(ttd_meshfile_read(tmpdir, 0, &bad_, err, sizeof err), "it is a directory");
    ENSURE_ERROR(ttd_meshfile_read(NULL, 0, &bad_, err, sizeof err), "no file name");
    /* a small error buffer: cut, terminated */
    buf b = {0};
    putf(&b, "v 0 0 0\n");
    char small[8];
    memset(small, 'x', sizeof small);
    ENSURE(ttd_meshfile_parse("long-name.obj", b.p, b.n, 0, &m, small, sizeof small) == -1);
    ENSURE(memchr(small, '\0', sizeof small) != NULL && m.verts == NULL && m.nt == 0);
    ENSURE(ttd_meshfile_parse("x.obj", b.p, b.n, 0, &m, NULL, 0) == -1);
    ENSURE(ttd_meshfile_parse("x.obj", NULL, 5, 0, &m, err, sizeof err) == -1);
    ENSURE(ttd_meshfile_parse(NULL, b.p, b.n, 0, &m, err, sizeof err) == -1 && strncmp(err, "<input>: ", 9) == 0);
    free(b.p);

    /* standard input */
    b = (buf){0};
    putf(&b, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    ENSURE(write_file("stdin.obj", &b, path, sizeof path) == 0);
    ENSURE(freopen(path, "rb", stdin) != NULL);
    ENSURE_MSG(ttd_meshfile_read("-", 0, &m, err, sizeof err) == 0, "%s", err);
    ENSURE(m.nt == 1 && m.nv == 3 && m.verts[3] == 1.0);
    ttd_meshfile_free(&m);
    ttd_meshfile_free(&m); /* twice is harmless */
    ttd_meshfile_free(NULL);
    free(b.p);

    /* text that merely looks like other formats */
    b = (buf){0};
    putf(&b, "# solid\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    ENSURE(parse("s.obj", &b, 0, &m) == 0 && m.format == TTD_MESHFILE_OBJ);
    ttd_meshfile_free(&m);
    free(b.p);
    b = (buf){0};
    putf(&b, "solidity 1\n");
    ENSURE_ERROR(parse("s.obj", &b, 0, &bad_), "s.obj: no triangles (read as obj)");
    free(b.p);
    /* a short binary file is a binary STL too short for its header */
    b = (buf){0};
    put(&b, "\x01\x02garbage", 9);
    ENSURE_ERROR(parse("g.bin", &b, 0, &bad_), "g.bin: truncated: file ends at byte 9 inside the 84-byte binary STL header");
    ENSURE_ERROR(parse("g.bin", &b, 0, &bad_), "(read as a binary STL: byte 0 is 0x01, which text does not hold)");
    free(b.p);
    /* Text with one byte that text does not hold (Latin-1 0xff) is read as a binary STL, and
     * the message says so and why. */
    b = (buf){0};
    putf(&b, "v 0 0 0\nv 1 0 0 # caf\xff\nv 0 1 0\nf 1 2 3\n# HHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHH\n");
    ENSURE_ERROR(parse("garbage.obj", &b, 0, &bad_),
                 "garbage.obj: truncated: 1212696648 facets declared, file ends at byte");
    ENSURE_ERROR(parse("garbage.obj", &b, 0, &bad_), "(read as a binary STL: byte 21 is 0xff, which text does not hold)");
    free(b.p);
    /* A binary STL recognised by its size gets no such words. */
    b = (buf){0};
    ttd_gen_mesh tet;
    ENSURE(ttd_gen_mesh_tetrahedron(&tet) == 0);
    stl_binary(&b, &tet, "solid tet");
    ttd_gen_mesh_free(&tet);
    float inf = (float)INFINITY;
    memcpy(b.p + 84 + 12, &inf, 4);
    ENSURE_ERROR(parse("inf.stl", &b, 0, &bad_), "inf.stl: byte 96: facet 0: vertex 1: coordinate is not finite");
    ENSURE(strstr(err, "read as") == NULL);
    free(b.p);
    ENSURE(strcmp(ttd_meshfile_format_name(TTD_MESHFILE_PLY_BINARY), "ply-binary") == 0);
    ENSURE(ttd_meshfile_format_name(TTD_MESHFILE_FORMAT_COUNT) == NULL);
    return 0;
}

static int remove_tmpdir(void)
{
    DIR *d = opendir(tmpdir);
    ENSURE(d != NULL);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        char path[600];
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", tmpdir, e->d_name);
        ENSURE(unlink(path) == 0);
    }
    closedir(d);
    ENSURE(rmdir(tmpdir) == 0);
    return 0;
}

int main(int argc, char **argv)
{
    const char *base = getenv("TMPDIR");
    snprintf(tmpdir, sizeof tmpdir, "%s/ttd_meshfile_XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(tmpdir)) {
        perror("mkdtemp");
        return 1;
    }
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(obj_plain_and_float);
    RUN_TEST(obj_variants);
    RUN_TEST(obj_errors);
    RUN_TEST(float_correctly_rounded);
    RUN_TEST(stl_ascii_variants);
    RUN_TEST(stl_binary_variants);
    RUN_TEST(stl_errors);
    RUN_TEST(ply_binary_variants);
    RUN_TEST(ply_ascii_variants);
    RUN_TEST(ply_errors);
    RUN_TEST(io_and_arguments);
    RUN_TEST(remove_tmpdir);
    TEST_MAIN_END();
}
