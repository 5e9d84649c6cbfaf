/* SPDX-License-Identifier: MIT */
/* The mesh-file reader of ttd/meshfile.h: format detection, one parser per format, and a shared
 * builder that grows the vertex and triangle arrays and merges STL's repeated vertices.
 *
 * Safety rules kept throughout: every read is bounds-checked against the buffer (nothing
 * assumes a NUL terminator; numbers are copied to a small terminated buffer for strtod);
 * every loop advances through the input, so run time is linear in its size; a count read
 * from a header is checked against the bytes that are left before anything is allocated for
 * it; every size computation is checked for overflow. */
#define _POSIX_C_SOURCE 200809L

#include "ttd/meshfile.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/reader.h"
#include "io/weld.h"


/* ---- context: messages and the mesh being built -------------------------------------- */

/* ctx (the messages and the mesh being built) is in io/reader.h, shared with io/gltf.c. */

static int vfail(ctx *c, const char *where, const char *fmt, va_list ap)
{
    if (!c->err || c->errsize == 0)
        return -1;
    char msg[512];
    vsnprintf(msg, sizeof msg, fmt, ap);
    snprintf(c->err, c->errsize, "%s%s: %s%s", c->name, where, msg, c->why);
    return -1;
}

/// "NAME: message"
static int fail(ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(ctx *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfail(c, "", fmt, ap);
    va_end(ap);
    return -1;
}

/// "NAME:LINE: message"
static int fail_line(ctx *c, size_t line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail_line(ctx *c, size_t line, const char *fmt, ...)
{
    char where[32];
    snprintf(where, sizeof where, ":%zu", line);
    va_list ap;
    va_start(ap, fmt);
    vfail(c, where, fmt, ap);
    va_end(ap);
    return -1;
}

/// "NAME: byte OFFSET: message"
static int fail_at(ctx *c, size_t off, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail_at(ctx *c, size_t off, const char *fmt, ...)
{
    char where[40];
    snprintf(where, sizeof where, ": byte %zu", off);
    va_list ap;
    va_start(ap, fmt);
    vfail(c, where, fmt, ap);
    va_end(ap);
    return -1;
}

/// Up to 24 bytes of a token for a message: printable ASCII as is, others as \xHH, "..." when cut.
static const char *quote(const uchar *p, size_t len, char out[128])
{
    size_t o = 0, k = 0;
    for (; k < len && k < 24; ++k) {
        uchar ch = p[k];
        if (ch >= 0x20 && ch < 0x7f && ch != '\'')
            out[o++] = (char)ch;
        else
            o += (size_t)snprintf(out + o, 128 - o, "\\x%02x", ch);
    }
    if (k < len) {
        memcpy(out + o, "...", 3);
        o += 3;
    }
    out[o] = '\0';
    return out;
}

static int oom(ctx *c)
{
    return fail(c, "out of memory (%zu vertices and %zu triangles so far)", c->nv, c->nt);
}

/// Room for at least n vertices in total.
static int reserve_v(ctx *c, size_t n)
{
    if (n <= c->cap_v)
        return 0;
    if (n > SIZE_MAX / (3 * sizeof(double)))
        return oom(c);
    double *v = realloc(c->v, 3 * n * sizeof(double));
    if (!v)
        return oom(c);
    c->v = v;
    if (c->want_float) {
        float *vf = realloc(c->vf, 3 * n * sizeof(float));
        if (!vf)
            return oom(c);
        c->vf = vf;
    }
    c->cap_v = n;
    return 0;
}

static int reserve_t(ctx *c, size_t n)
{
    if (n <= c->cap_t)
        return 0;
    if (n > SIZE_MAX / (3 * sizeof(uint32_t)))
        return oom(c);
    uint32_t *t = realloc(c->t, 3 * n * sizeof(uint32_t));
    if (!t)
        return oom(c);
    c->t = t;
    c->cap_t = n;
    return 0;
}

static size_t grown(size_t cap)
{
    return cap < 1024 ? 1024 : (cap > SIZE_MAX / 2 ? SIZE_MAX : 2 * cap);
}

/// Appends a vertex (x[3] doubles, f[3] floats used when want_float).
static int push_v(ctx *c, const double *x, const float *f)
{
    if (c->nv >= UINT32_MAX)
        return fail(c, "more than %lu vertices: indices would not fit in 32 bits", (unsigned long)UINT32_MAX - 1);
    if (c->nv == c->cap_v && reserve_v(c, grown(c->cap_v)) != 0)
        return -1;
    memcpy(c->v + 3 * c->nv, x, 3 * sizeof(double));
    if (c->want_float)
        memcpy(c->vf + 3 * c->nv, f, 3 * sizeof(float));
    ++c->nv;
    return 0;
}

static int push_t(ctx *c, uint32_t a, uint32_t b, uint32_t d)
{
    if (c->nt == c->cap_t && reserve_t(c, grown(c->cap_t)) != 0)
        return -1;
    uint32_t *t = c->t + 3 * c->nt++;
    t[0] = a;
    t[1] = b;
    t[2] = d;
    return 0;
}

/* The helpers io/reader.h exports to the other readers. */
int ttd_io_fail(ctx *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfail(c, "", fmt, ap);
    va_end(ap);
    return -1;
}

int ttd_io_fail_at(ctx *c, size_t off, const char *fmt, ...)
{
    char where[40];
    snprintf(where, sizeof where, ": byte %zu", off);
    va_list ap;
    va_start(ap, fmt);
    vfail(c, where, fmt, ap);
    va_end(ap);
    return -1;
}

int ttd_io_push_v(ctx *c, const double *x, const float *f) { return push_v(c, x, f); }
int ttd_io_push_t(ctx *c, uint32_t a, uint32_t b, uint32_t d) { return push_t(c, a, b, d); }
int ttd_io_oom(ctx *c) { return oom(c); }

/* ---- STL's vertex merging: bitwise-identical double coordinates become one vertex ------ */
/* The key is the doubles alone, so the vertex numbering does not depend on want_float. Two
 * tokens can round to the same double and yet to neighbouring floats only when that double is
 * exactly halfway between two floats; the merged vertex then keeps its first float. */

static size_t merge_hash(const ctx *c, const double *x)
{
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int k = 0; k < 3; ++k) {
        uint64_t b;
        memcpy(&b, x + k, sizeof b);
        h = (h ^ b) * 0xBF58476D1CE4E5B9ull;
        h ^= h >> 29;
    }
    return (size_t)(h ^ (h >> 32)) & c->merge_mask;
}

/// A table of at least 2 slots per vertex expected (expect counts the vertices, not slots).
static int merge_init(ctx *c, size_t expect)
{
    size_t cap = 1024;
    while (cap / 2 < expect) {
        if (cap > SIZE_MAX / 4 / sizeof(uint32_t))
            return oom(c);
        cap *= 2;
    }
    uint32_t *m = malloc(cap * sizeof *m);
    if (!m)
        return oom(c);
    for (size_t k = 0; k < cap; ++k)
        m[k] = UINT32_MAX;
    free(c->merge);
    c->merge = m;
    c->merge_mask = cap - 1;
    for (size_t i = 0; i < c->nv; ++i) { /* rehash what is there */
        size_t h = merge_hash(c, c->v + 3 * i);
        while (c->merge[h] != UINT32_MAX)
            h = (h + 1) & c->merge_mask;
        c->merge[h] = (uint32_t)i;
    }
    return 0;
}

/// The index of the vertex with these exact bits, added when new.
static int merged_vertex(ctx *c, const double *x, const float *f, uint32_t *idx)
{
    if (2 * (c->nv + 1) > c->merge_mask + 1 && merge_init(c, 2 * (c->nv + 1)) != 0)
        return -1;
    size_t h = merge_hash(c, x);
    while (c->merge[h] != UINT32_MAX) {
        if (memcmp(c->v + 3 * (size_t)c->merge[h], x, 3 * sizeof(double)) == 0) {
            *idx = c->merge[h];
            return 0;
        }
        h = (h + 1) & c->merge_mask;
    }
    if (push_v(c, x, f) != 0)
        return -1;
    *idx = (uint32_t)(c->nv - 1);
    c->merge[h] = *idx;
    return 0;
}

/* ---- text -------------------------------------------------------------------------- */

static int is_blank(uchar ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f'; }
static int is_space(uchar ch) { return is_blank(ch) || ch == '\n'; }

static int lower(uchar ch) { return ch >= 'A' && ch <= 'Z' ? ch + ('a' - 'A') : ch; }

/// Token [p, p+len) equals word (case-insensitive when ci).
static int tok_is(const uchar *p, size_t len, const char *word, int ci)
{
    size_t n = strlen(word);
    if (len != n)
        return 0;
    for (size_t k = 0; k < n; ++k)
        if ((ci ? lower(p[k]) : p[k]) != (uchar)word[k])
            return 0;
    return 1;
}

/// Longest number token accepted (a double needs at most ~770 significant digits to be exact,
/// but no writer emits more than ~40).
#define MAX_NUMBER 400

/// A coordinate from a token: strtod for the double, strtof on the same text for the float.
static int parse_coord(ctx *c, const uchar *p, size_t len, size_t line, double *d, float *f)
{
    char q[128], buf[MAX_NUMBER + 1];
    if (len > MAX_NUMBER)
        return fail_line(c, line, "number '%s' is too long (over %d characters)", quote(p, len, q), MAX_NUMBER);
    memcpy(buf, p, len);
    buf[len] = '\0';
    char *end;
    errno = 0;
    *d = strtod(buf, &end);
    if (len == 0 || end != buf + len)
        return fail_line(c, line, "'%s' is not a number", quote(p, len, q));
    if (!isfinite(*d))
        return fail_line(c, line, "coordinate '%s' is %s", quote(p, len, q),
                         errno == ERANGE ? "out of range (overflows double)" : "not finite");
    if (c->want_float) {
        *f = strtof(buf, &end);
        if (!isfinite(*f))
            return fail_line(c, line, "coordinate '%s' is out of range for float", quote(p, len, q));
    }
    return 0;
}

/// A whole decimal integer token (optional sign) in [lo, hi].
static int parse_int(const uchar *p, size_t len, long long lo, long long hi, long long *out)
{
    size_t k = 0;
    int neg = 0;
    if (k < len && (p[k] == '+' || p[k] == '-'))
        neg = p[k++] == '-';
    if (k == len)
        return -1;
    unsigned long long v = 0;
    for (; k < len; ++k) {
        if (p[k] < '0' || p[k] > '9')
            return -1;
        if (v > (1ull << 62))
            return -1; /* far beyond any count or index */
        v = 10 * v + (unsigned)(p[k] - '0');
    }
    if (v > (1ull << 62))
        return -1;
    long long s = neg ? -(long long)v : (long long)v;
    if (s < lo || s > hi)
        return -1;
    *out = s;
    return 0;
}

/// A stream of blank- or newline-separated tokens with line numbers (ASCII STL and PLY).
typedef struct lexer {
    const uchar *p, *end;
    size_t line; /* of the next byte */
    size_t last; /* of the last token: where messages about the end of the file point */
} lexer;

/// The next token; 0 at the end of input. *tline: the token's line.
static int lex_next(lexer *L, const uchar **tok, size_t *len, size_t *tline)
{
    while (L->p < L->end && is_space(*L->p)) {
        if (*L->p == '\n')
            ++L->line;
        ++L->p;
    }
    if (L->p == L->end)
        return 0;
    *tok = L->p;
    while (L->p < L->end && !is_space(*L->p))
        ++L->p;
    *len = (size_t)(L->p - *tok);
    *tline = L->last = L->line;
    return 1;
}

/// Skips the rest of the current line (the newline included).
static void lex_skip_line(lexer *L)
{
    const uchar *nl = memchr(L->p, '\n', (size_t)(L->end - L->p));
    if (nl) {
        L->p = nl + 1;
        ++L->line;
    } else {
        L->p = L->end;
    }
}

/* ---- OBJ --------------------------------------------------------------------------- */

/// A vertex reference i, i/j, i//k or i/j/k: its vertex index i (syntax only).
static int obj_ref(const uchar *p, size_t len, long long *idx)
{
    size_t k = 0;
    while (k < len && p[k] != '/')
        ++k;
    if (parse_int(p, k, -(1ll << 62), 1ll << 62, idx) != 0)
        return -1;
    if (k == len)
        return 0; /* i */
    /* j and k may be empty (i/, i//, i/j/, i//k: written by some exporters, read by others) */
    size_t j0 = ++k;
    while (k < len && p[k] != '/')
        ++k;
    long long ignored;
    if (k > j0 && parse_int(p + j0, k - j0, -(1ll << 62), 1ll << 62, &ignored) != 0)
        return -1; /* a bad j */
    if (k == len) /* i/j or i/ */
        return 0;
    ++k; /* i//k, i/j/k, i// or i/j/ */
    return k == len ? 0 : parse_int(p + k, len - k, -(1ll << 62), 1ll << 62, &ignored);
}

/// The next blank-separated token of [*p, end); 0 at the end of the line or at a comment.
static int line_token(const uchar **p, const uchar *end, const uchar **tok, size_t *len)
{
    const uchar *q = *p;
    while (q < end && is_blank(*q))
        ++q;
    if (q == end || *q == '#') {
        *p = end;
        return 0;
    }
    *tok = q;
    while (q < end && !is_blank(*q))
        ++q;
    *len = (size_t)(q - *tok);
    *p = q;
    return 1;
}

static int is_identifier(const uchar *p, size_t len)
{
    if (len == 0 || !((p[0] >= 'a' && p[0] <= 'z') || (p[0] >= 'A' && p[0] <= 'Z') || p[0] == '_'))
        return 0;
    for (size_t k = 1; k < len; ++k)
        if (!((p[k] >= 'a' && p[k] <= 'z') || (p[k] >= 'A' && p[k] <= 'Z') || (p[k] >= '0' && p[k] <= '9') || p[k] == '_'))
            return 0;
    return 1;
}

static int parse_obj(ctx *c, const uchar *data, size_t size)
{
    const uchar *p = data, *end = data + size;
    if (size >= 3 && p[0] == 0xEF && p[1] == 0xBB && p[2] == 0xBF)
        p += 3;
    char q[128];
    uchar *joined = NULL; /* a statement continued over lines by a final '\\', joined */
    size_t jcap = 0;
    int rc = 0;
    for (size_t line = 1, next = 1; p < end; line = next) {
        const uchar *nl = memchr(p, '\n', (size_t)(end - p));
        const uchar *le = nl ? nl : end, *s = p;
        p = nl ? nl + 1 : end;
        ++next;
        const uchar *last = le;
        while (last > s && last[-1] == '\r')
            --last;
        if (last > s && last[-1] == '\\' && p < end) {
            /* the lines up to one that does not end in '\\', each backslash a blank */
            size_t jn = 0;
            for (;;) {
                size_t part = (size_t)(last - s);
                if (jn + part + 1 > jcap) {
                    size_t ncap = 2 * (jn + part + 1) + 64;
                    uchar *nj = realloc(joined, ncap);
                    if (!nj) {
                        rc = oom(c);
                        goto out;
                    }
                    joined = nj;
                    jcap = ncap;
                }
                memcpy(joined + jn, s, part);
                jn += part;
                if (!(part > 0 && s[part - 1] == '\\') || p >= end)
                    break;
                joined[jn - 1] = ' ';
                nl = memchr(p, '\n', (size_t)(end - p));
                s = p;
                le = nl ? nl : end;
                p = nl ? nl + 1 : end;
                ++next;
                last = le;
                while (last > s && last[-1] == '\r')
                    --last;
            }
            s = joined;
            le = joined + jn;
        }
        const uchar *kw;
        size_t kwlen;
        if (!line_token(&s, le, &kw, &kwlen))
            continue; /* blank or comment */
        if (tok_is(kw, kwlen, "v", 0)) {
            double x[3];
            float f[3] = {0, 0, 0};
            for (int k = 0; k < 3; ++k) {
                const uchar *tk;
                size_t tl;
                if (!line_token(&s, le, &tk, &tl)) {
                    rc = fail_line(c, line, "vertex has %d coordinates, 3 needed", k);
                    goto out;
                }
                if (parse_coord(c, tk, tl, line, x + k, f + k) != 0) {
                    rc = -1;
                    goto out;
                }
            }
            if (push_v(c, x, f) != 0) { /* further numbers (w, or r g b) are ignored */
                rc = -1;
                goto out;
            }
        } else if (tok_is(kw, kwlen, "f", 0)) {
            const uchar *tk;
            size_t tl;
            uint32_t first = 0, prev = 0;
            size_t n = 0;
            while (line_token(&s, le, &tk, &tl)) {
                long long i;
                if (obj_ref(tk, tl, &i) != 0) {
                    rc = fail_line(c, line, "bad vertex reference '%s' (expected i, i/j, i//k or i/j/k)", quote(tk, tl, q));
                    goto out;
                }
                if (i == 0) {
                    rc = fail_line(c, line, "face index 0 is invalid (OBJ indices start at 1)");
                    goto out;
                }
                if ((i > 0 && (unsigned long long)i > c->nv) || (i < 0 && (unsigned long long)-i > c->nv)) {
                    rc = fail_line(c, line, "face index %lld out of range (the file has %zu vertices so far)", i, c->nv);
                    goto out;
                }
                uint32_t v = (uint32_t)(i > 0 ? (size_t)i - 1 : c->nv - (size_t)-i);
                if (n == 0)
                    first = v;
                else if (n >= 2 && push_t(c, first, prev, v) != 0) {
                    rc = -1;
                    goto out;
                }
                prev = v;
                ++n;
            }
            if (n < 3) {
                rc = fail_line(c, line, "face has %zu vertices, at least 3 needed", n);
                goto out;
            }
        } else if (!is_identifier(kw, kwlen)) {
            /* Not a statement (FCL's test meshes begin with a line of two counts): skipped and
             * counted, as FCL's loader, tinyobjloader and trimesh skip it; refused when strict. */
            if (c->strict) {
                rc = fail_line(c, line, "unexpected '%s' (not an OBJ statement)", quote(kw, kwlen, q));
                goto out;
            }
            if (c->skipped++ == 0)
                c->first_skipped = line;
        }
        /* any other statement (vt vn vp l p o g s usemtl mtllib ...) is ignored */
    }
out:
    free(joined);
    return rc;
}

/* ---- STL --------------------------------------------------------------------------- */

static uint32_t le32(const uchar *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t le64(const uchar *p)
{
    return (uint64_t)le32(p) | (uint64_t)le32(p + 4) << 32;
}

static float f32_of(uint32_t b)
{
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

static int parse_stl_binary(ctx *c, const uchar *data, size_t size)
{
    if (size < 84)
        return fail(c, "truncated: file ends at byte %zu inside the 84-byte binary STL header", size);
    uint32_t n = le32(data + 80);
    uint64_t need = 84 + 50 * (uint64_t)n;
    if (size < need)
        return fail(c, "truncated: %lu facets declared, file ends at byte %zu (%llu bytes needed)",
                    (unsigned long)n, size, (unsigned long long)need);
    if (size > need)
        return fail(c, "%lu facets declared take %llu bytes, but the file has %zu (trailing data, or not a binary STL)",
                    (unsigned long)n, (unsigned long long)need, size);
    if (n == 0)
        return fail(c, "binary STL with 0 facets: no triangles");
    if (reserve_t(c, n) != 0 || reserve_v(c, n < 1024 ? 1024 : n) != 0 || merge_init(c, n) != 0)
        return -1;
    for (uint32_t i = 0; i < n; ++i) {
        const uchar *fp = data + 84 + 50 * (size_t)i + 12; /* the normal is ignored */
        uint32_t idx[3];
        for (int k = 0; k < 3; ++k) {
            double x[3];
            float f[3];
            for (int d = 0; d < 3; ++d) {
                f[d] = f32_of(le32(fp + 12 * k + 4 * d));
                if (!isfinite(f[d]))
                    return fail_at(c, (size_t)(fp - data) + 12 * (size_t)k + 4 * (size_t)d,
                                   "facet %lu: vertex %d: coordinate is not finite", (unsigned long)i, k + 1);
                x[d] = (double)f[d];
            }
            if (merged_vertex(c, x, f, idx + k) != 0)
                return -1;
        }
        if (push_t(c, idx[0], idx[1], idx[2]) != 0)
            return -1;
    }
    return 0;
}

/// The next token, which must be word (case-insensitive).
static int stl_expect(ctx *c, lexer *L, const char *word)
{
    const uchar *tk;
    size_t tl, line;
    char q[128];
    if (!lex_next(L, &tk, &tl, &line))
        return fail_line(c, L->last, "truncated: file ends where '%s' was expected", word);
    if (!tok_is(tk, tl, word, 1))
        return fail_line(c, line, "expected '%s', found '%s'", word, quote(tk, tl, q));
    return 0;
}

static int parse_stl_ascii(ctx *c, const uchar *data, size_t size)
{
    lexer L = {data, data + size, 1, 1};
    if (size >= 3 && data[0] == 0xEF && data[1] == 0xBB && data[2] == 0xBF)
        L.p += 3;
    const uchar *tk;
    size_t tl, line;
    char q[128];
    if (stl_expect(c, &L, "solid") != 0)
        return -1;
    lex_skip_line(&L); /* the solid's name */
    for (;;) {
        if (!lex_next(&L, &tk, &tl, &line))
            return fail_line(c, L.last, "truncated: file ends before 'endsolid'");
        if (tok_is(tk, tl, "endsolid", 1)) {
            lex_skip_line(&L);
            if (!lex_next(&L, &tk, &tl, &line))
                break;
            if (!tok_is(tk, tl, "solid", 1))
                return fail_line(c, line, "expected 'solid' or the end of the file after 'endsolid', found '%s'", quote(tk, tl, q));
            lex_skip_line(&L); /* another solid follows */
            continue;
        }
        if (!tok_is(tk, tl, "facet", 1))
            return fail_line(c, line, "expected 'facet' or 'endsolid', found '%s'", quote(tk, tl, q));
        if (stl_expect(c, &L, "normal") != 0)
            return -1;
        for (int k = 0; k < 3; ++k) { /* the normal: three numbers, not used (NaN is seen in the wild) */
            double ignored;
            char buf[MAX_NUMBER + 1], *e;
            if (!lex_next(&L, &tk, &tl, &line))
                return fail_line(c, L.last, "truncated: file ends inside a facet normal");
            if (tl > MAX_NUMBER)
                return fail_line(c, line, "number '%s' is too long (over %d characters)", quote(tk, tl, q), MAX_NUMBER);
            memcpy(buf, tk, tl);
            buf[tl] = '\0';
            ignored = strtod(buf, &e);
            (void)ignored;
            if (e != buf + tl)
                return fail_line(c, line, "facet normal component '%s' is not a number", quote(tk, tl, q));
        }
        if (stl_expect(c, &L, "outer") != 0 || stl_expect(c, &L, "loop") != 0)
            return -1;
        uint32_t idx[3];
        for (int k = 0; k < 3; ++k) {
            if (!lex_next(&L, &tk, &tl, &line))
                return fail_line(c, L.last, "truncated: file ends inside a facet");
            if (!tok_is(tk, tl, "vertex", 1))
                return fail_line(c, line, "facet has %d vertices, 3 needed (found '%s')", k, quote(tk, tl, q));
            double x[3];
            float f[3] = {0, 0, 0};
            for (int d = 0; d < 3; ++d) {
                if (!lex_next(&L, &tk, &tl, &line))
                    return fail_line(c, L.last, "truncated: file ends inside a vertex");
                if (parse_coord(c, tk, tl, line, x + d, f + d) != 0)
                    return -1;
            }
            if (merged_vertex(c, x, f, idx + k) != 0)
                return -1;
        }
        if (!lex_next(&L, &tk, &tl, &line))
            return fail_line(c, L.last, "truncated: file ends where 'endloop' was expected");
        if (tok_is(tk, tl, "vertex", 1))
            return fail_line(c, line, "facet has more than 3 vertices");
        if (!tok_is(tk, tl, "endloop", 1))
            return fail_line(c, line, "expected 'endloop', found '%s'", quote(tk, tl, q));
        if (stl_expect(c, &L, "endfacet") != 0 || push_t(c, idx[0], idx[1], idx[2]) != 0)
            return -1;
    }
    return 0;
}

/* ---- PLY --------------------------------------------------------------------------- */

typedef enum ply_type { PLY_I8, PLY_U8, PLY_I16, PLY_U16, PLY_I32, PLY_U32, PLY_F32, PLY_F64, PLY_NONE } ply_type;

static const struct {
    const char *name, *alias;
    size_t size;
    long long lo, hi; /* integer types' range */
} ply_types[] = {
    {"char", "int8", 1, -128, 127},
    {"uchar", "uint8", 1, 0, 255},
    {"short", "int16", 2, -32768, 32767},
    {"ushort", "uint16", 2, 0, 65535},
    {"int", "int32", 4, -2147483648ll, 2147483647ll},
    {"uint", "uint32", 4, 0, 4294967295ll},
    {"float", "float32", 4, 0, 0},
    {"double", "float64", 8, 0, 0},
};

static int ply_is_int(ply_type t) { return t <= PLY_U32; }

static ply_type ply_type_of(const uchar *p, size_t len)
{
    for (int k = 0; k <= PLY_F64; ++k)
        if (tok_is(p, len, ply_types[k].name, 0) || tok_is(p, len, ply_types[k].alias, 0))
            return (ply_type)k;
    return PLY_NONE;
}

enum { ROLE_NONE = 0, ROLE_X, ROLE_Y, ROLE_Z, ROLE_INDICES };

typedef struct ply_prop {
    ply_type type;       /* the scalar's, or the list items' */
    ply_type count_type; /* PLY_NONE for a scalar */
    int role;
} ply_prop;

typedef struct ply_elem {
    const uchar *name;
    size_t name_len, first_prop, nprops, line;
    unsigned long long count;
} ply_elem;

typedef struct ply_header {
    ply_elem *elems;
    ply_prop *props;
    size_t nelems, nprops, cap_e, cap_p;
    int binary;
    size_t data_start, data_line; /* first byte after end_header, and its line */
    size_t vertex, face;           /* element indices, SIZE_MAX when absent */
} ply_header;

static void ply_header_free(ply_header *h)
{
    free(h->elems);
    free(h->props);
}

static int ply_header_parse(ctx *c, const uchar *data, size_t size, ply_header *h)
{
    const uchar *p = data, *end = data + size;
    if (size >= 3 && p[0] == 0xEF && p[1] == 0xBB && p[2] == 0xBF)
        p += 3;
    char q[128], q2[128];
    int have_format = 0;
    h->vertex = h->face = SIZE_MAX;
    for (size_t line = 1;; ++line) {
        if (p == end)
            return fail_line(c, line - 1, "truncated: the header has no 'end_header' line");
        const uchar *nl = memchr(p, '\n', (size_t)(end - p));
        const uchar *le = nl ? nl : end, *s = p;
        p = nl ? nl + 1 : end;
        const uchar *kw, *a, *b, *d = NULL, *e;
        size_t kl, al, bl, dl = 0, el;
        if (!line_token(&s, le, &kw, &kl)) {
            if (line == 1)
                return fail_line(c, line, "not a PLY file (first line is not 'ply')");
            continue;
        }
        if (line == 1) {
            if (!tok_is(kw, kl, "ply", 0) || line_token(&s, le, &a, &al))
                return fail_line(c, line, "not a PLY file (first line is not 'ply')");
            continue;
        }
        if (tok_is(kw, kl, "comment", 0) || tok_is(kw, kl, "obj_info", 0))
            continue;
        if (tok_is(kw, kl, "format", 0)) {
            if (!line_token(&s, le, &a, &al) || !line_token(&s, le, &b, &bl))
                return fail_line(c, line, "format line needs a format and a version");
            if (tok_is(a, al, "ascii", 0))
                h->binary = 0;
            else if (tok_is(a, al, "binary_little_endian", 0))
                h->binary = 1;
            else if (tok_is(a, al, "binary_big_endian", 0))
                h->binary = 2;
            else
                return fail_line(c, line, "unknown format '%s'", quote(a, al, q));
            have_format = 1;
            continue;
        }
        if (tok_is(kw, kl, "element", 0)) {
            long long n;
            if (!line_token(&s, le, &a, &al) || !line_token(&s, le, &b, &bl))
                return fail_line(c, line, "element line needs a name and a count");
            if (parse_int(b, bl, 0, 1ll << 62, &n) != 0)
                return fail_line(c, line, "element count '%s' is not a count", quote(b, bl, q));
            if (h->nelems == h->cap_e) {
                size_t cap = h->cap_e ? 2 * h->cap_e : 8;
                ply_elem *ne = realloc(h->elems, cap * sizeof *ne);
                if (!ne)
                    return oom(c);
                h->elems = ne;
                h->cap_e = cap;
            }
            ply_elem *el0 = h->elems + h->nelems;
            el0->name = a;
            el0->name_len = al;
            el0->count = (unsigned long long)n;
            el0->first_prop = h->nprops;
            el0->nprops = 0;
            el0->line = line;
            size_t *slot = tok_is(a, al, "vertex", 0) ? &h->vertex : tok_is(a, al, "face", 0) ? &h->face : NULL;
            if (slot) {
                if (*slot != SIZE_MAX)
                    return fail_line(c, line, "a second '%s' element", quote(a, al, q));
                *slot = h->nelems;
            }
            ++h->nelems;
            continue;
        }
        if (tok_is(kw, kl, "property", 0)) {
            if (h->nelems == 0)
                return fail_line(c, line, "property before any element");
            ply_prop pr = {PLY_NONE, PLY_NONE, ROLE_NONE};
            const uchar *name;
            size_t nl2;
            if (!line_token(&s, le, &a, &al))
                return fail_line(c, line, "property line needs a type and a name");
            if (tok_is(a, al, "list", 0)) {
                if (!line_token(&s, le, &b, &bl) || !line_token(&s, le, &d, &dl) || !line_token(&s, le, &e, &el))
                    return fail_line(c, line, "list property needs a count type, an item type and a name");
                pr.count_type = ply_type_of(b, bl);
                pr.type = ply_type_of(d, dl);
                if (pr.count_type == PLY_NONE)
                    return fail_line(c, line, "unknown property type '%s'", quote(b, bl, q));
                if (pr.type == PLY_NONE)
                    return fail_line(c, line, "unknown property type '%s'", quote(d, dl, q));
                if (!ply_is_int(pr.count_type))
                    return fail_line(c, line, "property list count type '%s' is not an integer type", quote(b, bl, q));
                name = e;
                nl2 = el;
            } else {
                if (!line_token(&s, le, &b, &bl))
                    return fail_line(c, line, "property line needs a type and a name");
                pr.type = ply_type_of(a, al);
                if (pr.type == PLY_NONE)
                    return fail_line(c, line, "unknown property type '%s'", quote(a, al, q));
                name = b;
                nl2 = bl;
            }
            ply_elem *el0 = h->elems + h->nelems - 1;
            if (h->nelems - 1 == h->vertex) {
                pr.role = tok_is(name, nl2, "x", 0) ? ROLE_X : tok_is(name, nl2, "y", 0) ? ROLE_Y
                        : tok_is(name, nl2, "z", 0) ? ROLE_Z : ROLE_NONE;
                if (pr.role != ROLE_NONE && pr.count_type != PLY_NONE)
                    return fail_line(c, line, "vertex property '%s' is a list; a scalar is needed", quote(name, nl2, q));
            } else if (h->nelems - 1 == h->face &&
                       (tok_is(name, nl2, "vertex_indices", 0) || tok_is(name, nl2, "vertex_index", 0))) {
                if (pr.count_type == PLY_NONE)
                    return fail_line(c, line, "face property '%s' is not a list", quote(name, nl2, q));
                if (!ply_is_int(pr.type))
                    return fail_line(c, line, "face index type '%s' is not an integer type", quote(d, dl, q));
                pr.role = ROLE_INDICES;
            }
            for (size_t k = 0; pr.role != ROLE_NONE && k < el0->nprops; ++k)
                if (h->props[el0->first_prop + k].role == pr.role)
                    return fail_line(c, line, "element '%s' has a second property '%s'", quote(el0->name, el0->name_len, q2),
                                     quote(name, nl2, q));
            if (h->nprops == h->cap_p) {
                size_t cap = h->cap_p ? 2 * h->cap_p : 16;
                ply_prop *np = realloc(h->props, cap * sizeof *np);
                if (!np)
                    return oom(c);
                h->props = np;
                h->cap_p = cap;
            }
            h->props[h->nprops++] = pr;
            ++el0->nprops;
            continue;
        }
        if (tok_is(kw, kl, "end_header", 0)) {
            if (!have_format)
                return fail_line(c, line, "no 'format' line before 'end_header'");
            h->data_start = (size_t)(p - data);
            h->data_line = line + 1;
            break;
        }
        return fail_line(c, line, "unexpected header line starting with '%s'", quote(kw, kl, q));
    }
    if (h->vertex == SIZE_MAX)
        return fail(c, "no 'vertex' element in the PLY header");
    if (h->face == SIZE_MAX)
        return fail(c, "no 'face' element in the PLY header: no triangles");
    const ply_elem *ve = h->elems + h->vertex, *fe = h->elems + h->face;
    static const char *const axis[3] = {"x", "y", "z"};
    for (int r = ROLE_X; r <= ROLE_Z; ++r) {
        size_t k = 0;
        while (k < ve->nprops && h->props[ve->first_prop + k].role != r)
            ++k;
        if (k == ve->nprops)
            return fail_line(c, ve->line, "element 'vertex' has no property '%s'", axis[r - ROLE_X]);
    }
    size_t k = 0;
    while (k < fe->nprops && h->props[fe->first_prop + k].role != ROLE_INDICES)
        ++k;
    if (k == fe->nprops)
        return fail_line(c, fe->line, "element 'face' has no list property 'vertex_indices' or 'vertex_index'");
    if (ve->count > UINT32_MAX - 1ull)
        return fail_line(c, ve->line, "%llu vertices: indices would not fit in 32 bits", ve->count);
    /* Counts the file cannot hold are refused here, before anything is allocated for them:
     * in binary each element takes at least its scalars and list counts; in ASCII each
     * property at least one character and one separator. */
    size_t left = size - h->data_start;
    unsigned long long need = 0;
    for (size_t i = 0; i < h->nelems; ++i) {
        const ply_elem *el0 = h->elems + i;
        unsigned long long min = 0;
        for (size_t j = 0; j < el0->nprops; ++j) {
            const ply_prop *pr = h->props + el0->first_prop + j;
            min += h->binary ? ply_types[pr->count_type != PLY_NONE ? pr->count_type : pr->type].size : 2;
        }
        if (min == 0)
            continue;
        unsigned long long room = (unsigned long long)left + 1 - (need < left + 1ull ? need : left + 1ull);
        if (el0->count > room / min)
            return fail_line(c, el0->line, "element '%s' declares %llu elements of at least %llu bytes each, but only %zu bytes follow the header",
                             quote(el0->name, el0->name_len, q), el0->count, min, left);
        need += el0->count * min;
    }
    return 0;
}

/// One value read from the data: as an integer (integer types) and as double and float.
typedef struct ply_value {
    long long i;
    double d;
    float f;
} ply_value;

/// Reads a scalar of type t from the binary data at *off, little-endian (binary 1) or big-endian
/// (binary 2: its bytes reversed first, then read as little-endian).
static int ply_read_bin(ctx *c, const uchar *data, size_t size, size_t *off, ply_type t, ply_value *v,
                        const ply_elem *el, unsigned long long idx, int binary)
{
    size_t n = ply_types[t].size;
    if (size - *off < n) {
        char q[128];
        return fail_at(c, size, "truncated: file ends inside %s %llu of %llu", quote(el->name, el->name_len, q), idx, el->count);
    }
    const uchar *p = data + *off;
    uchar swapped[8];
    if (binary == 2 && n <= sizeof swapped) {
        for (size_t k = 0; k < n; ++k)
            swapped[k] = p[n - 1 - k];
        p = swapped;
    }
    *off += n;
    switch (t) {
    case PLY_I8: v->i = (signed char)p[0]; break;
    case PLY_U8: v->i = p[0]; break;
    case PLY_I16: v->i = (int16_t)(uint16_t)(p[0] | p[1] << 8); break;
    case PLY_U16: v->i = (uint16_t)(p[0] | p[1] << 8); break;
    case PLY_I32: v->i = (int32_t)le32(p); break;
    case PLY_U32: v->i = le32(p); break;
    case PLY_F32: v->f = f32_of(le32(p)); v->d = (double)v->f; return 0;
    case PLY_F64: {
        uint64_t b = le64(p);
        memcpy(&v->d, &b, sizeof v->d);
        v->f = (float)v->d;
        return 0;
    }
    default: return -1;
    }
    v->d = (double)v->i;
    v->f = (float)v->i;
    return 0;
}

/// Reads a scalar of type t from the next ASCII token. Integer types must hold a whole
/// number in their range; a coordinate (coord) is read as parse_coord does; other float
/// values only need to be a token (files carry NaN normals).
static int ply_read_text(ctx *c, lexer *L, ply_type t, int coord, ply_value *v, const ply_elem *el,
                         unsigned long long idx, size_t *tline)
{
    const uchar *tk;
    size_t tl, line;
    char q[128], q2[128];
    if (!lex_next(L, &tk, &tl, &line))
        return fail_line(c, L->last, "truncated: file ends inside %s %llu of %llu", quote(el->name, el->name_len, q), idx, el->count);
    *tline = line;
    if (ply_is_int(t)) {
        if (parse_int(tk, tl, ply_types[t].lo, ply_types[t].hi, &v->i) != 0)
            return fail_line(c, line, "'%s' is not a whole number in the range of '%s' (%s %llu)", quote(tk, tl, q),
                             ply_types[t].name, quote(el->name, el->name_len, q2), idx);
        v->d = (double)v->i;
        v->f = (float)v->i;
        return 0;
    }
    if (coord)
        return parse_coord(c, tk, tl, line, &v->d, &v->f);
    v->d = 0;
    v->f = 0;
    return 0;
}

/// Reads or skips every element in file order, storing vertices and face triangles.
static int ply_body(ctx *c, const uchar *data, size_t size, const ply_header *h)
{
    const ply_elem *ve = h->elems + h->vertex;
    size_t off = h->data_start;
    lexer L = {data + h->data_start, data + size, h->data_line, h->data_line - 1};
    if (reserve_v(c, ve->count > 0 ? (size_t)ve->count : 1) != 0 ||
        reserve_t(c, h->elems[h->face].count > 0 ? (size_t)h->elems[h->face].count : 1) != 0)
        return -1;
    char q[128];
    static const char *const axis[3] = {"x", "y", "z"};
    for (size_t ei = 0; ei < h->nelems; ++ei) {
        const ply_elem *el = h->elems + ei;
        int is_v = ei == h->vertex, is_f = ei == h->face;
        if (el->nprops == 0)
            continue;
        /* a skipped element of scalars only: one jump in binary */
        int lists = 0;
        size_t stride = 0;
        for (size_t j = 0; j < el->nprops; ++j) {
            lists |= h->props[el->first_prop + j].count_type != PLY_NONE;
            stride += ply_types[h->props[el->first_prop + j].type].size;
        }
        if (h->binary && !is_v && !is_f && !lists) {
            if (el->count > (size - off) / stride) /* cannot happen after the header's check */
                return fail_at(c, size, "truncated: file ends inside element '%s'", quote(el->name, el->name_len, q));
            off += (size_t)el->count * stride;
            continue;
        }
        for (unsigned long long i = 0; i < el->count; ++i) {
            double x[3] = {0, 0, 0};
            float f[3] = {0, 0, 0};
            size_t coord_at[3] = {0, 0, 0}, coord_line[3] = {0, 0, 0};
            for (size_t j = 0; j < el->nprops; ++j) {
                const ply_prop *pr = h->props + el->first_prop + j;
                ply_value v;
                if (pr->count_type == PLY_NONE) {
                    size_t at = off, at_line = 0;
                    int coord = pr->role >= ROLE_X && pr->role <= ROLE_Z;
                    if (h->binary ? ply_read_bin(c, data, size, &off, pr->type, &v, el, i, h->binary)
                                  : ply_read_text(c, &L, pr->type, coord, &v, el, i, &at_line))
                        return -1;
                    if (coord) {
                        x[pr->role - ROLE_X] = v.d;
                        f[pr->role - ROLE_X] = v.f;
                        coord_at[pr->role - ROLE_X] = at;
                        coord_line[pr->role - ROLE_X] = at_line;
                    }
                    continue;
                }
                size_t count_at = off, count_line = 0, item_line = 0;
                if (h->binary ? ply_read_bin(c, data, size, &off, pr->count_type, &v, el, i, h->binary)
                              : ply_read_text(c, &L, pr->count_type, 0, &v, el, i, &count_line))
                    return -1;
                if (v.i < 0) {
                    if (h->binary)
                        return fail_at(c, count_at, "%s %llu: negative list count %lld", quote(el->name, el->name_len, q), i, v.i);
                    return fail_line(c, count_line, "%s %llu: negative list count %lld", quote(el->name, el->name_len, q), i, v.i);
                }
                unsigned long long n = (unsigned long long)v.i;
                if (pr->role != ROLE_INDICES) { /* skipped */
                    if (h->binary) {
                        if (n > (size - off) / ply_types[pr->type].size)
                            return fail_at(c, size, "truncated: file ends inside %s %llu of %llu (a list of %llu)",
                                           quote(el->name, el->name_len, q), i, el->count, n);
                        off += (size_t)n * ply_types[pr->type].size;
                    } else {
                        for (unsigned long long k = 0; k < n; ++k)
                            if (ply_read_text(c, &L, pr->type, 0, &v, el, i, &item_line) != 0)
                                return -1;
                    }
                    continue;
                }
                if (n < 3) {
                    if (h->binary)
                        return fail_at(c, count_at, "face %llu has %llu vertices, at least 3 needed", i, n);
                    return fail_line(c, count_line, "face %llu has %llu vertices, at least 3 needed", i, n);
                }
                uint32_t first = 0, prev = 0;
                for (unsigned long long k = 0; k < n; ++k) {
                    size_t at = off;
                    if (h->binary ? ply_read_bin(c, data, size, &off, pr->type, &v, el, i, h->binary)
                                  : ply_read_text(c, &L, pr->type, 0, &v, el, i, &item_line))
                        return -1;
                    if (v.i < 0 || (unsigned long long)v.i >= ve->count) {
                        if (h->binary)
                            return fail_at(c, at, "face %llu: vertex index %lld out of range (the file has %llu vertices)", i, v.i, ve->count);
                        return fail_line(c, item_line, "face %llu: vertex index %lld out of range (the file has %llu vertices)", i, v.i, ve->count);
                    }
                    uint32_t vi = (uint32_t)v.i;
                    if (k == 0)
                        first = vi;
                    else if (k >= 2 && push_t(c, first, prev, vi) != 0)
                        return -1;
                    prev = vi;
                }
            }
            if (!is_v)
                continue;
            for (int d = 0; d < 3; ++d) {
                const char *why = !isfinite(x[d]) ? "is not finite" : (c->want_float && !isfinite(f[d])) ? "is out of range for float" : NULL;
                if (!why)
                    continue;
                if (h->binary)
                    return fail_at(c, coord_at[d], "vertex %llu: coordinate %s %s", i, axis[d], why);
                return fail_line(c, coord_line[d], "vertex %llu: coordinate %s %s", i, axis[d], why);
            }
            if (push_v(c, x, f) != 0)
                return -1;
        }
    }
    if (h->binary) {
        if (off != size)
            return fail_at(c, off, "%zu byte%s of data after the last element", size - off, size - off == 1 ? "" : "s");
    } else {
        const uchar *tk;
        size_t tl, line;
        if (lex_next(&L, &tk, &tl, &line))
            return fail_line(c, line, "data after the last element: '%s'", quote(tk, tl, q));
    }
    return 0;
}

static int parse_ply(ctx *c, const uchar *data, size_t size, ttd_meshfile_format *fmt)
{
    ply_header h;
    memset(&h, 0, sizeof h);
    int rc = ply_header_parse(c, data, size, &h);
    if (rc == 0) {
        *fmt = h.binary ? TTD_MESHFILE_PLY_BINARY : TTD_MESHFILE_PLY_ASCII;
        rc = ply_body(c, data, size, &h);
    }
    ply_header_free(&h);
    return rc;
}

/* ---- OFF --------------------------------------------------------------------------- */
/* The header keyword [ST][C][N]OFF (texture coordinates, colours, normals: numbers after x y z
 * on a vertex line, ignored), the counts nv nf [ne] (on the header line or the next), nv vertex
 * lines (x y z first), nf face lines (n, then n indices from 0, then an optional colour). '#'
 * starts a comment; blank lines are skipped. 4OFF, nOFF and binary OFF are refused by name. */

/* The next line with a token: [*s, *le) and its number; 0 at the end of the data. */
static int off_line(const uchar **p, const uchar *end, size_t *line, const uchar **s, const uchar **le)
{
    while (*p < end) {
        const uchar *nl = memchr(*p, '\n', (size_t)(end - *p));
        *s = *p;
        *le = nl ? nl : end;
        *p = nl ? nl + 1 : end;
        ++*line;
        const uchar *q = *s, *tk;
        size_t tl;
        if (line_token(&q, *le, &tk, &tl))
            return 1;
    }
    return 0;
}

/* The OFF keyword's prefix letters: 0 for a keyword this reader takes, else -1 (not OFF) or the
 * letter that makes it one it does not ('4' or 'n'). */
static int off_keyword(const uchar *p, size_t len)
{
    if (len < 3 || memcmp(p + len - 3, "OFF", 3) != 0)
        return -1;
    size_t k = 0;
    if (k + 1 < len - 2 && p[k] == 'S' && p[k + 1] == 'T')
        k += 2;
    if (k < len - 3 && p[k] == 'C')
        ++k;
    if (k < len - 3 && p[k] == 'N')
        ++k;
    if (k < len - 3 && p[k] == 'C') /* NCOFF as some write it */
        ++k;
    if (k < len - 3 && (p[k] == '4' || p[k] == 'n'))
        return p[k];
    return k == len - 3 ? 0 : -1;
}

static int parse_off(ctx *c, const uchar *data, size_t size)
{
    const uchar *p = data, *end = data + size, *s, *le, *tk;
    size_t line = 0, tl;
    char q[128];
    if (size >= 3 && p[0] == 0xEF && p[1] == 0xBB && p[2] == 0xBF)
        p += 3;
    if (!off_line(&p, end, &line, &s, &le) || !line_token(&s, le, &tk, &tl))
        return fail(c, "empty file");
    int kw = off_keyword(tk, tl);
    if (kw != 0)
        return fail_line(c, line, "'%s': %s", quote(tk, tl, q),
                         kw > 0 ? "an OFF variant this reader does not take (4OFF and nOFF are not 3D triangle meshes)"
                                : "not an OFF header");
    long long count[3] = {0, 0, 0};
    int have = 0;
    size_t count_line = line;
    while (have < 3) {
        const uchar *ct;
        size_t cl;
        if (!line_token(&s, le, &ct, &cl)) {
            if (have >= 2)
                break;
            if (!off_line(&p, end, &line, &s, &le))
                return fail_line(c, line, "truncated: the counts (vertices faces edges) are missing");
            count_line = line;
            continue;
        }
        if (have == 0 && tok_is(ct, cl, "BINARY", 0))
            return fail_line(c, line, "binary OFF is not read (write it as text)");
        if (parse_int(ct, cl, 0, (1ll << 62), count + have) != 0)
            return fail_line(c, line, "'%s' is not a count (vertices faces edges)", quote(ct, cl, q));
        ++have;
    }
    if (line_token(&s, le, &tk, &tl))
        return fail_line(c, count_line, "unexpected '%s' after the counts", quote(tk, tl, q));
    const size_t left = (size_t)(end - p);
    /* every vertex and face is a line of at least 2 bytes: nothing is allocated past what the
     * file could hold */
    if ((unsigned long long)count[0] > left / 2 + 1 || (unsigned long long)count[1] > left / 2 + 1 ||
        (unsigned long long)count[0] + (unsigned long long)count[1] > (unsigned long long)left / 2 + 1)
        return fail_line(c, count_line, "%lld vertices and %lld faces declared, but only %zu bytes follow", count[0], count[1], left);
    if (count[0] >= (long long)UINT32_MAX)
        return fail_line(c, count_line, "%lld vertices: indices would not fit in 32 bits", count[0]);
    const size_t nv = (size_t)count[0], nf = (size_t)count[1];
    if (reserve_v(c, nv ? nv : 1) != 0 || reserve_t(c, nf ? nf : 1) != 0)
        return -1;
    for (size_t i = 0; i < nv; ++i) {
        if (!off_line(&p, end, &line, &s, &le))
            return fail_line(c, line, "truncated: file ends at vertex %zu of %zu", i, nv);
        double x[3];
        float f[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k) {
            if (!line_token(&s, le, &tk, &tl))
                return fail_line(c, line, "vertex %zu has %d coordinates, 3 needed", i, k);
            if (parse_coord(c, tk, tl, line, x + k, f + k) != 0)
                return -1;
        }
        if (push_v(c, x, f) != 0)
            return -1;
    }
    for (size_t i = 0; i < nf; ++i) {
        if (!off_line(&p, end, &line, &s, &le))
            return fail_line(c, line, "truncated: file ends at face %zu of %zu", i, nf);
        long long n;
        if (!line_token(&s, le, &tk, &tl) || parse_int(tk, tl, 0, 1ll << 62, &n) != 0)
            return fail_line(c, line, "face %zu: '%s' is not a vertex count", i, quote(tk, tl, q));
        if (n < 3)
            return fail_line(c, line, "face %zu has %lld vertices, at least 3 needed", i, n);
        uint32_t first = 0, prev = 0;
        for (long long k = 0; k < n; ++k) {
            long long v;
            if (!line_token(&s, le, &tk, &tl))
                return fail_line(c, line, "face %zu: %lld vertices declared, %lld given", i, n, k);
            if (parse_int(tk, tl, -(1ll << 62), 1ll << 62, &v) != 0)
                return fail_line(c, line, "face %zu: '%s' is not a vertex index", i, quote(tk, tl, q));
            if (v < 0 || (unsigned long long)v >= nv)
                return fail_line(c, line, "face %zu: vertex index %lld out of range (the file has %zu vertices)", i, v, nv);
            if (k == 0)
                first = (uint32_t)v;
            else if (k >= 2 && push_t(c, first, prev, (uint32_t)v) != 0)
                return -1;
            prev = (uint32_t)v;
        }
        /* a colour may follow */
    }
    if (off_line(&p, end, &line, &s, &le) && line_token(&s, le, &tk, &tl))
        return fail_line(c, line, "data after the last face: '%s'", quote(tk, tl, q));
    return 0;
}

/* ---- detection and entry points ---------------------------------------------------- */

/* Formats recognised by their first bytes and not read: their names, for the message. */
static const char *foreign_format(const uchar *data, size_t size)
{
    static const struct {
        const char *magic;
        size_t len;
        const char *name;
    } known[] = {
        {"PK\x05\x06", 4, "an empty zip archive"},
        {"\x1f\x8b", 2, "gzip-compressed data (decompress it first)"},
        {"(\xb5/\xfd", 4, "zstd-compressed data (decompress it first)"},
        {"BZh", 3, "bzip2-compressed data (decompress it first)"},
        {"\xfd" "7zXZ", 5, "xz-compressed data (decompress it first)"},
        {"Kaydara FBX Binary", 18, "a binary FBX file"},
        {"ISO-10303-21", 12, "a STEP file (CAD boundary representation, not triangles)"},
        {"#VRML", 5, "a VRML file"},
        {"%PDF", 4, "a PDF document"},
        {"\x89PNG", 4, "a PNG image"},
        {"\xff\xd8\xff", 3, "a JPEG image"},
        {"<?xml", 5, "an XML file (COLLADA, X3D, or a 3MF's model: not read)"},
        {"glTF", 4, "binary glTF"}, /* reaches here only with a version or length that does not fit */
    };
    for (size_t k = 0; k < sizeof known / sizeof known[0]; ++k)
        if (size >= known[k].len && memcmp(data, known[k].magic, known[k].len) == 0)
            return known[k].name;
    return NULL;
}

/* The format of the content; why receives, for a binary STL assumed from bytes that no text
 * holds, the words that say so (appended to the parser's messages), else "". *foreign: a format
 * recognised and not read (its description), else NULL. */
static ttd_meshfile_format detect(const uchar *data, size_t size, char *why, size_t whysize, const char **foreign)
{
    why[0] = '\0';
    *foreign = NULL;
    size_t s = size >= 3 && data[0] == 0xEF && data[1] == 0xBB && data[2] == 0xBF ? 3 : 0;
    if (size - s >= 4 && memcmp(data + s, "ply", 3) == 0 && (data[s + 3] == '\n' || data[s + 3] == '\r'))
        return TTD_MESHFILE_PLY_ASCII; /* the header says which PLY */
    if (size >= 12 && memcmp(data, "glTF", 4) == 0 && le32(data + 4) == 2 && le32(data + 8) == size)
        return TTD_MESHFILE_GLB; /* its header states the file's size */
    if (size >= 84 && (size - 84) % 50 == 0 && (size - 84) / 50 == le32(data + 80))
        return TTD_MESHFILE_STL_BINARY; /* even when the header begins with "solid" */
    if (size >= 4 && memcmp(data, "glTF", 4) == 0)
        return TTD_MESHFILE_GLB; /* a broken one: its reader says what is wrong */
    if (size >= 4 && memcmp(data, "PK\x03\x04", 4) == 0)
        return TTD_MESHFILE_3MF; /* a zip archive: its reader says when it holds no 3D model */
    if ((*foreign = foreign_format(data, size)) != NULL)
        return TTD_MESHFILE_FORMAT_COUNT;
    /* Bytes no text file has (NUL, control characters other than white space, bytes that
     * never occur in UTF-8) in the first 84: a binary STL whose size does not match (its
     * parser then says so). */
    for (size_t k = 0; k < size && k < 84; ++k) {
        uchar ch = data[k];
        if ((ch < 0x20 && !is_space(ch)) || ch == 0x7f || ch == 0xc0 || ch == 0xc1 || ch >= 0xf5) {
            snprintf(why, whysize, " (read as a binary STL: byte %zu is 0x%02x, which text does not hold)", k,
                     (unsigned)ch);
            return TTD_MESHFILE_STL_BINARY;
        }
    }
    while (s < size && is_space(data[s]))
        ++s;
    size_t w = s;
    while (w < size && !is_space(data[w]))
        ++w;
    if (off_keyword(data + s, w - s) >= 0)
        return TTD_MESHFILE_OFF;
    if (size - s >= 5 && tok_is(data + s, 5, "solid", 1) && (size - s == 5 || is_space(data[s + 5])))
        return TTD_MESHFILE_STL_ASCII;
    if (s < size && data[s] == '{')
        return TTD_MESHFILE_GLTF;
    return TTD_MESHFILE_OBJ;
}

static void free_ctx(ctx *c)
{
    free(c->v);
    free(c->vf);
    free(c->t);
    free(c->merge);
}

static int parse_in(const char *name, const char *dir, const unsigned char *data, size_t size, int flags,
                    ttd_meshfile *out, char *err, size_t errsize)
{
    ctx c;
    memset(&c, 0, sizeof c);
    c.name = name ? name : "<input>";
    c.dir = dir;
    c.err = err;
    c.errsize = errsize;
    c.want_float = (flags & TTD_MESHFILE_FLOAT) != 0;
    c.strict = (flags & TTD_MESHFILE_STRICT) != 0;
    if (err && errsize)
        err[0] = '\0';
    if (!out)
        return fail(&c, "no output mesh given");
    memset(out, 0, sizeof *out);
    if (!data && size > 0)
        return fail(&c, "no data given");
    if (size == 0)
        return fail(&c, "empty file");
    const char *foreign;
    ttd_meshfile_format fmt = detect(data, size, c.why, sizeof c.why, &foreign);
    if (foreign)
        return fail(&c, "%s, not a mesh format this reader takes (OBJ, STL, PLY, OFF, glTF, 3MF)", foreign);
    int rc;
    switch (fmt) {
    case TTD_MESHFILE_PLY_ASCII: rc = parse_ply(&c, data, size, &fmt); break;
    case TTD_MESHFILE_OFF: rc = parse_off(&c, data, size); break;
    case TTD_MESHFILE_GLB: rc = ttd_io_parse_gltf(&c, data, size, 1); break;
    case TTD_MESHFILE_GLTF: rc = ttd_io_parse_gltf(&c, data, size, 0); break;
    case TTD_MESHFILE_3MF: rc = ttd_io_parse_3mf(&c, data, size); break;
    case TTD_MESHFILE_STL_BINARY: rc = parse_stl_binary(&c, data, size); break;
    case TTD_MESHFILE_STL_ASCII: rc = parse_stl_ascii(&c, data, size); break;
    default: rc = parse_obj(&c, data, size); break;
    }
    if (rc == 0 && c.nt == 0)
        rc = fail(&c, "no triangles (read as %s)", ttd_meshfile_format_name(fmt));
    if (rc != 0) {
        free_ctx(&c);
        return -1;
    }
    free(c.merge);
    out->verts = c.v;
    out->verts_f = c.want_float ? c.vf : NULL;
    out->nv = c.nv;
    out->tris = c.t;
    out->nt = c.nt;
    out->format = fmt;
    out->skipped_lines = c.skipped;
    out->first_skipped_line = c.first_skipped;
    return 0;
}

int ttd_meshfile_parse(const char *name, const unsigned char *data, size_t size, int flags,
                       ttd_meshfile *out, char *err, size_t errsize)
{
    return parse_in(name, NULL, data, size, flags, out, err, errsize);
}

int ttd_meshfile_read(const char *path, int flags, ttd_meshfile *out, char *err, size_t errsize)
{
    ctx c;
    memset(&c, 0, sizeof c);
    c.name = path ? (strcmp(path, "-") == 0 ? "<stdin>" : path) : "<null>";
    c.err = err;
    c.errsize = errsize;
    if (out)
        memset(out, 0, sizeof *out);
    if (!path)
        return fail(&c, "no file name given");
    int is_stdin = strcmp(path, "-") == 0;
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    if (!f)
        return fail(&c, "cannot open: %s", strerror(errno));
    size_t cap = 1 << 16, n = 0;
    uchar *buf = NULL;
    int rc = -1;
    struct stat st;
    if (fstat(fileno(f), &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            fail(&c, "cannot read: it is a directory");
            goto done;
        }
        if (S_ISREG(st.st_mode) && st.st_size > 0 && (unsigned long long)st.st_size < SIZE_MAX - 1)
            cap = (size_t)st.st_size + 1; /* read a regular file in one go */
    }
    buf = malloc(cap);
    if (!buf) {
        fail(&c, "out of memory reading the file");
        goto done;
    }
    for (;;) {
        if (n == cap) {
            size_t ncap = cap > SIZE_MAX / 2 ? SIZE_MAX : 2 * cap;
            uchar *nb = ncap > cap ? realloc(buf, ncap) : NULL;
            if (!nb) {
                fail(&c, "out of memory reading the file (%zu bytes so far)", n);
                goto done;
            }
            buf = nb;
            cap = ncap;
        }
        errno = 0;
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) {
            if (ferror(f)) {
                fail(&c, "read error: %s", strerror(errno ? errno : EIO));
                goto done;
            }
            break;
        }
    }
    {
        /* the folder a glTF's external buffers are named from */
        char *dir = is_stdin ? NULL : strdup(path);
        if (dir) {
            char *slash = strrchr(dir, '/');
            if (slash)
                *(slash == dir ? slash + 1 : slash) = '\0';
            else
                strcpy(dir, ".");
        }
        rc = parse_in(c.name, dir, buf, n, flags, out, err, errsize);
        free(dir);
    }
done:
    free(buf);
    if (!is_stdin)
        fclose(f);
    return rc;
}

void ttd_meshfile_free(ttd_meshfile *m)
{
    if (!m)
        return;
    free(m->verts);
    free(m->verts_f);
    free(m->tris);
    memset(m, 0, sizeof *m);
}

const char *ttd_meshfile_format_name(ttd_meshfile_format f)
{
    static const char *const names[TTD_MESHFILE_FORMAT_COUNT] = {"obj", "stl-ascii", "stl-binary", "ply-ascii",
                                                                  "ply-binary", "off", "glb", "gltf", "3mf"};
    return (unsigned)f < TTD_MESHFILE_FORMAT_COUNT ? names[f] : NULL;
}

int ttd_meshfile_weld(ttd_meshfile *m, double tolerance, size_t *dropped, char *err, size_t errsize)
{
    if (err && errsize)
        err[0] = '\0';
    if (dropped)
        *dropped = 0;
    if (!m || !m->verts || m->nv == 0 || (m->nt > 0 && !m->tris)) {
        if (err && errsize)
            snprintf(err, errsize, "weld: no mesh given");
        return -1;
    }
    if (!(tolerance >= 0) || !isfinite(tolerance)) {
        if (err && errsize)
            snprintf(err, errsize, "weld: the tolerance %g is not a finite number >= 0", tolerance);
        return -1;
    }
    uint32_t *map = malloc(m->nv * sizeof *map), *rep = malloc(m->nv * sizeof *rep);
    double *v = malloc(3 * m->nv * sizeof *v);
    float *vf = m->verts_f ? malloc(3 * m->nv * sizeof *vf) : NULL;
    size_t n = 0;
    if (!map || !rep || !v || (m->verts_f && !vf) || ttd_weld_classes(m->verts, m->nv, tolerance, map, rep, &n) != 0) {
        free(map);
        free(rep);
        free(v);
        free(vf);
        if (err && errsize)
            snprintf(err, errsize, "weld: out of memory (%zu vertices)", m->nv);
        return -1;
    }
    size_t k = 0;
    for (size_t t = 0; t < m->nt; ++t) {
        uint32_t a = map[m->tris[3 * t]], b = map[m->tris[3 * t + 1]], c = map[m->tris[3 * t + 2]];
        if (a != b && b != c && a != c)
            ++k;
    }
    if (k == 0) {
        if (err && errsize)
            snprintf(err, errsize, "weld: every one of the %zu triangles collapses at tolerance %g", m->nt, tolerance);
        free(map);
        free(rep);
        free(v);
        free(vf);
        return -1;
    }
    k = 0;
    for (size_t t = 0; t < m->nt; ++t) {
        uint32_t a = map[m->tris[3 * t]], b = map[m->tris[3 * t + 1]], c = map[m->tris[3 * t + 2]];
        if (a == b || b == c || a == c)
            continue;
        m->tris[3 * k] = a;
        m->tris[3 * k + 1] = b;
        m->tris[3 * k + 2] = c;
        ++k;
    }
    /* the representative's coordinates in both precisions (its float rounded from its own text) */
    for (size_t j = 0; j < n; ++j)
        for (int d = 0; d < 3; ++d) {
            v[3 * j + (size_t)d] = m->verts[3 * (size_t)rep[j] + (size_t)d] + 0.0;
            if (vf)
                vf[3 * j + (size_t)d] = m->verts_f[3 * (size_t)rep[j] + (size_t)d] + 0.0f;
        }
    free(m->verts);
    free(m->verts_f);
    m->verts = v;
    m->verts_f = vf;
    if (dropped)
        *dropped = m->nt - k;
    m->nv = n;
    m->nt = k;
    free(map);
    free(rep);
    return 0;
}
