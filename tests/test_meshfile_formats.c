/* SPDX-License-Identifier: MIT */
/* The mesh-file reader's further formats and forms (ttd/meshfile.h, docs/mesh-files.md): OFF,
 * binary glTF (GLB) and .gltf with data: URI and external buffers, the OBJ forms other readers
 * take, and files recognised by their first bytes and refused by name. Files are written here
 * from generator meshes (gen/meshes.h) by this test's own writers and read back: coordinates
 * exactly (OFF: %.17g; glTF: their float32), triangles in order. Malformed files (every prefix
 * of a GLB, bad accessors and views, bad OFF counts) must fail with a message, never crash.
 * With assimp (libassimp-dev, its C API) as the independent reader: the triangle counts of every
 * file written here equal assimp's, and the files assimp writes from them (GLB, glTF, OBJ, STL,
 * PLY) read here as the same triangles; without it those checks are skipped, saying so. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "meshes.h"
#include <ttd/meshfile.h>
#include "test_macros.h"

#ifdef TTD_HAVE_ASSIMP
#include <assimp/cexport.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#endif

typedef struct buf {
    unsigned char *p;
    size_t n, cap;
} buf;

static void put(buf *b, const void *data, size_t n)
{
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->n + n)
            cap *= 2;
        b->p = realloc(b->p, cap);
        if (!b->p) {
            fprintf(stderr, "out of memory\n");
            exit(2);
        }
        b->cap = cap;
    }
    memcpy(b->p + b->n, data, n);
    b->n += n;
}

static void putf(buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void putf(buf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *s = malloc((size_t)n + 1);
    if (!s)
        exit(2);
    va_start(ap, fmt);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    va_end(ap);
    put(b, s, (size_t)n);
    free(s);
}

static void put32(buf *b, uint32_t v)
{
    unsigned char x[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16), (unsigned char)(v >> 24)};
    put(b, x, 4);
}

static char tmpdir[256];

static int write_file(const char *name, const buf *b, char *path, size_t pathsize)
{
    snprintf(path, pathsize, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    size_t w = fwrite(b->p, 1, b->n, f);
    return fclose(f) == 0 && w == b->n ? 0 : -1;
}

static int parse(const char *name, const buf *b, ttd_meshfile *m, char *err, size_t errsize)
{
    return ttd_meshfile_parse(name, b->p, b->n, TTD_MESHFILE_FLOAT, m, err, errsize);
}

/* m equals g: vertices (as float32 when f32, else exactly), triangles in order. */
static int same_mesh(const ttd_meshfile *m, const ttd_gen_mesh *g, int f32, const double *shift)
{
    ENSURE_MSG(m->nv == g->nv && m->nt == g->nt, "%zu/%zu vertices, %zu/%zu triangles", m->nv, g->nv, m->nt, g->nt);
    for (size_t i = 0; i < 3 * g->nv; ++i) {
        double want = f32 ? (double)(float)g->verts[i] : g->verts[i];
        if (shift)
            want = (double)(float)want + shift[i % 3];
        ENSURE_MSG(m->verts[i] == want, "coordinate %zu: %.17g, want %.17g", i, m->verts[i], want);
    }
    ENSURE(memcmp(m->tris, g->tris, 3 * g->nt * sizeof(uint32_t)) == 0);
    return 0;
}

#define ENSURE_FAILS(expr, text)                                                                   \
    do {                                                                                           \
        char err_[512] = "";                                                                       \
        ttd_meshfile m_;                                                                           \
        int rc_ = (expr);                                                                          \
        (void)m_;                                                                                  \
        ENSURE_MSG(rc_ == -1 && strstr(err_, text) != NULL, "rc %d, message '%s', want '%s'", rc_, err_, text); \
        ENSURE_MSG(strstr(err_, "binary STL") == NULL, "read as an STL: %s", err_);                \
    } while (0)

/* ---- OBJ forms ------------------------------------------------------------------------- */

static int test_obj_forms(void)
{
    const char *plain = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 3 2\n";
    const char *forms[] = {
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1// 2// 3// 4//\nf 1/1/ 3/3/ 2/2/\n",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/ 2/ 3/5 4//7\nf -4 -2 -3\n",
        "v 0 0 0\nv 1 0 \\\n 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\\n3 \\\r\n 4\nf 1 3 2\n",
        "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nf 1 \\\r\n2 3 4\r\nf 1 3 2 # comment \\\n",
    };
    ttd_meshfile a, b;
    char err[512];
    ENSURE(ttd_meshfile_parse("p.obj", (const unsigned char *)plain, strlen(plain), 0, &a, err, sizeof err) == 0);
    for (size_t k = 0; k < sizeof forms / sizeof forms[0]; ++k) {
        ENSURE_MSG(ttd_meshfile_parse("f.obj", (const unsigned char *)forms[k], strlen(forms[k]), 0, &b, err, sizeof err) == 0,
                   "form %zu: %s", k, err);
        ENSURE_MSG(b.nv == a.nv && b.nt == a.nt && memcmp(a.verts, b.verts, 3 * a.nv * sizeof(double)) == 0 &&
                       memcmp(a.tris, b.tris, 3 * a.nt * sizeof(uint32_t)) == 0,
                   "form %zu differs", k);
        ttd_meshfile_free(&b);
    }
    ttd_meshfile_free(&a);
    /* a continued line's errors name its first line; a bad reference still fails */
    const char *bad = "v 0 0 0\nv 1 0 0\nf 1 2 \\\n 9\n";
    ENSURE_FAILS(ttd_meshfile_parse("c.obj", (const unsigned char *)bad, strlen(bad), 0, &m_, err_, sizeof err_),
                 "c.obj:3: face index 9 out of range");
    const char *bad2 = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/x/\n";
    ENSURE_FAILS(ttd_meshfile_parse("d.obj", (const unsigned char *)bad2, strlen(bad2), 0, &m_, err_, sizeof err_),
                 "bad vertex reference '3/x/'");
    return 0;
}

/* ---- OFF ------------------------------------------------------------------------------- */

static void write_off(buf *b, const ttd_gen_mesh *g, const char *kw, int extras)
{
    putf(b, "%s\n# written by test_meshfile_formats\n%zu %zu 0\n", kw, g->nv, g->nt);
    for (size_t i = 0; i < g->nv; ++i) {
        putf(b, "%.17g %.17g %.17g", g->verts[3 * i], g->verts[3 * i + 1], g->verts[3 * i + 2]);
        if (extras)
            putf(b, " 0.5 0.25 1 1");
        putf(b, "\n");
    }
    for (size_t t = 0; t < g->nt; ++t)
        putf(b, "3 %u %u %u%s\n", g->tris[3 * t], g->tris[3 * t + 1], g->tris[3 * t + 2], extras ? " 255 0 0" : "");
}

static int test_off(void)
{
    ttd_gen_mesh s = {0}, t = {0};
    ENSURE(ttd_gen_icosphere(3, &s) == 0 && ttd_gen_torus(1, 0.3, 24, 12, &t) == 0);
    const ttd_gen_mesh *gs[2] = {&s, &t};
    const char *kws[3] = {"OFF", "COFF", "NOFF"};
    char err[512];
    for (int k = 0; k < 2; ++k)
        for (int w = 0; w < 3; ++w) {
            buf b = {0};
            write_off(&b, gs[k], kws[w], w > 0);
            ttd_meshfile m;
            ENSURE_MSG(parse("a.off", &b, &m, err, sizeof err) == 0, "%s", err);
            ENSURE(m.format == TTD_MESHFILE_OFF);
            ENSURE(same_mesh(&m, gs[k], 0, NULL) == 0);
            ttd_meshfile_free(&m);
            free(b.p);
        }
    /* counts on the header line; quads fanned */
    const char *q = "OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    ttd_meshfile m;
    ENSURE(ttd_meshfile_parse("q.off", (const unsigned char *)q, strlen(q), 0, &m, err, sizeof err) == 0);
    ENSURE(m.nt == 2 && m.tris[3] == 0 && m.tris[4] == 2 && m.tris[5] == 3);
    ttd_meshfile_free(&m);
    /* malformed */
    static const struct {
        const char *text, *want;
    } bad[] = {
        {"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# a comment long enough for a face\n", "b.off:7: truncated: file ends at face 1 of 2"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n", "truncated: file ends at vertex 2 of 3"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "b.off:6: face 0: vertex index 3 out of range (the file has 3 vertices)"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "vertex index -1 out of range"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "face 0 has 2 vertices, at least 3 needed"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "face 0: 4 vertices declared, 3 given"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", "data after the last face"},
        {"OFF\n3 x 0\n", "'x' is not a count"},
        {"OFF\n3\n", "truncated: the counts"},
        {"OFF\n-3 1 0\n", "'-3' is not a count"},
        {"OFF\n99999999999 1 0\n0 0 0\n", "99999999999 vertices and 1 faces declared, but only"},
        {"OFF\n3 1 0\n0 0 nan\n1 0 0\n0 1 0\n3 0 1 2\n", "coordinate 'nan' is not finite"},
        {"OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "vertex 0 has 2 coordinates, 3 needed"},
        {"4OFF\n1 0 0\n0 0 0 0\n", "an OFF variant this reader does not take"},
        {"OFF BINARY\n", "binary OFF is not read"},
        {"OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "no triangles (read as off)"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k)
        ENSURE_FAILS(ttd_meshfile_parse("b.off", (const unsigned char *)bad[k].text, strlen(bad[k].text), 0, &m_, err_,
                                        sizeof err_),
                     bad[k].want);
    ttd_gen_mesh_free(&s);
    ttd_gen_mesh_free(&t);
    return 0;
}

/* ---- glTF ------------------------------------------------------------------------------ */

/* The binary buffer: positions (float32), then indices (u32, u16 or u8 as isize says). */
static void gltf_bin(buf *b, const ttd_gen_mesh *g, int isize)
{
    for (size_t i = 0; i < 3 * g->nv; ++i) {
        float f = (float)g->verts[i];
        uint32_t u;
        memcpy(&u, &f, 4);
        put32(b, u);
    }
    for (size_t i = 0; i < 3 * g->nt; ++i) {
        uint32_t v = g->tris[i];
        unsigned char x[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16), (unsigned char)(v >> 24)};
        put(b, x, (size_t)isize);
    }
    while (b->n % 4)
        put(b, "", 1);
}

/* The JSON: one mesh, one node (translated by t when not NULL), buffer 0 given by uri (NULL: GLB). */
static void gltf_json(buf *j, const ttd_gen_mesh *g, int isize, size_t binlen, const char *uri, const double *t)
{
    size_t plen = 12 * g->nv, ilen = (size_t)isize * 3 * g->nt;
    int ct = isize == 4 ? 5125 : isize == 2 ? 5123 : 5121;
    putf(j, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"test\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],");
    if (t)
        putf(j, "\"nodes\":[{\"mesh\":0,\"translation\":[%.17g,%.17g,%.17g]}],", t[0], t[1], t[2]);
    else
        putf(j, "\"nodes\":[{\"mesh\":0}],");
    putf(j, "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4}]}],");
    putf(j, "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},", g->nv);
    putf(j, "{\"bufferView\":1,\"componentType\":%d,\"count\":%zu,\"type\":\"SCALAR\"}],", ct, 3 * g->nt);
    putf(j, "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],", plen,
         plen, ilen);
    if (uri)
        putf(j, "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"%s\"}]}", binlen, uri);
    else
        putf(j, "\"buffers\":[{\"byteLength\":%zu}]}", binlen);
}

static void glb_from(buf *out, const buf *json, const buf *bin)
{
    size_t jl = (json->n + 3) / 4 * 4;
    put(out, "glTF", 4);
    put32(out, 2);
    put32(out, (uint32_t)(12 + 8 + jl + (bin ? 8 + bin->n : 0)));
    put32(out, (uint32_t)jl);
    put32(out, 0x4E4F534Au);
    put(out, json->p, json->n);
    for (size_t k = json->n; k < jl; ++k)
        put(out, " ", 1);
    if (bin) {
        put32(out, (uint32_t)bin->n);
        put32(out, 0x004E4942u);
        put(out, bin->p, bin->n);
    }
}

static void glb_mesh(buf *out, const ttd_gen_mesh *g, int isize, const double *t)
{
    buf bin = {0}, json = {0};
    gltf_bin(&bin, g, isize);
    gltf_json(&json, g, isize, bin.n, NULL, t);
    glb_from(out, &json, &bin);
    free(bin.p);
    free(json.p);
}

static void base64(buf *out, const buf *in)
{
    static const char a[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < in->n; i += 3) {
        uint32_t v = (uint32_t)in->p[i] << 16 | (i + 1 < in->n ? (uint32_t)in->p[i + 1] << 8 : 0) |
                     (i + 2 < in->n ? in->p[i + 2] : 0);
        char q[4] = {a[v >> 18], a[(v >> 12) & 63], i + 1 < in->n ? a[(v >> 6) & 63] : '=', i + 2 < in->n ? a[v & 63] : '='};
        put(out, q, 4);
    }
}

static int test_gltf(void)
{
    ttd_gen_mesh s = {0}, t = {0}, small = {0};
    ENSURE(ttd_gen_icosphere(3, &s) == 0 && ttd_gen_torus(1, 0.3, 24, 12, &t) == 0 && ttd_gen_icosphere(1, &small) == 0);
    char err[512], path[512];
    ttd_meshfile m;
    /* GLB with u32 and u16 indices, and u8 on a mesh of under 256 vertices; a translated node */
    const int isz[3] = {4, 2, 1};
    const ttd_gen_mesh *gs[3] = {&s, &t, &small};
    for (int k = 0; k < 3; ++k) {
        buf b = {0};
        glb_mesh(&b, gs[k], isz[k], NULL);
        ENSURE_MSG(parse("a.glb", &b, &m, err, sizeof err) == 0, "%s", err);
        ENSURE(m.format == TTD_MESHFILE_GLB);
        ENSURE(same_mesh(&m, gs[k], 1, NULL) == 0);
        ttd_meshfile_free(&m);
        free(b.p);
    }
    {
        const double shift[3] = {0.5, -2, 1e3};
        buf b = {0};
        glb_mesh(&b, &s, 4, shift);
        ENSURE_MSG(parse("t.glb", &b, &m, err, sizeof err) == 0, "%s", err);
        ENSURE(same_mesh(&m, &s, 1, shift) == 0);
        ttd_meshfile_free(&m);
        free(b.p);
    }
    /* .gltf with a data: URI, and with an external .bin (read from a path only) */
    {
        buf bin = {0}, b64 = {0}, json = {0};
        gltf_bin(&bin, &t, 4);
        put(&b64, "data:application/octet-stream;base64,", 37);
        base64(&b64, &bin);
        put(&b64, "", 1);
        gltf_json(&json, &t, 4, bin.n, (const char *)b64.p, NULL);
        ENSURE_MSG(parse("d.gltf", &json, &m, err, sizeof err) == 0, "%s", err);
        ENSURE(m.format == TTD_MESHFILE_GLTF && same_mesh(&m, &t, 1, NULL) == 0);
        ttd_meshfile_free(&m);
        free(json.p);
        json = (buf){0};
        gltf_json(&json, &t, 4, bin.n, "my%20mesh.bin", NULL);
        ENSURE(write_file("my mesh.bin", &bin, path, sizeof path) == 0);
        ENSURE(write_file("e.gltf", &json, path, sizeof path) == 0);
        ENSURE_MSG(ttd_meshfile_read(path, 0, &m, err, sizeof err) == 0, "%s", err);
        ENSURE(same_mesh(&m, &t, 1, NULL) == 0);
        ttd_meshfile_free(&m);
        ENSURE_FAILS(parse("e.gltf", &json, &m_, err_, sizeof err_), "a read from memory cannot open");
        /* the external file shorter than declared */
        buf half = {0};
        put(&half, bin.p, bin.n / 2);
        ENSURE(write_file("my mesh.bin", &half, path, sizeof path) == 0);
        ENSURE(write_file("e.gltf", &json, path, sizeof path) == 0);
        ENSURE_FAILS(ttd_meshfile_read(path, 0, &m_, err_, sizeof err_), "declared");
        free(half.p);
        free(bin.p);
        free(b64.p);
        free(json.p);
    }
    /* every prefix of a GLB fails with a message (truncation), never a crash */
    {
        buf b = {0};
        glb_mesh(&b, &small, 2, NULL);
        for (size_t n = 0; n < b.n; ++n) {
            int rc = ttd_meshfile_parse("cut.glb", b.p, n, 0, &m, err, sizeof err);
            ENSURE_MSG(rc == -1 && err[0] != '\0', "a GLB cut at %zu of %zu bytes: rc %d", n, b.n, rc);
            if (n >= 12)
                ENSURE_MSG(strstr(err, "truncated GLB") != NULL, "cut at %zu: %s", n, err);
        }
        free(b.p);
    }
    /* malformed JSON documents, each with a message naming the fault */
    {
        buf bin = {0};
        gltf_bin(&bin, &small, 4);
        static const struct {
            const char *from, *to, *want;
        } edits[] = {
            {"\"count\":42,", "\"count\":43,", "do not fit in bufferView"},           /* positions beyond the view */
            {"\"componentType\":5125", "\"componentType\":5126", "indices of componentType 5126"},
            {"\"componentType\":5126", "\"componentType\":5123", "positions of componentType 5123"},
            {"\"bufferView\":1,", "\"bufferView\":7,", "bufferView 7 does not exist"},
            {"\"indices\":1", "\"indices\":5", "accessor 5 does not exist"},
            {"\"POSITION\":0", "\"NORMAL\":0", "has no 'POSITION'"},
            {"\"version\":\"2.0\"", "\"version\":\"1.0\"", "only glTF 2.0 is read"},
            {"\"asset\":{", "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\"asset\":{",
             "requires the extension 'KHR_draco_mesh_compression'"},
            {"\"type\":\"VEC3\"", "\"type\":\"VEC3\",\"sparse\":{}", "is sparse"},
            {"\"byteLength\":1464}]}", "\"byteLength\":9999}]}", "buffer 0 declares 9999 bytes"},
            {"\"nodes\":[0]", "\"nodes\":[3]", "node 3 does not exist"},
            {"{\"mesh\":0}", "{\"mesh\":0,\"children\":[0]}", "deeper than 64"},
            {"\"scenes\"", "\"scenes\" 1", "expected ':'"},
        };
        buf json = {0};
        gltf_json(&json, &small, 4, bin.n, NULL, NULL);
        put(&json, "", 1);
        for (size_t k = 0; k < sizeof edits / sizeof edits[0]; ++k) {
            const char *at = strstr((const char *)json.p, edits[k].from);
            ENSURE_MSG(at != NULL, "edit %zu: '%s' not in the JSON", k, edits[k].from);
            buf e = {0}, glb = {0};
            put(&e, json.p, (size_t)(at - (const char *)json.p));
            put(&e, edits[k].to, strlen(edits[k].to));
            put(&e, at + strlen(edits[k].from), strlen(at + strlen(edits[k].from)));
            glb_from(&glb, &e, &bin);
            ENSURE_FAILS(parse("bad.glb", &glb, &m_, err_, sizeof err_), edits[k].want);
            free(e.p);
            free(glb.p);
        }
        /* an index beyond the positions, written into the binary chunk */
        buf bad = {0};
        put(&bad, bin.p, bin.n);
        uint32_t big = 42;
        memcpy(bad.p + 12 * small.nv + 4 * 7, &big, 4);
        buf glb = {0};
        json.n--; /* drop the NUL */
        glb_from(&glb, &json, &bad);
        ENSURE_FAILS(parse("idx.glb", &glb, &m_, err_, sizeof err_), "index 42 (element 7 of accessor 1) out of range: POSITION has 42");
        free(bad.p);
        free(glb.p);
        free(json.p);
        free(bin.p);
    }
    ttd_gen_mesh_free(&s);
    ttd_gen_mesh_free(&t);
    ttd_gen_mesh_free(&small);
    return 0;
}

/* ---- 3MF --------------------------------------------------------------------------------- */

static uint32_t crc32_of(const unsigned char *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k)
            c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1)));
    }
    return ~c;
}

static void put16(buf *b, unsigned v)
{
    unsigned char x[2] = {(unsigned char)v, (unsigned char)(v >> 8)};
    put(b, x, 2);
}

/* A zip of stored entries (names[k] holding parts[k]). */
static void zip_stored(buf *z, const char *const *names, const buf *parts, int n)
{
    size_t off[8];
    for (int k = 0; k < n; ++k) {
        off[k] = z->n;
        put32(z, 0x04034b50u), put16(z, 20), put16(z, 0), put16(z, 0), put16(z, 0), put16(z, 0);
        put32(z, crc32_of(parts[k].p, parts[k].n)), put32(z, (uint32_t)parts[k].n), put32(z, (uint32_t)parts[k].n);
        put16(z, (unsigned)strlen(names[k])), put16(z, 0);
        put(z, names[k], strlen(names[k]));
        put(z, parts[k].p, parts[k].n);
    }
    size_t cd = z->n;
    for (int k = 0; k < n; ++k) {
        put32(z, 0x02014b50u), put16(z, 20), put16(z, 20), put16(z, 0), put16(z, 0), put16(z, 0), put16(z, 0);
        put32(z, crc32_of(parts[k].p, parts[k].n)), put32(z, (uint32_t)parts[k].n), put32(z, (uint32_t)parts[k].n);
        put16(z, (unsigned)strlen(names[k])), put16(z, 0), put16(z, 0), put16(z, 0), put16(z, 0), put32(z, 0);
        put32(z, (uint32_t)off[k]);
        put(z, names[k], strlen(names[k]));
    }
    size_t cdlen = z->n - cd;
    put32(z, 0x06054b50u), put16(z, 0), put16(z, 0), put16(z, (unsigned)n), put16(z, (unsigned)n);
    put32(z, (uint32_t)cdlen), put32(z, (uint32_t)cd), put16(z, 0);
}

/* g as a 3MF: one object placed once (translated by t when not NULL). */
static void threemf_mesh(buf *out, const ttd_gen_mesh *g, const double *t, const char *model_name)
{
    buf parts[3] = {{0}, {0}, {0}};
    putf(&parts[0], "<?xml version=\"1.0\" encoding=\"UTF-8\"?><Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"/>");
    putf(&parts[1], "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">"
                    "<Relationship Target=\"/%s\" Id=\"rel0\" Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></Relationships>",
         model_name);
    buf *m = &parts[2];
    putf(m, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!-- written by test_meshfile_formats -->\n"
            "<model unit=\"millimeter\" xml:lang=\"en-US\" xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n"
            "<resources><object id=\"7\" type=\"model\"><mesh><vertices>\n");
    for (size_t i = 0; i < g->nv; ++i)
        putf(m, "<vertex x=\"%.17g\" y=\"%.17g\" z=\"%.17g\" />\n", g->verts[3 * i], g->verts[3 * i + 1], g->verts[3 * i + 2]);
    putf(m, "</vertices><triangles>\n");
    for (size_t k = 0; k < g->nt; ++k)
        putf(m, "<triangle v1=\"%u\" v2=\"%u\" v3=\"%u\"/>\n", g->tris[3 * k], g->tris[3 * k + 1], g->tris[3 * k + 2]);
    putf(m, "</triangles></mesh></object></resources>\n<build>");
    if (t)
        putf(m, "<item objectid=\"7\" transform=\"1 0 0 0 1 0 0 0 1 %.17g %.17g %.17g\"/>", t[0], t[1], t[2]);
    else
        putf(m, "<item objectid=\"7\"/>");
    putf(m, "</build></model>\n");
    const char *names[3] = {"[Content_Types].xml", "_rels/.rels", model_name};
    zip_stored(out, names, parts, 3);
    for (int k = 0; k < 3; ++k)
        free(parts[k].p);
}

static int test_3mf(void)
{
    ttd_gen_mesh s = {0}, t = {0};
    ENSURE(ttd_gen_icosphere(2, &s) == 0 && ttd_gen_torus(1, 0.3, 16, 8, &t) == 0);
    char err[512];
    ttd_meshfile m;
    const ttd_gen_mesh *gs[2] = {&s, &t};
    for (int k = 0; k < 2; ++k) {
        buf b = {0};
        threemf_mesh(&b, gs[k], NULL, "3D/3dmodel.model");
        ENSURE_MSG(parse("a.3mf", &b, &m, err, sizeof err) == 0, "%s", err);
        ENSURE(m.format == TTD_MESHFILE_3MF && same_mesh(&m, gs[k], 0, NULL) == 0);
        for (size_t i = 0; i < 3 * m.nv; ++i) /* floats by strtof on the text: the double's rounding */
            ENSURE(m.verts_f[i] == (float)gs[k]->verts[i]);
        ttd_meshfile_free(&m);
        free(b.p);
    }
    {
        const double shift[3] = {4, 0.25, -8};
        buf b = {0};
        threemf_mesh(&b, &s, shift, "3D/Model.model");
        ENSURE_MSG(parse("t.3mf", &b, &m, err, sizeof err) == 0, "%s", err);
        ENSURE(m.nv == s.nv && m.nt == s.nt);
        for (size_t i = 0; i < 3 * s.nv; ++i)
            ENSURE(m.verts[i] == s.verts[i] + shift[i % 3]);
        ttd_meshfile_free(&m);
        /* every prefix fails with a message */
        for (size_t n = 0; n < b.n; n += 1 + n / 64)
            ENSURE_MSG(ttd_meshfile_parse("cut.3mf", b.p, n, 0, &m, err, sizeof err) == -1 && err[0], "cut at %zu", n);
        free(b.p);
    }
    /* malformed models */
    static const struct {
        const char *from, *to, *want;
    } edits[] = {
        {"v3=\"2\"", "v3=\"99\"", "v3 = 99 out of range (the object has 42 vertices)"},
        {"<item objectid=\"7\"/>", "<item objectid=\"8\"/>", "object 8 does not exist"},
        {"<item objectid=\"7\"/>", "", "the model's build places no object"},
        {"<item objectid=\"7\"/>", "<item objectid=\"7\" transform=\"1 0 0\"/>", "is not 12 finite numbers"},
        {"x=\"0\"", "x=\"abc\"", "'x' = 'abc' is not a finite number"},
        {"</model>", "<object", "ends inside a tag"},
        {"3D/3dmodel.model\" Id", "3D/other.model\" Id", "'3D/other.model' is named but absent"},
    };
    ttd_gen_mesh small = {0};
    ENSURE(ttd_gen_icosphere(1, &small) == 0);
    for (size_t k = 0; k < sizeof edits / sizeof edits[0]; ++k) {
        buf b = {0};
        threemf_mesh(&b, &small, NULL, "3D/3dmodel.model");
        /* edit inside the stored zip: same-length edits keep the sizes; others are rebuilt */
        unsigned char *at = NULL;
        for (size_t q = 0; q + strlen(edits[k].from) <= b.n && !at; ++q)
            if (memcmp(b.p + q, edits[k].from, strlen(edits[k].from)) == 0)
                at = b.p + q;
        ENSURE_MSG(at != NULL, "edit %zu: '%s' absent", k, edits[k].from);
        /* rebuild with the edit applied to the text of the part that holds it */
        buf e = {0};
        put(&e, b.p, (size_t)(at - b.p));
        put(&e, edits[k].to, strlen(edits[k].to));
        size_t rest = (size_t)(at - b.p) + strlen(edits[k].from);
        put(&e, b.p + rest, b.n - rest);
        /* sizes in the headers are now off by the difference: rewrite the archive from its parts */
        free(b.p);
        {
            /* re-split: find the three local entries by their names and take their data up to
             * the next local header (the edit changed one part's length) */
            const char *names[3] = {"[Content_Types].xml", "_rels/.rels", "3D/3dmodel.model"};
            buf parts[3] = {{0}, {0}, {0}};
            size_t pos = 0;
            for (int q = 0; q < 3; ++q) {
                size_t nl = (size_t)(e.p[pos + 26] | e.p[pos + 27] << 8);
                size_t start = pos + 30 + nl, stop = start;
                while (stop + 4 <= e.n && !(e.p[stop] == 'P' && e.p[stop + 1] == 'K' && (e.p[stop + 2] == 3 || e.p[stop + 2] == 1)))
                    ++stop;
                put(&parts[q], e.p + start, stop - start);
                pos = stop;
            }
            buf z = {0};
            zip_stored(&z, names, parts, 3);
            ENSURE_FAILS(parse("bad.3mf", &z, &m_, err_, sizeof err_), edits[k].want);
            for (int q = 0; q < 3; ++q)
                free(parts[q].p);
            free(z.p);
        }
        free(e.p);
    }
    /* a zip without a model, and an unknown compression method */
    {
        const char *names[1] = {"readme.txt"};
        buf parts[1] = {{0}};
        putf(&parts[0], "hello");
        buf z = {0};
        zip_stored(&z, names, parts, 1);
        ENSURE_FAILS(parse("x.zip", &z, &m_, err_, sizeof err_), "a zip archive without a 3D model part: not a 3MF file");
        free(z.p);
        free(parts[0].p);
        buf b = {0};
        threemf_mesh(&b, &small, NULL, "3D/3dmodel.model");
        b.p[8] = 14; /* the first local header's method: LZMA; the model's central entry too */
        for (size_t q = 0; q + 4 <= b.n; ++q)
            if (b.p[q] == 'P' && b.p[q + 1] == 'K' && b.p[q + 2] == 1 && b.p[q + 3] == 2)
                b.p[q + 10] = 14;
        ENSURE_FAILS(parse("m.3mf", &b, &m_, err_, sizeof err_), "compressed by method 14");
        free(b.p);
    }
    ttd_gen_mesh_free(&small);
    ttd_gen_mesh_free(&s);
    ttd_gen_mesh_free(&t);
    return 0;
}

/* ---- formats recognised and refused by name ---------------------------------------------- */

static int test_magic(void)
{
    static const struct {
        const char *bytes;
        size_t n;
        const char *want;
    } cases[] = {
        {"PK\x03\x04\x14\0\0\0\x08\0" "3D/3dmodel.model", 26, "truncated or damaged zip archive (3MF)"},
        {"PK\x05\x06\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0", 22, "an empty zip archive"},
        {"\x1f\x8b\x08\0\0\0\0\0", 8, "gzip-compressed data"},
        {"Kaydara FBX Binary  \0\x1a\0", 23, "a binary FBX file"},
        {"ISO-10303-21;\nHEADER;\n", 22, "a STEP file"},
        {"<?xml version=\"1.0\"?>\n<COLLADA>", 31, "an XML file"},
        {"glTF\x01\0\0\0\x14\0\0\0\0\0\0\0\0\0\0\0", 20, "GLB version 1: only glTF 2.0 is read"},
        {"glTF\x02\0\0\0\xff\0\0\0\0\0\0\0\0\0\0\0", 20, "truncated GLB: its header says 255 bytes, the file has 20"},
        {"{\"not\":\"gltf\"}", 14, "a JSON file without \"asset\": not glTF"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        ENSURE_FAILS(ttd_meshfile_parse("x", (const unsigned char *)cases[k].bytes, cases[k].n, 0, &m_, err_, sizeof err_),
                     cases[k].want);
    }
    /* a GLB whose size happens to read as a binary STL's (84 + 50 n) is still GLB */
    ttd_gen_mesh g = {0};
    ENSURE(ttd_gen_mesh_tetrahedron(&g) == 0);
    buf b = {0};
    glb_mesh(&b, &g, 4, NULL);
    ttd_meshfile m;
    char err[512];
    ENSURE_MSG(parse("tet.glb", &b, &m, err, sizeof err) == 0, "%s", err);
    ENSURE(m.format == TTD_MESHFILE_GLB && m.nt == 4);
    ttd_meshfile_free(&m);
    free(b.p);
    ttd_gen_mesh_free(&g);
    return 0;
}

/* ---- assimp, the independent reader ------------------------------------------------------ */

#ifdef TTD_HAVE_ASSIMP
static size_t assimp_triangles(const char *path, int *ok)
{
    const struct aiScene *sc = aiImportFile(path, aiProcess_Triangulate);
    *ok = sc != NULL;
    if (!sc) {
        fprintf(stderr, "  assimp cannot read %s: %s\n", path, aiGetErrorString());
        return 0;
    }
    size_t n = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; ++i)
        for (unsigned f = 0; f < sc->mMeshes[i]->mNumFaces; ++f)
            n += sc->mMeshes[i]->mFaces[f].mNumIndices == 3;
    aiReleaseImport(sc);
    return n;
}

/* Triangles as sorted corner triples, each rotated to start at its smallest corner, coordinates
 * on a grid of 2^-16: assimp reads text coordinates with its own parser, which can be an ulp off
 * the correctly rounded value (1.0409497605e-16 read as 1.04094982e-16, not ...76e-16). */
static int cmp9(const void *a, const void *b)
{
    const float *p = a, *q = b;
    for (int k = 0; k < 9; ++k)
        if (p[k] != q[k])
            return p[k] < q[k] ? -1 : 1;
    return 0;
}

static int cmp3f(const float *p, const float *q)
{
    for (int k = 0; k < 3; ++k)
        if (p[k] != q[k])
            return p[k] < q[k] ? -1 : 1;
    return 0;
}

static float *triangle_set(const double *v, const uint32_t *t, size_t nt)
{
    float *out = malloc(9 * nt * sizeof *out);
    for (size_t f = 0; f < nt; ++f) {
        float c[3][3];
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d)
                c[k][d] = (float)(nearbyint(v[3 * (size_t)t[3 * f + (size_t)k] + (size_t)d] * 65536) / 65536) + 0.0f;
        int s = 0;
        for (int k = 1; k < 3; ++k)
            if (cmp3f(c[k], c[s]) < 0)
                s = k;
        for (int k = 0; k < 3; ++k)
            memcpy(out + 9 * f + 3 * k, c[(s + k) % 3], 12);
    }
    qsort(out, nt, 9 * sizeof *out, cmp9);
    return out;
}
#endif

static int test_against_assimp(void)
{
#ifndef TTD_HAVE_ASSIMP
    printf("  SKIPPED: assimp (libassimp-dev) not found when this was built: no comparison with an independent reader\n");
    return 0;
#else
    ttd_gen_mesh s = {0}, t = {0};
    ENSURE(ttd_gen_icosphere(3, &s) == 0 && ttd_gen_torus(1, 0.3, 24, 12, &t) == 0);
    const ttd_gen_mesh *gs[2] = {&s, &t};
    char path[512], out[512], err[512];
    for (int k = 0; k < 2; ++k) {
        /* the files written here: our count equals assimp's */
        buf off = {0}, glb = {0}, bin = {0}, json = {0}, tmf = {0};
        write_off(&off, gs[k], "OFF", 0);
        threemf_mesh(&tmf, gs[k], NULL, "3D/3dmodel.model");
        glb_mesh(&glb, gs[k], 4, NULL);
        gltf_bin(&bin, gs[k], 4);
        gltf_json(&json, gs[k], 4, bin.n, "m.bin", NULL);
        const struct {
            const char *name;
            const buf *b;
        } files[] = {{"m.off", &off}, {"m.glb", &glb}, {"m.gltf", &json}, {"m.3mf", &tmf}};
        ENSURE(write_file("m.bin", &bin, path, sizeof path) == 0);
        for (int f = 0; f < 4; ++f) {
            ENSURE(write_file(files[f].name, files[f].b, path, sizeof path) == 0);
            ttd_meshfile m;
            ENSURE_MSG(ttd_meshfile_read(path, 0, &m, err, sizeof err) == 0, "%s", err);
            int ok;
            size_t n = assimp_triangles(path, &ok);
            ENSURE(ok);
            ENSURE_MSG(m.nt == n && n == gs[k]->nt, "%s: %zu triangles here, %zu by assimp", files[f].name, m.nt, n);
            ttd_meshfile_free(&m);
        }
        /* files assimp writes from the OFF: the same triangles here */
        snprintf(path, sizeof path, "%s/m.off", tmpdir);
        const struct aiScene *sc = aiImportFile(path, aiProcess_Triangulate);
        ENSURE(sc != NULL);
        float *want = triangle_set(gs[k]->verts, gs[k]->tris, gs[k]->nt);
        static const char *const fmts[][2] = {{"glb2", "x.glb"}, {"gltf2", "x.gltf"}, {"obj", "x.obj"},
                                              {"stl", "x.stl"},  {"stlb", "xb.stl"}, {"ply", "x.ply"},
                                              {"plyb", "xb.ply"}};
        for (size_t f = 0; f < sizeof fmts / sizeof fmts[0]; ++f) {
            snprintf(out, sizeof out, "%s/%s", tmpdir, fmts[f][1]);
            if (aiExportScene(sc, fmts[f][0], out, 0) != aiReturn_SUCCESS) {
                printf("  assimp cannot write %s here (%s): skipped\n", fmts[f][0], aiGetErrorString());
                continue;
            }
            ttd_meshfile m;
            ENSURE_MSG(ttd_meshfile_read(out, 0, &m, err, sizeof err) == 0, "%s: %s", fmts[f][0], err);
            ENSURE_MSG(m.nt == gs[k]->nt, "assimp's %s: %zu triangles, %zu written", fmts[f][0], m.nt, gs[k]->nt);
            float *got = triangle_set(m.verts, m.tris, m.nt);
            for (size_t q = 0; q < 9 * m.nt; ++q)
                ENSURE_MSG(got[q] == want[q], "assimp's %s: other triangles: %zu: %.9g, %.9g", fmts[f][0], q,
                           (double)got[q], (double)want[q]);
            free(got);
            ttd_meshfile_free(&m);
        }
        aiReleaseImport(sc);
        free(want);
        free(off.p), free(glb.p), free(bin.p), free(json.p), free(tmf.p);
    }
    ttd_gen_mesh_free(&s);
    ttd_gen_mesh_free(&t);
    return 0;
#endif
}

static int remove_tmpdir(void)
{
    static const char *const names[] = {"my mesh.bin", "e.gltf", "m.off", "m.glb", "m.gltf", "m.bin", "x.glb",
                                        "x.gltf", "x.bin", "x.obj", "x.mtl", "x.stl", "xb.stl", "x.ply", "xb.ply", "m.3mf"};
    char path[512];
    for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k) {
        snprintf(path, sizeof path, "%s/%s", tmpdir, names[k]);
        unlink(path);
    }
    ENSURE(rmdir(tmpdir) == 0);
    return 0;
}

int main(int argc, char **argv)
{
    snprintf(tmpdir, sizeof tmpdir, "%s/ttd_formats_XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmpdir)) {
        perror("mkdtemp");
        return 2;
    }
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(test_obj_forms);
    RUN_TEST(test_off);
    RUN_TEST(test_gltf);
    RUN_TEST(test_3mf);
    RUN_TEST(test_magic);
    RUN_TEST(test_against_assimp);
    RUN_TEST(remove_tmpdir);
    TEST_MAIN_END();
}
