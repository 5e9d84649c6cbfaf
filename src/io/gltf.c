/* SPDX-License-Identifier: MIT */
/* glTF 2.0 for the mesh-file reader: a GLB container (a 12-byte header, a JSON chunk, an optional
 * binary chunk) or a .gltf JSON text whose buffers are data: URIs (base64) or files beside it.
 * Only what a triangle mesh needs is read: the default scene's node tree (matrix or TRS, composed
 * down the tree, each mesh instance's positions moved by its node's world matrix), each
 * primitive's POSITION accessor (float VEC3) and its indices (unsigned byte, short or int;
 * none: 0 .. count - 1), modes TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN (points and lines are
 * skipped). A file without scenes gives every mesh once, unmoved.
 *
 * The JSON reader is a small recursive descent into a node array (values, with objects' keys as
 * raw slices of the text), depth-limited; every offset, length, stride and count read from the
 * file is checked against the bytes that exist before it is used, and every index against the
 * positions it indexes, so a malformed file gives a message, never a read outside a buffer. */
#define _POSIX_C_SOURCE 200809L

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/reader.h"

/* ---- JSON ------------------------------------------------------------------------------ */

enum { J_NULL, J_FALSE, J_TRUE, J_NUM, J_STR, J_ARR, J_OBJ };

typedef struct jnode {
    int type;
    double num;
    size_t s, len;        /* J_STR: the raw text between the quotes */
    size_t key, key_len;  /* an object member's key: raw text */
    uint32_t first, next; /* first child, next sibling; UINT32_MAX none */
    uint32_t count;       /* children */
} jnode;

typedef struct json {
    const uchar *p;
    size_t size, pos;
    jnode *n;
    size_t nn, cap;
    ctx *c;
    size_t base; /* where the JSON starts in the file, for byte offsets in messages */
} json;

#define JSON_MAX_DEPTH 64

static void j_ws(json *j)
{
    while (j->pos < j->size && (j->p[j->pos] == ' ' || j->p[j->pos] == '\t' || j->p[j->pos] == '\n' || j->p[j->pos] == '\r'))
        ++j->pos;
}

static int j_err(json *j, const char *what)
{
    return ttd_io_fail_at(j->c, j->base + j->pos, "glTF JSON: %s", what);
}

static int j_new(json *j, int type, uint32_t *out)
{
    if (j->nn == j->cap) {
        size_t cap = j->cap ? 2 * j->cap : 256;
        if (cap > UINT32_MAX - 1)
            return ttd_io_oom(j->c);
        jnode *n = realloc(j->n, cap * sizeof *n);
        if (!n)
            return ttd_io_oom(j->c);
        j->n = n;
        j->cap = cap;
    }
    jnode *x = j->n + j->nn;
    memset(x, 0, sizeof *x);
    x->type = type;
    x->first = x->next = UINT32_MAX;
    *out = (uint32_t)j->nn++;
    return 0;
}

/* A string's raw extent (escapes checked for shape only); pos at the opening quote. */
static int j_string(json *j, size_t *s, size_t *len)
{
    ++j->pos;
    *s = j->pos;
    while (j->pos < j->size && j->p[j->pos] != '"') {
        uchar ch = j->p[j->pos];
        if (ch < 0x20)
            return j_err(j, "control character in a string");
        if (ch == '\\') {
            if (j->pos + 1 >= j->size)
                return j_err(j, "truncated string");
            uchar e = j->p[j->pos + 1];
            if (e == 'u') {
                if (j->size - j->pos < 6)
                    return j_err(j, "truncated \\u escape");
                j->pos += 6;
                continue;
            }
            if (!strchr("\"\\/bfnrt", e))
                return j_err(j, "bad escape in a string");
            j->pos += 2;
            continue;
        }
        ++j->pos;
    }
    if (j->pos >= j->size)
        return j_err(j, "unterminated string");
    *len = j->pos - *s;
    ++j->pos;
    return 0;
}

static int j_value(json *j, int depth, uint32_t *out);

static int j_container(json *j, int depth, int obj, uint32_t *out)
{
    uint32_t me;
    if (j_new(j, obj ? J_OBJ : J_ARR, &me) != 0)
        return -1;
    ++j->pos;
    j_ws(j);
    uint32_t last = UINT32_MAX;
    if (j->pos < j->size && j->p[j->pos] == (obj ? '}' : ']')) {
        ++j->pos;
        *out = me;
        return 0;
    }
    for (;;) {
        size_t ks = 0, kl = 0;
        if (obj) {
            j_ws(j);
            if (j->pos >= j->size || j->p[j->pos] != '"')
                return j_err(j, "expected a key");
            if (j_string(j, &ks, &kl) != 0)
                return -1;
            j_ws(j);
            if (j->pos >= j->size || j->p[j->pos] != ':')
                return j_err(j, "expected ':'");
            ++j->pos;
        }
        uint32_t child;
        if (j_value(j, depth + 1, &child) != 0)
            return -1;
        j->n[child].key = ks;
        j->n[child].key_len = kl;
        if (last == UINT32_MAX)
            j->n[me].first = child;
        else
            j->n[last].next = child;
        last = child;
        j->n[me].count++;
        j_ws(j);
        if (j->pos >= j->size)
            return j_err(j, "truncated");
        if (j->p[j->pos] == ',') {
            ++j->pos;
            continue;
        }
        if (j->p[j->pos] == (obj ? '}' : ']')) {
            ++j->pos;
            *out = me;
            return 0;
        }
        return j_err(j, obj ? "expected ',' or '}'" : "expected ',' or ']'");
    }
}

static int j_value(json *j, int depth, uint32_t *out)
{
    if (depth > JSON_MAX_DEPTH)
        return j_err(j, "nested too deeply");
    j_ws(j);
    if (j->pos >= j->size)
        return j_err(j, "truncated");
    uchar ch = j->p[j->pos];
    if (ch == '{' || ch == '[')
        return j_container(j, depth, ch == '{', out);
    if (ch == '"') {
        if (j_new(j, J_STR, out) != 0)
            return -1;
        size_t s, len;
        if (j_string(j, &s, &len) != 0)
            return -1;
        j->n[*out].s = s;
        j->n[*out].len = len;
        return 0;
    }
    static const struct {
        const char *w;
        int type;
    } words[] = {{"null", J_NULL}, {"false", J_FALSE}, {"true", J_TRUE}};
    for (int k = 0; k < 3; ++k) {
        size_t wl = strlen(words[k].w);
        if (j->size - j->pos >= wl && memcmp(j->p + j->pos, words[k].w, wl) == 0) {
            j->pos += wl;
            return j_new(j, words[k].type, out);
        }
    }
    if (ch == '-' || (ch >= '0' && ch <= '9')) {
        char buf[64];
        size_t k = 0;
        while (j->pos + k < j->size && k < sizeof buf - 1 && strchr("+-0123456789.eE", j->p[j->pos + k]))
            ++k;
        memcpy(buf, j->p + j->pos, k);
        buf[k] = '\0';
        char *end;
        double v = strtod(buf, &end);
        if (end != buf + k || k == 0 || k == sizeof buf - 1)
            return j_err(j, "bad number");
        j->pos += k;
        if (j_new(j, J_NUM, out) != 0)
            return -1;
        j->n[*out].num = v;
        return 0;
    }
    return j_err(j, "unexpected character");
}

/* ---- access -------------------------------------------------------------------------- */

typedef struct gltf {
    ctx *c;
    json j;
    uint32_t root;
    const uchar *bin; /* GLB's binary chunk, or NULL */
    size_t bin_len;
    const uchar **bufs; /* each buffer's bytes once loaded (NULL: not yet) */
    size_t *buf_len;
    int *buf_own;     /* 1: allocated here */
    size_t nbufs;
    size_t instances; /* mesh instances placed so far (a node graph's blow-up is bounded) */
} gltf;

static const jnode *jn(const gltf *g, uint32_t i) { return i == UINT32_MAX ? NULL : g->j.n + i; }

/* The member key of an object (NULL: absent or not an object). */
static const jnode *get(const gltf *g, const jnode *obj, const char *key)
{
    if (!obj || obj->type != J_OBJ)
        return NULL;
    size_t kl = strlen(key);
    for (uint32_t i = obj->first; i != UINT32_MAX; i = g->j.n[i].next) {
        const jnode *m = g->j.n + i;
        if (m->key_len == kl && memcmp(g->j.p + m->key, key, kl) == 0)
            return m;
    }
    return NULL;
}

/* Element i of an array (NULL: out of range or not an array). */
static const jnode *at(const gltf *g, const jnode *arr, size_t i)
{
    if (!arr || arr->type != J_ARR || i >= arr->count)
        return NULL;
    uint32_t k = arr->first;
    for (size_t n = 0; n < i; ++n)
        k = g->j.n[k].next;
    return jn(g, k);
}

/* An integer member in [0, hi]: 0 with *out, 1 when absent (*out = dflt), -1 after a message. */
static int get_uint(gltf *g, const jnode *obj, const char *key, double hi, size_t dflt, const char *what, size_t *out)
{
    const jnode *v = get(g, obj, key);
    if (!v) {
        *out = dflt;
        return 1;
    }
    if (v->type != J_NUM || !(v->num >= 0) || v->num > hi || v->num != floor(v->num))
        return ttd_io_fail(g->c, "glTF: %s: '%s' is not a whole number in 0 .. %.0f", what, key, hi);
    *out = (size_t)v->num;
    return 0;
}

/* A required integer member: 0 with *out, or -1 after a message (absent included). */
static int need_uint(gltf *g, const jnode *obj, const char *key, double hi, const char *what, size_t *out)
{
    int r = get_uint(g, obj, key, hi, 0, what, out);
    if (r == 1)
        return ttd_io_fail(g->c, "glTF: %s has no '%s'", what, key);
    return r;
}

static int str_is(const gltf *g, const jnode *v, const char *s)
{
    return v && v->type == J_STR && v->len == strlen(s) && memcmp(g->j.p + v->s, s, v->len) == 0;
}

/* ---- buffers --------------------------------------------------------------------------- */

static int b64(uchar ch)
{
    if (ch >= 'A' && ch <= 'Z')
        return ch - 'A';
    if (ch >= 'a' && ch <= 'z')
        return ch - 'a' + 26;
    if (ch >= '0' && ch <= '9')
        return ch - '0' + 52;
    return ch == '+' ? 62 : ch == '/' ? 63 : -1;
}

static int load_buffer(gltf *g, size_t i)
{
    char what[48];
    snprintf(what, sizeof what, "buffer %zu", i);
    const jnode *b = at(g, get(g, jn(g, g->root), "buffers"), i);
    if (!b)
        return ttd_io_fail(g->c, "glTF: buffer %zu does not exist", i);
    size_t len;
    if (need_uint(g, b, "byteLength", 9e15, what, &len) != 0)
        return -1;
    const jnode *uri = get(g, b, "uri");
    if (!uri) {
        if (i != 0 || !g->bin)
            return ttd_io_fail(g->c, "glTF: %s has no uri and the file has no binary chunk", what);
        if (g->bin_len < len)
            return ttd_io_fail(g->c, "glTF: %s declares %zu bytes, the binary chunk holds %zu", what, len, g->bin_len);
        g->bufs[i] = g->bin;
        g->buf_len[i] = len;
        return 0;
    }
    if (uri->type != J_STR)
        return ttd_io_fail(g->c, "glTF: %s: uri is not a string", what);
    const uchar *u = g->j.p + uri->s;
    size_t ul = uri->len;
    if (ul >= 5 && memcmp(u, "data:", 5) == 0) {
        const uchar *comma = memchr(u, ',', ul);
        if (!comma || comma - u < 7 || memcmp(comma - 7, ";base64", 7) != 0)
            return ttd_io_fail(g->c, "glTF: %s: a data: uri that is not base64", what);
        const uchar *d = comma + 1, *e = u + ul;
        uchar *out = malloc((size_t)(e - d) / 4 * 3 + 3);
        if (!out)
            return ttd_io_oom(g->c);
        size_t n = 0;
        uint32_t acc = 0;
        int bits = 0;
        for (; d < e; ++d) {
            if (*d == '=')
                break;
            int x = b64(*d);
            if (x < 0) {
                free(out);
                return ttd_io_fail(g->c, "glTF: %s: a character that is not base64 in its data: uri", what);
            }
            acc = acc << 6 | (uint32_t)x;
            bits += 6;
            if (bits >= 8) {
                bits -= 8;
                out[n++] = (uchar)(acc >> bits);
            }
        }
        if (n < len) {
            free(out);
            return ttd_io_fail(g->c, "glTF: %s declares %zu bytes, its data: uri holds %zu", what, len, n);
        }
        g->bufs[i] = out;
        g->buf_len[i] = len;
        g->buf_own[i] = 1;
        return 0;
    }
    /* a relative file name, percent-decoded */
    if (memchr(u, ':', ul) || (ul > 0 && (u[0] == '/' || u[0] == '\\')))
        return ttd_io_fail(g->c, "glTF: %s: uri '%.*s' is not a file beside the .gltf (absolute paths and schemes are not read)",
                           what, (int)(ul > 80 ? 80 : ul), (const char *)u);
    if (!g->c->dir)
        return ttd_io_fail(g->c, "glTF: %s is the file '%.*s', which a read from memory cannot open", what,
                           (int)(ul > 80 ? 80 : ul), (const char *)u);
    size_t dl = strlen(g->c->dir);
    char *path = malloc(dl + ul + 2);
    if (!path)
        return ttd_io_oom(g->c);
    memcpy(path, g->c->dir, dl);
    size_t pl = dl;
    if (dl > 0)
        path[pl++] = '/';
    for (size_t k = 0; k < ul; ++k) {
        if (u[k] == '%' && k + 2 < ul && isxdigit(u[k + 1]) && isxdigit(u[k + 2])) {
            char hx[3] = {(char)u[k + 1], (char)u[k + 2], 0};
            path[pl++] = (char)strtol(hx, NULL, 16);
            k += 2;
        } else {
            path[pl++] = (char)u[k];
        }
    }
    path[pl] = '\0';
    if (strlen(path) != pl) {
        free(path);
        return ttd_io_fail(g->c, "glTF: %s: uri holds a NUL byte", what);
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        int e = errno;
        ttd_io_fail(g->c, "glTF: %s: cannot open '%s': %s", what, path, strerror(e));
        free(path);
        return -1;
    }
    uchar *out = malloc(len ? len : 1);
    size_t got = out ? fread(out, 1, len, f) : 0;
    fclose(f);
    if (!out) {
        free(path);
        return ttd_io_oom(g->c);
    }
    if (got < len) {
        ttd_io_fail(g->c, "glTF: %s: '%s' holds %zu bytes, %zu declared", what, path, got, len);
        free(path);
        free(out);
        return -1;
    }
    free(path);
    g->bufs[i] = out;
    g->buf_len[i] = len;
    g->buf_own[i] = 1;
    return 0;
}

/* An accessor's bytes: *p the first element, *stride, *count; checks every bound. comp: the
 * component type wanted (0: any of the index types), type "VEC3" or "SCALAR". */
static int accessor(gltf *g, size_t ai, const char *type, int want_float, const uchar **p, size_t *stride,
                    size_t *count, size_t *csize)
{
    char what[48];
    snprintf(what, sizeof what, "accessor %zu", ai);
    const jnode *root = jn(g, g->root), *a = at(g, get(g, root, "accessors"), ai);
    if (!a)
        return ttd_io_fail(g->c, "glTF: accessor %zu does not exist", ai);
    if (get(g, a, "sparse"))
        return ttd_io_fail(g->c, "glTF: %s is sparse, which is not read", what);
    size_t ct, n, off, vi;
    if (need_uint(g, a, "componentType", 1e6, what, &ct) != 0 || need_uint(g, a, "count", 9e15, what, &n) != 0)
        return -1;
    if (!str_is(g, get(g, a, "type"), type))
        return ttd_io_fail(g->c, "glTF: %s is not of type %s", what, type);
    if (want_float) {
        if (ct != 5126)
            return ttd_io_fail(g->c, "glTF: %s: positions of componentType %zu (only 5126, float, is read)", what, ct);
        *csize = 4;
    } else {
        if (ct != 5121 && ct != 5123 && ct != 5125)
            return ttd_io_fail(g->c, "glTF: %s: indices of componentType %zu (5121, 5123 or 5125 needed)", what, ct);
        *csize = ct == 5121 ? 1 : ct == 5123 ? 2 : 4;
    }
    if (get_uint(g, a, "byteOffset", 9e15, 0, what, &off) < 0)
        return -1;
    size_t elem = (want_float ? 3 : 1) * *csize;
    *count = n;
    int has_view = get_uint(g, a, "bufferView", 1e9, 0, what, &vi);
    if (has_view < 0)
        return -1;
    if (has_view == 1)
        return ttd_io_fail(g->c, "glTF: %s has no bufferView (all zeros), which is not read", what);
    const jnode *v = at(g, get(g, root, "bufferViews"), vi);
    if (!v)
        return ttd_io_fail(g->c, "glTF: %s: bufferView %zu does not exist", what, vi);
    size_t bi, voff, vlen, vstride;
    char vwhat[48];
    snprintf(vwhat, sizeof vwhat, "bufferView %zu", vi);
    if (need_uint(g, v, "buffer", 1e9, vwhat, &bi) != 0 || need_uint(g, v, "byteLength", 9e15, vwhat, &vlen) != 0)
        return -1;
    if (get_uint(g, v, "byteOffset", 9e15, 0, vwhat, &voff) < 0)
        return -1;
    int has_stride = get_uint(g, v, "byteStride", 252, 0, vwhat, &vstride);
    if (has_stride < 0)
        return -1;
    *stride = has_stride == 0 ? vstride : elem;
    if (*stride < elem)
        return ttd_io_fail(g->c, "glTF: %s: byteStride %zu is shorter than an element (%zu bytes)", vwhat, *stride, elem);
    if (bi >= g->nbufs)
        return ttd_io_fail(g->c, "glTF: %s: buffer %zu does not exist", vwhat, bi);
    if (!g->bufs[bi] && load_buffer(g, bi) != 0)
        return -1;
    if (voff > g->buf_len[bi] || vlen > g->buf_len[bi] - voff)
        return ttd_io_fail(g->c, "glTF: %s: bytes %zu .. %zu lie beyond buffer %zu (%zu bytes)", vwhat, voff, voff + vlen, bi,
                           g->buf_len[bi]);
    if (n > 0 && (off > vlen || (n - 1) > (vlen - off) / *stride || (n - 1) * *stride + elem > vlen - off))
        return ttd_io_fail(g->c, "glTF: %s: %zu elements from byte %zu do not fit in %s (%zu bytes)", what, n, off, vwhat, vlen);
    *p = g->bufs[bi] + voff + off;
    return 0;
}

static uint32_t rd32(const uchar *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

/* ---- meshes and nodes ------------------------------------------------------------------- */

/* One mesh placed by M (column-major 4x4; NULL: unmoved). */
static int place_mesh(gltf *g, size_t mi, const double *M)
{
    const jnode *mesh = at(g, get(g, jn(g, g->root), "meshes"), mi);
    if (!mesh)
        return ttd_io_fail(g->c, "glTF: mesh %zu does not exist", mi);
    const jnode *prims = get(g, mesh, "primitives");
    if (!prims || prims->type != J_ARR)
        return ttd_io_fail(g->c, "glTF: mesh %zu has no primitives", mi);
    for (size_t pi = 0; pi < prims->count; ++pi) {
        const jnode *pr = at(g, prims, pi);
        char what[64];
        snprintf(what, sizeof what, "mesh %zu primitive %zu", mi, pi);
        size_t mode, pa, ia;
        if (get_uint(g, pr, "mode", 6, 4, what, &mode) < 0)
            return -1;
        if (mode < 4)
            continue; /* points and lines */
        if (need_uint(g, get(g, pr, "attributes"), "POSITION", 1e9, what, &pa) != 0)
            return -1;
        const uchar *pp, *ip = NULL;
        size_t pstride, np, pcs, istride = 0, ni, ics = 0;
        if (accessor(g, pa, "VEC3", 1, &pp, &pstride, &np, &pcs) != 0)
            return -1;
        int has_idx = get_uint(g, pr, "indices", 1e9, 0, what, &ia);
        if (has_idx < 0)
            return -1;
        if (has_idx == 0) {
            if (accessor(g, ia, "SCALAR", 0, &ip, &istride, &ni, &ics) != 0)
                return -1;
        } else {
            ni = np;
        }
        if (g->c->nv + np >= UINT32_MAX)
            return ttd_io_fail(g->c, "glTF: more than %lu vertices: indices would not fit in 32 bits", (unsigned long)UINT32_MAX - 1);
        const size_t base = g->c->nv;
        for (size_t k = 0; k < np; ++k) {
            const uchar *e = pp + k * pstride;
            float f[3];
            double x[3], y[3];
            for (int d = 0; d < 3; ++d) {
                uint32_t b = rd32(e + 4 * d);
                memcpy(f + d, &b, sizeof(float));
                x[d] = (double)f[d];
                if (!isfinite(x[d]))
                    return ttd_io_fail(g->c, "glTF: accessor %zu: position %zu is not finite", pa, k);
            }
            if (M) {
                for (int r = 0; r < 3; ++r)
                    y[r] = ((M[r] * x[0] + M[4 + r] * x[1]) + M[8 + r] * x[2]) + M[12 + r];
                for (int d = 0; d < 3; ++d) {
                    f[d] = (float)y[d];
                    if (!isfinite(y[d]))
                        return ttd_io_fail(g->c, "glTF: a node's transform moves position %zu of accessor %zu out of range", k, pa);
                    if (g->c->want_float && !isfinite(f[d]))
                        return ttd_io_fail(g->c, "glTF: a node's transform moves position %zu of accessor %zu out of range for float",
                                           k, pa);
                    x[d] = y[d];
                }
            }
            if (ttd_io_push_v(g->c, x, f) != 0)
                return -1;
        }
        /* the triangles, indices checked against the positions */
        uint32_t tri[3], w[3];
        size_t ntri = mode == 4 ? ni / 3 : ni >= 3 ? ni - 2 : 0;
        if (mode == 4 && ni % 3 != 0)
            return ttd_io_fail(g->c, "glTF: %s: %zu indices, not a multiple of 3", what, ni);
        for (size_t t = 0; t < ntri; ++t) {
            size_t pos[3];
            if (mode == 4)
                pos[0] = 3 * t, pos[1] = 3 * t + 1, pos[2] = 3 * t + 2;
            else if (mode == 5) /* strip: every other triangle turned so that all face one way */
                pos[0] = t + (t & 1), pos[1] = t + 1 - (t & 1), pos[2] = t + 2;
            else /* fan */
                pos[0] = 0, pos[1] = t + 1, pos[2] = t + 2;
            for (int c = 0; c < 3; ++c) {
                uint32_t v;
                if (ip) {
                    const uchar *q = ip + pos[c] * istride;
                    v = ics == 1 ? q[0] : ics == 2 ? (uint32_t)(q[0] | q[1] << 8) : rd32(q);
                } else {
                    v = (uint32_t)pos[c];
                }
                if (v >= np)
                    return ttd_io_fail(g->c, "glTF: %s: index %lu (element %zu of accessor %zu) out of range: POSITION has %zu",
                                       what, (unsigned long)v, pos[c], ia, np);
                w[c] = v;
            }
            for (int c = 0; c < 3; ++c)
                tri[c] = (uint32_t)(base + w[c]);
            if (ttd_io_push_t(g->c, tri[0], tri[1], tri[2]) != 0)
                return -1;
        }
    }
    return 0;
}

/* C = A B, column-major 4x4. */
static void mat_mul(const double *A, const double *B, double *C)
{
    for (int col = 0; col < 4; ++col)
        for (int r = 0; r < 4; ++r)
            C[4 * col + r] = ((A[r] * B[4 * col] + A[4 + r] * B[4 * col + 1]) + A[8 + r] * B[4 * col + 2]) + A[12 + r] * B[4 * col + 3];
}

static int read_numbers(gltf *g, const jnode *arr, size_t n, double *out, const char *what, const char *key)
{
    if (!arr || arr->type != J_ARR || arr->count != n)
        return ttd_io_fail(g->c, "glTF: %s: '%s' is not %zu numbers", what, key, n);
    for (size_t k = 0; k < n; ++k) {
        const jnode *v = at(g, arr, k);
        if (v->type != J_NUM || !isfinite(v->num))
            return ttd_io_fail(g->c, "glTF: %s: '%s' is not %zu numbers", what, key, n);
        out[k] = v->num;
    }
    return 0;
}

static int place_node(gltf *g, size_t ni, const double *parent, int depth)
{
    char what[32];
    snprintf(what, sizeof what, "node %zu", ni);
    if (depth > 64)
        return ttd_io_fail(g->c, "glTF: %s: the node tree is deeper than 64 (a cycle?)", what);
    if (++g->instances > (1u << 20))
        return ttd_io_fail(g->c, "glTF: more than %u node instances (nodes shared many times over)", 1u << 20);
    const jnode *node = at(g, get(g, jn(g, g->root), "nodes"), ni);
    if (!node)
        return ttd_io_fail(g->c, "glTF: node %zu does not exist", ni);
    double L[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, W[16];
    const jnode *m = get(g, node, "matrix");
    if (m) {
        if (read_numbers(g, m, 16, L, what, "matrix") != 0)
            return -1;
    } else {
        double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
        if ((get(g, node, "translation") && read_numbers(g, get(g, node, "translation"), 3, t, what, "translation") != 0) ||
            (get(g, node, "rotation") && read_numbers(g, get(g, node, "rotation"), 4, q, what, "rotation") != 0) ||
            (get(g, node, "scale") && read_numbers(g, get(g, node, "scale"), 3, s, what, "scale") != 0))
            return -1;
        const double x = q[0], y = q[1], z = q[2], w = q[3];
        const double R[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
                             2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                             2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}; /* columns */
        for (int col = 0; col < 3; ++col)
            for (int r = 0; r < 3; ++r)
                L[4 * col + r] = R[3 * col + r] * s[col];
        L[12] = t[0], L[13] = t[1], L[14] = t[2];
    }
    if (parent)
        mat_mul(parent, L, W);
    else
        memcpy(W, L, sizeof W);
    size_t mi;
    int has_mesh = get_uint(g, node, "mesh", 1e9, 0, what, &mi);
    if (has_mesh < 0 || (has_mesh == 0 && place_mesh(g, mi, W) != 0))
        return -1;
    const jnode *ch = get(g, node, "children");
    if (ch) {
        if (ch->type != J_ARR)
            return ttd_io_fail(g->c, "glTF: %s: children is not an array", what);
        for (uint32_t k = ch->first; k != UINT32_MAX; k = g->j.n[k].next) {
            const jnode *v = jn(g, k);
            if (v->type != J_NUM || !(v->num >= 0) || v->num != floor(v->num) || v->num > 1e9)
                return ttd_io_fail(g->c, "glTF: %s: a child that is not a node index", what);
            if (place_node(g, (size_t)v->num, W, depth + 1) != 0)
                return -1;
        }
    }
    return 0;
}

static int gltf_document(gltf *g)
{
    const jnode *root = jn(g, g->root);
    if (!root || root->type != J_OBJ)
        return ttd_io_fail(g->c, "glTF: the JSON is not an object");
    const jnode *asset = get(g, root, "asset"), *ver = get(g, asset, "version");
    if (!asset)
        return ttd_io_fail(g->c, "a JSON file without \"asset\": not glTF");
    if (!ver || ver->type != J_STR || ver->len < 1 || g->j.p[ver->s] != '2')
        return ttd_io_fail(g->c, "glTF: asset version %s%.*s%s: only glTF 2.0 is read", ver && ver->type == J_STR ? "'" : "",
                           ver && ver->type == J_STR ? (int)(ver->len > 16 ? 16 : ver->len) : 7,
                           ver && ver->type == J_STR ? (const char *)g->j.p + ver->s : "missing",
                           ver && ver->type == J_STR ? "'" : "");
    const jnode *req = get(g, root, "extensionsRequired");
    if (req && req->type == J_ARR && req->count > 0) {
        const jnode *e = at(g, req, 0);
        return ttd_io_fail(g->c, "glTF: requires the extension '%.*s', which is not read",
                           e && e->type == J_STR ? (int)(e->len > 64 ? 64 : e->len) : 1,
                           e && e->type == J_STR ? (const char *)g->j.p + e->s : "?");
    }
    const jnode *bufs = get(g, root, "buffers");
    g->nbufs = bufs && bufs->type == J_ARR ? bufs->count : 0;
    if (g->nbufs) {
        g->bufs = calloc(g->nbufs, sizeof *g->bufs);
        g->buf_len = calloc(g->nbufs, sizeof *g->buf_len);
        g->buf_own = calloc(g->nbufs, sizeof *g->buf_own);
        if (!g->bufs || !g->buf_len || !g->buf_own)
            return ttd_io_oom(g->c);
    }
    const jnode *scenes = get(g, root, "scenes");
    if (scenes && scenes->type == J_ARR && scenes->count > 0) {
        size_t si;
        if (get_uint(g, root, "scene", (double)scenes->count - 1, 0, "the document", &si) < 0)
            return -1;
        const jnode *sc = at(g, scenes, si), *nodes = get(g, sc, "nodes");
        if (nodes && nodes->type == J_ARR)
            for (uint32_t k = nodes->first; k != UINT32_MAX; k = g->j.n[k].next) {
                const jnode *v = jn(g, k);
                if (v->type != J_NUM || !(v->num >= 0) || v->num != floor(v->num) || v->num > 1e9)
                    return ttd_io_fail(g->c, "glTF: scene %zu: a node that is not an index", si);
                if (place_node(g, (size_t)v->num, NULL, 0) != 0)
                    return -1;
            }
        return 0;
    }
    const jnode *meshes = get(g, root, "meshes");
    for (size_t mi = 0; meshes && meshes->type == J_ARR && mi < meshes->count; ++mi)
        if (place_mesh(g, mi, NULL) != 0)
            return -1;
    return 0;
}

int ttd_io_parse_gltf(ctx *c, const uchar *data, size_t size, int glb)
{
    gltf g;
    memset(&g, 0, sizeof g);
    g.c = c;
    const uchar *js = data;
    size_t jlen = size, base = 0;
    if (glb) {
        if (size < 12)
            return ttd_io_fail(c, "truncated GLB: %zu bytes, the header alone takes 12", size);
        uint32_t version = rd32(data + 4), length = rd32(data + 8);
        if (version != 2)
            return ttd_io_fail(c, "GLB version %lu: only glTF 2.0 is read", (unsigned long)version);
        if (length != size)
            return ttd_io_fail(c, "%s GLB: its header says %lu bytes, the file has %zu", length > size ? "truncated" : "damaged",
                               (unsigned long)length, size);
        if (size < 20)
            return ttd_io_fail_at(c, 12, "truncated GLB: no JSON chunk");
        uint32_t clen = rd32(data + 12), ctype = rd32(data + 16);
        if (ctype != 0x4E4F534Au)
            return ttd_io_fail_at(c, 16, "GLB: the first chunk is not JSON");
        if (clen > size - 20)
            return ttd_io_fail_at(c, 12, "truncated GLB: a JSON chunk of %lu bytes, %zu left", (unsigned long)clen, size - 20);
        js = data + 20;
        jlen = clen;
        base = 20;
        size_t off = 20 + (size_t)clen;
        while (off + 8 <= size) { /* the binary chunk, if any; unknown chunks skipped */
            uint32_t len = rd32(data + off), type = rd32(data + off + 4);
            if (len > size - off - 8)
                return ttd_io_fail_at(c, off, "truncated GLB: a chunk of %lu bytes, %zu left", (unsigned long)len, size - off - 8);
            if (type == 0x004E4942u && !g.bin) {
                g.bin = data + off + 8;
                g.bin_len = len;
            }
            off += 8 + (size_t)len;
        }
        if (off != size)
            return ttd_io_fail_at(c, off, "GLB: %zu bytes after the last chunk", size - off);
    }
    g.j.p = js;
    g.j.size = jlen;
    g.j.c = c;
    g.j.base = base;
    if (jlen >= 3 && js[0] == 0xEF && js[1] == 0xBB && js[2] == 0xBF)
        g.j.pos = 3;
    int rc = j_value(&g.j, 0, &g.root);
    if (rc == 0) {
        j_ws(&g.j);
        while (g.j.pos < g.j.size && g.j.p[g.j.pos] == '\0') /* GLB pads with spaces; some writers NUL */
            ++g.j.pos;
        if (g.j.pos != g.j.size)
            rc = j_err(&g.j, "data after the JSON value");
    }
    if (rc == 0)
        rc = gltf_document(&g);
    for (size_t i = 0; i < g.nbufs; ++i)
        if (g.buf_own && g.buf_own[i])
            free((void *)(uintptr_t)g.bufs[i]);
    free(g.bufs);
    free(g.buf_len);
    free(g.buf_own);
    free(g.j.n);
    return rc;
}
