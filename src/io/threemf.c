/* SPDX-License-Identifier: MIT */
/* 3MF for the mesh-file reader: a zip archive (stored or deflated entries, io/inflate.c) whose
 * model part (named by _rels/.rels, else the first 3D/ *.model) is XML: objects of <vertex x y z>
 * and <triangle v1 v2 v3>, objects made of <component objectid transform> of others, and the
 * <build>'s <item objectid transform> that place them. Every item is placed: its object's
 * triangles (components followed down, transforms composed) become the mesh's, vertices moved
 * in double by the composed transform (3MF's 3x4 matrix, "m00 m01 m02 m10 ... m32", applied to
 * row vectors). Without a transform the coordinates are exactly the text's (floats by strtof on
 * the same text). Zip64, encryption and methods other than stored and deflate are refused by
 * name; sizes are checked against the archive before anything is allocated for them. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/inflate.h"
#include "io/reader.h"

static uint32_t u16(const uchar *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8; }
static uint32_t u32(const uchar *p) { return u16(p) | u16(p + 2) << 16; }

/* ---- zip --------------------------------------------------------------------------------- */

typedef struct zip {
    const uchar *data;
    size_t size, cd, ncd; /* central directory: offset, entries */
} zip;

static int zip_open(ctx *c, zip *z, const uchar *data, size_t size)
{
    z->data = data;
    z->size = size;
    if (size < 22)
        return ttd_io_fail(c, "truncated zip archive (3MF): %zu bytes, no end record", size);
    size_t lo = size - 22 > 65535 ? size - 22 - 65535 : 0;
    for (size_t e = size - 22 + 1; e-- > lo;) {
        if (u32(data + e) != 0x06054b50u)
            continue;
        size_t n = u16(data + e + 10), cdsize = u32(data + e + 12), cd = u32(data + e + 16);
        if (n == 0xffff || cd == 0xffffffffu || cdsize == 0xffffffffu)
            return ttd_io_fail(c, "zip64 archive (3MF): not read");
        if (cd > e || cdsize > e - cd)
            return ttd_io_fail_at(c, e, "zip archive (3MF): the central directory (%zu bytes at %zu) lies outside the file", cdsize, cd);
        z->cd = cd;
        z->ncd = n;
        return 0;
    }
    return ttd_io_fail(c, "truncated or damaged zip archive (3MF): no end-of-central-directory record");
}

/* Entry k of the central directory: its name and header offset; -1 after a message. */
static int zip_entry(ctx *c, const zip *z, size_t *off, const uchar **name, size_t *nlen)
{
    if (*off > z->size || z->size - *off < 46 || u32(z->data + *off) != 0x02014b50u)
        return ttd_io_fail_at(c, *off, "zip archive (3MF): a damaged central directory entry");
    size_t n = u16(z->data + *off + 28), e = u16(z->data + *off + 30), m = u16(z->data + *off + 32);
    if (n + e + m > z->size - *off - 46)
        return ttd_io_fail_at(c, *off, "zip archive (3MF): a central directory entry runs past the file");
    *name = z->data + *off + 46;
    *nlen = n;
    return 0;
}

/* The entry named name (exactly, or ignoring ASCII case when ci): its central header's offset,
 * or SIZE_MAX when absent; -1 in *rc after a message. */
static size_t zip_find(ctx *c, const zip *z, const char *name, size_t len, int ci, int *rc)
{
    size_t off = z->cd;
    for (size_t k = 0; k < z->ncd; ++k) {
        const uchar *nm = NULL;
        size_t nl = 0;
        if (zip_entry(c, z, &off, &nm, &nl) != 0) {
            *rc = -1;
            return SIZE_MAX;
        }
        int same = nl == len;
        for (size_t q = 0; same && q < len; ++q) {
            uchar a = nm[q], b = (uchar)name[q];
            if (ci) {
                a = (uchar)(a >= 'A' && a <= 'Z' ? a + 32 : a);
                b = (uchar)(b >= 'A' && b <= 'Z' ? b + 32 : b);
            }
            same = a == b;
        }
        if (same)
            return off;
        off += 46 + nl + u16(z->data + off + 30) + u16(z->data + off + 32);
    }
    return SIZE_MAX;
}

/* The bytes of the entry whose central header is at off, NUL-terminated (malloc'd). */
static int zip_read(ctx *c, const zip *z, size_t off, uchar **out, size_t *len)
{
    const uchar *h = z->data + off;
    size_t flags = u16(h + 8), method = u16(h + 10), csize = u32(h + 20), usize = u32(h + 24), lho = u32(h + 42);
    if (flags & 1)
        return ttd_io_fail(c, "3MF: an encrypted zip entry: not read");
    if (method != 0 && method != 8)
        return ttd_io_fail(c, "3MF: a zip entry compressed by method %zu (only stored and deflate are read)", method);
    if (lho > z->size || z->size - lho < 30 || u32(z->data + lho) != 0x04034b50u)
        return ttd_io_fail_at(c, lho, "3MF: a damaged zip local header");
    size_t start = lho + 30 + u16(z->data + lho + 26) + u16(z->data + lho + 28);
    if (start > z->size || csize > z->size - start)
        return ttd_io_fail_at(c, lho, "truncated 3MF: a zip entry of %zu bytes runs past the file", csize);
    if ((method == 0 && usize != csize) || usize > 1032 * (unsigned long long)csize + 1024)
        return ttd_io_fail_at(c, lho, "3MF: a zip entry declares %zu bytes from %zu, which deflate cannot give", usize, csize);
    uchar *buf = malloc(usize + 1);
    if (!buf)
        return ttd_io_oom(c);
    size_t got = usize;
    if (method == 0)
        memcpy(buf, z->data + start, usize);
    else if (ttd_io_inflate(z->data + start, csize, buf, usize, &got) != 0 || got != usize) {
        free(buf);
        return ttd_io_fail_at(c, start, "3MF: a zip entry's deflate data is damaged");
    }
    buf[usize] = '\0';
    *out = buf;
    *len = usize;
    return 0;
}

/* ---- XML: tags and attributes ------------------------------------------------------------ */

typedef struct xtag {
    const uchar *name, *attrs;
    size_t nlen, alen;
    int closing, empty;
} xtag;

/* The next element tag after *p (text, comments, declarations and CDATA skipped); 0 at the end,
 * -1 for an unterminated construct. */
static int next_tag(const uchar **p, const uchar *end, xtag *t)
{
    for (;;) {
        const uchar *lt = memchr(*p, '<', (size_t)(end - *p));
        if (!lt)
            return 0;
        const uchar *q = lt + 1;
        const char *close = NULL;
        if (end - q >= 3 && memcmp(q, "!--", 3) == 0)
            close = "-->";
        else if (end - q >= 8 && memcmp(q, "![CDATA[", 8) == 0)
            close = "]]>";
        else if (q < end && (*q == '?' || *q == '!'))
            close = ">";
        if (close) {
            size_t cl = strlen(close);
            const uchar *r = q;
            while (r + cl <= end && memcmp(r, close, cl) != 0)
                ++r;
            if (r + cl > end)
                return -1;
            *p = r + cl;
            continue;
        }
        const uchar *gt = q;
        char quote = 0;
        for (; gt < end; ++gt) { /* '>' inside an attribute's quotes does not end the tag */
            if (quote) {
                if (*gt == (uchar)quote)
                    quote = 0;
            } else if (*gt == '"' || *gt == '\'') {
                quote = (char)*gt;
            } else if (*gt == '>') {
                break;
            }
        }
        if (gt >= end)
            return -1;
        t->closing = q < gt && *q == '/';
        if (t->closing)
            ++q;
        t->empty = gt[-1] == '/';
        const uchar *ne = q;
        while (ne < gt && *ne != ' ' && *ne != '\t' && *ne != '\r' && *ne != '\n' && *ne != '/')
            ++ne;
        const uchar *colon = memchr(q, ':', (size_t)(ne - q)); /* the local name */
        t->name = colon ? colon + 1 : q;
        t->nlen = (size_t)(ne - t->name);
        t->attrs = ne;
        t->alen = (size_t)(gt - ne);
        *p = gt + 1;
        return 1;
    }
}

static int tag_is(const xtag *t, const char *n) { return t->nlen == strlen(n) && memcmp(t->name, n, t->nlen) == 0; }

/* Attribute name's value (local name compared); 1 found, 0 absent. */
static int attr(const xtag *t, const char *name, const uchar **v, size_t *vlen)
{
    const uchar *p = t->attrs, *end = t->attrs + t->alen;
    size_t nl = strlen(name);
    while (p < end) {
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == '/'))
            ++p;
        const uchar *a = p;
        while (p < end && *p != '=' && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n')
            ++p;
        const uchar *ae = p;
        while (p < end && *p != '=')
            ++p;
        if (p >= end)
            return 0;
        ++p;
        while (p < end && *p != '"' && *p != '\'')
            ++p;
        if (p >= end)
            return 0;
        uchar qc = *p++;
        const uchar *vs = p;
        while (p < end && *p != qc)
            ++p;
        if (p >= end)
            return 0;
        const uchar *colon = memchr(a, ':', (size_t)(ae - a));
        const uchar *ln = colon ? colon + 1 : a;
        if ((size_t)(ae - ln) == nl && memcmp(ln, name, nl) == 0) {
            *v = vs;
            *vlen = (size_t)(p - vs);
            return 1;
        }
        ++p;
    }
    return 0;
}

/* ---- the model ----------------------------------------------------------------------------- */

typedef struct comp {
    size_t obj; /* an object id */
    double m[12];
    int identity;
} comp;

typedef struct object {
    size_t id;
    double *v;
    float *vf;
    size_t nv, cap_v;
    uint32_t *t;
    size_t nt, cap_t;
    comp *cs;
    size_t ncs, cap_cs;
} object;

typedef struct model {
    ctx *c;
    object *obj;
    size_t nobj, cap_obj;
    comp *items;
    size_t nitems, cap_items;
    size_t placed;
} model;

static int grow(ctx *c, void **p, size_t *cap, size_t n, size_t elem)
{
    if (n < *cap)
        return 0;
    size_t nc = *cap ? 2 * *cap : 64;
    if (nc > SIZE_MAX / elem / 2)
        return ttd_io_oom(c);
    void *q = realloc(*p, nc * elem);
    if (!q)
        return ttd_io_oom(c);
    *p = q;
    *cap = nc;
    return 0;
}

static int number(ctx *c, const xtag *t, const char *name, const char *what, double *d, float *f)
{
    const uchar *v;
    size_t vl;
    char buf[401];
    if (!attr(t, name, &v, &vl))
        return ttd_io_fail(c, "3MF: a %s without '%s'", what, name);
    if (vl == 0 || vl > 400)
        return ttd_io_fail(c, "3MF: a %s's '%s' is not a number", what, name);
    memcpy(buf, v, vl);
    buf[vl] = '\0';
    char *end;
    *d = strtod(buf, &end);
    if (end != buf + vl || !isfinite(*d))
        return ttd_io_fail(c, "3MF: a %s's '%s' = '%.40s' is not a finite number", what, name, buf);
    if (f) {
        *f = strtof(buf, &end);
        if (c->want_float && !isfinite(*f))
            return ttd_io_fail(c, "3MF: a %s's '%s' = '%.40s' is out of range for float", what, name, buf);
    }
    return 0;
}

static int whole(ctx *c, const xtag *t, const char *name, const char *what, size_t *out)
{
    double d = 0;
    if (number(c, t, name, what, &d, NULL) != 0)
        return -1;
    if (!(d >= 0) || d > 4e9 || d != floor(d))
        return ttd_io_fail(c, "3MF: a %s's '%s' is not an index", what, name);
    *out = (size_t)d;
    return 0;
}

static int transform(ctx *c, const xtag *t, double m[12], int *identity)
{
    static const double id[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    const uchar *v;
    size_t vl;
    memcpy(m, id, sizeof id);
    *identity = 1;
    if (!attr(t, "transform", &v, &vl))
        return 0;
    char buf[1024];
    if (vl >= sizeof buf)
        return ttd_io_fail(c, "3MF: a transform that is too long");
    memcpy(buf, v, vl);
    buf[vl] = '\0';
    char *p = buf;
    for (int k = 0; k < 12; ++k) {
        char *end;
        m[k] = strtod(p, &end);
        if (end == p || !isfinite(m[k]))
            return ttd_io_fail(c, "3MF: transform '%.60s' is not 12 finite numbers", buf);
        p = end;
    }
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
        ++p;
    if (*p)
        return ttd_io_fail(c, "3MF: transform '%.60s' is not 12 finite numbers", buf);
    *identity = memcmp(m, id, sizeof id) == 0;
    return 0;
}

/* p * A then * B (row vectors): the 3x3 parts multiplied, the translation carried. */
static void compose(const double *A, const double *B, double *C)
{
    for (int r = 0; r < 4; ++r)
        for (int col = 0; col < 3; ++col)
            C[3 * r + col] = (A[3 * r] * B[col] + A[3 * r + 1] * B[3 + col]) + A[3 * r + 2] * B[6 + col] + (r == 3 ? B[9 + col] : 0);
}

static object *find_object(model *md, size_t id)
{
    for (size_t k = 0; k < md->nobj; ++k)
        if (md->obj[k].id == id)
            return md->obj + k;
    return NULL;
}

static int place(model *md, size_t id, const double *m, int identity, int depth)
{
    ctx *c = md->c;
    if (depth > 32)
        return ttd_io_fail(c, "3MF: components nested deeper than 32 (a cycle?) at object %zu", id);
    if (++md->placed > (1u << 20))
        return ttd_io_fail(c, "3MF: more than %u placed objects", 1u << 20);
    object *o = find_object(md, id);
    if (!o)
        return ttd_io_fail(c, "3MF: object %zu does not exist", id);
    size_t base = c->nv;
    if (c->nv + o->nv >= UINT32_MAX)
        return ttd_io_fail(c, "3MF: more than %lu vertices: indices would not fit in 32 bits", (unsigned long)UINT32_MAX - 1);
    for (size_t i = 0; i < o->nv; ++i) {
        const double *x = o->v + 3 * i;
        double y[3];
        float f[3];
        for (int d = 0; d < 3; ++d) {
            y[d] = identity ? x[d] : ((x[0] * m[d] + x[1] * m[3 + d]) + x[2] * m[6 + d]) + m[9 + d];
            f[d] = identity ? o->vf[3 * i + (size_t)d] : (float)y[d];
            if (!isfinite(y[d]) || (c->want_float && !isfinite(f[d])))
                return ttd_io_fail(c, "3MF: a transform moves vertex %zu of object %zu out of range%s", i, id,
                                   isfinite(y[d]) ? " for float" : "");
        }
        if (ttd_io_push_v(c, y, f) != 0)
            return -1;
    }
    for (size_t k = 0; k < o->nt; ++k)
        if (ttd_io_push_t(c, (uint32_t)(base + o->t[3 * k]), (uint32_t)(base + o->t[3 * k + 1]), (uint32_t)(base + o->t[3 * k + 2])) != 0)
            return -1;
    for (size_t k = 0; k < o->ncs; ++k) {
        double cm[12];
        compose(o->cs[k].m, m, cm);
        if (place(md, o->cs[k].obj, cm, identity && o->cs[k].identity, depth + 1) != 0)
            return -1;
    }
    return 0;
}

static int read_model(model *md, const uchar *x, size_t n)
{
    ctx *c = md->c;
    const uchar *p = x, *end = x + n;
    xtag t;
    object *cur = NULL;
    int in_build = 0, r;
    while ((r = next_tag(&p, end, &t)) == 1) {
        if (tag_is(&t, "object")) {
            if (t.closing) {
                cur = NULL;
                continue;
            }
            size_t id = 0;
            if (whole(c, &t, "id", "object", &id) != 0)
                return -1;
            if (find_object(md, id))
                return ttd_io_fail(c, "3MF: object id %zu appears twice", id);
            if (grow(c, (void **)&md->obj, &md->cap_obj, md->nobj, sizeof *md->obj) != 0)
                return -1;
            cur = md->obj + md->nobj++;
            memset(cur, 0, sizeof *cur);
            cur->id = id;
            if (t.empty)
                cur = NULL;
        } else if (tag_is(&t, "vertex") && !t.closing) {
            if (!cur)
                return ttd_io_fail(c, "3MF: a vertex outside an object");
            if (cur->nv == cur->cap_v) {
                size_t nc = cur->cap_v ? 2 * cur->cap_v : 64;
                double *nv = realloc(cur->v, 3 * nc * sizeof(double));
                if (!nv)
                    return ttd_io_oom(c);
                cur->v = nv;
                float *nf = realloc(cur->vf, 3 * nc * sizeof(float));
                if (!nf)
                    return ttd_io_oom(c);
                cur->vf = nf;
                cur->cap_v = nc;
            }
            static const char *const xyz[3] = {"x", "y", "z"};
            for (int d = 0; d < 3; ++d)
                if (number(c, &t, xyz[d], "vertex", cur->v + 3 * cur->nv + d, cur->vf + 3 * cur->nv + d) != 0)
                    return -1;
            cur->nv++;
        } else if (tag_is(&t, "triangle") && !t.closing) {
            if (!cur)
                return ttd_io_fail(c, "3MF: a triangle outside an object");
            size_t v[3];
            static const char *const vn[3] = {"v1", "v2", "v3"};
            for (int d = 0; d < 3; ++d) {
                if (whole(c, &t, vn[d], "triangle", v + d) != 0)
                    return -1;
                if (v[d] >= cur->nv)
                    return ttd_io_fail(c, "3MF: object %zu: triangle %zu: %s = %zu out of range (the object has %zu vertices)", cur->id,
                                       cur->nt, vn[d], v[d], cur->nv);
            }
            if (grow(c, (void **)&cur->t, &cur->cap_t, cur->nt, 3 * sizeof(uint32_t)) != 0)
                return -1;
            for (int d = 0; d < 3; ++d)
                cur->t[3 * cur->nt + (size_t)d] = (uint32_t)v[d];
            cur->nt++;
        } else if (tag_is(&t, "component") && !t.closing) {
            if (!cur)
                return ttd_io_fail(c, "3MF: a component outside an object");
            if (grow(c, (void **)&cur->cs, &cur->cap_cs, cur->ncs, sizeof *cur->cs) != 0)
                return -1;
            comp *k = cur->cs + cur->ncs;
            if (whole(c, &t, "objectid", "component", &k->obj) != 0 || transform(c, &t, k->m, &k->identity) != 0)
                return -1;
            cur->ncs++;
        } else if (tag_is(&t, "build")) {
            in_build = !t.closing && !t.empty;
        } else if (tag_is(&t, "item") && !t.closing && in_build) {
            if (grow(c, (void **)&md->items, &md->cap_items, md->nitems, sizeof *md->items) != 0)
                return -1;
            comp *k = md->items + md->nitems;
            if (whole(c, &t, "objectid", "item", &k->obj) != 0 || transform(c, &t, k->m, &k->identity) != 0)
                return -1;
            md->nitems++;
        }
    }
    if (r < 0)
        return ttd_io_fail(c, "3MF: the model's XML ends inside a tag or comment");
    if (md->nitems == 0)
        return ttd_io_fail(c, "3MF: the model's build places no object");
    for (size_t k = 0; k < md->nitems; ++k)
        if (place(md, md->items[k].obj, md->items[k].m, md->items[k].identity, 0) != 0)
            return -1;
    return 0;
}

int ttd_io_parse_3mf(ctx *c, const uchar *data, size_t size)
{
    zip z;
    if (zip_open(c, &z, data, size) != 0)
        return -1;
    /* the model part: _rels/.rels's 3dmodel relationship, else the first 3D/ *.model */
    int rc = 0;
    char name[512] = "";
    size_t at = zip_find(c, &z, "_rels/.rels", 11, 0, &rc);
    if (rc)
        return -1;
    if (at != SIZE_MAX) {
        uchar *rels;
        size_t rl;
        if (zip_read(c, &z, at, &rels, &rl) != 0)
            return -1;
        const uchar *p = rels, *end = rels + rl;
        xtag t;
        while (next_tag(&p, end, &t) == 1 && !name[0]) {
            const uchar *v, *tv;
            size_t vl, tl;
            if (!tag_is(&t, "Relationship") || !attr(&t, "Type", &tv, &tl) || !attr(&t, "Target", &v, &vl))
                continue;
            if (tl < 8 || memcmp(tv + tl - 8, "/3dmodel", 8) != 0)
                continue;
            if (vl > 0 && v[0] == '/')
                ++v, --vl;
            if (vl < sizeof name) {
                memcpy(name, v, vl);
                name[vl] = '\0';
            }
        }
        free(rels);
    }
    if (name[0]) {
        at = zip_find(c, &z, name, strlen(name), 0, &rc);
        if (at == SIZE_MAX && !rc)
            at = zip_find(c, &z, name, strlen(name), 1, &rc);
    } else {
        at = SIZE_MAX;
        size_t off = z.cd;
        for (size_t k = 0; k < z.ncd && at == SIZE_MAX; ++k) {
            const uchar *nm = NULL;
            size_t nl = 0;
            if (zip_entry(c, &z, &off, &nm, &nl) != 0)
                return -1;
            if (nl > 9 && (nm[0] == '3') && nm[1] == 'D' && nm[2] == '/' && memcmp(nm + nl - 6, ".model", 6) == 0)
                at = off;
            off += 46 + nl + u16(z.data + off + 30) + u16(z.data + off + 32);
        }
    }
    if (rc)
        return -1;
    if (at == SIZE_MAX)
        return ttd_io_fail(c, "a zip archive without a 3D model part: not a 3MF file%s%s%s", name[0] ? " ('" : "", name,
                           name[0] ? "' is named but absent)" : "");
    uchar *xml;
    size_t xl;
    if (zip_read(c, &z, at, &xml, &xl) != 0)
        return -1;
    model md;
    memset(&md, 0, sizeof md);
    md.c = c;
    rc = read_model(&md, xml, xl);
    free(xml);
    for (size_t k = 0; k < md.nobj; ++k) {
        free(md.obj[k].v);
        free(md.obj[k].vf);
        free(md.obj[k].t);
        free(md.obj[k].cs);
    }
    free(md.obj);
    free(md.items);
    return rc;
}
