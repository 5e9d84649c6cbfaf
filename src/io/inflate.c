/* SPDX-License-Identifier: MIT */
/* Deflate decompression (RFC 1951) for the 3MF reader's zip entries: stored, fixed-Huffman and
 * dynamic-Huffman blocks, canonical codes decoded one bit at a time by counts per length (the
 * slow, small way: a 3MF model is read once). Every read is bounds-checked against the input and
 * every write against the output's declared size; malformed data gives -1, never a read or write
 * outside the buffers. */
#include "io/inflate.h"

#include <string.h>

typedef struct bits {
    const unsigned char *in;
    size_t n, pos; /* byte position */
    unsigned buf, cnt;
    unsigned char *out;
    size_t cap, len;
} bits;

static int need(bits *s, unsigned k, unsigned *v)
{
    unsigned long long b = s->buf;
    while (s->cnt < k) {
        if (s->pos >= s->n)
            return -1;
        b |= (unsigned long long)s->in[s->pos++] << s->cnt;
        s->cnt += 8;
    }
    *v = (unsigned)(b & ((1ull << k) - 1));
    s->buf = (unsigned)(b >> k);
    s->cnt -= k;
    return 0;
}

typedef struct huff {
    short count[16];  /* codes of each length */
    short symbol[320]; /* symbols in canonical order */
} huff;

/* Builds a code from n lengths; 0, or -1 for an over-subscribed set (incomplete sets are allowed
 * as the format allows them for a single distance code). */
static int build(huff *h, const unsigned char *len, int n)
{
    short offs[16];
    memset(h->count, 0, sizeof h->count);
    for (int s = 0; s < n; ++s)
        h->count[len[s]]++;
    if (h->count[0] == n)
        return 0;
    int left = 1;
    for (int l = 1; l < 16; ++l) {
        left <<= 1;
        left -= h->count[l];
        if (left < 0)
            return -1;
    }
    offs[1] = 0;
    for (int l = 1; l < 15; ++l)
        offs[l + 1] = (short)(offs[l] + h->count[l]);
    for (int s = 0; s < n; ++s)
        if (len[s])
            h->symbol[offs[len[s]]++] = (short)s;
    return 0;
}

static int decode(bits *s, const huff *h)
{
    int code = 0, first = 0, index = 0;
    for (int l = 1; l < 16; ++l) {
        unsigned b;
        if (need(s, 1, &b) != 0)
            return -1;
        code |= (int)b;
        int count = h->count[l];
        if (code - count < first)
            return h->symbol[index + (code - first)];
        index += count;
        first += count;
        first <<= 1;
        code <<= 1;
    }
    return -1;
}

static const short len_base[29] = {3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31,
                                   35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
static const short len_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
static const short dist_base[30] = {1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193,
                                    257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
static const short dist_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

static int codes(bits *s, const huff *lit, const huff *dist)
{
    for (;;) {
        int sym = decode(s, lit);
        if (sym < 0)
            return -1;
        if (sym < 256) {
            if (s->len >= s->cap)
                return -1;
            s->out[s->len++] = (unsigned char)sym;
        } else if (sym == 256) {
            return 0;
        } else {
            sym -= 257;
            if (sym >= 29)
                return -1;
            unsigned e;
            if (need(s, (unsigned)len_extra[sym], &e) != 0)
                return -1;
            size_t len = (size_t)len_base[sym] + e;
            int ds = decode(s, dist);
            if (ds < 0 || ds >= 30)
                return -1;
            if (need(s, (unsigned)dist_extra[ds], &e) != 0)
                return -1;
            size_t d = (size_t)dist_base[ds] + e;
            if (d > s->len || len > s->cap - s->len)
                return -1;
            for (size_t k = 0; k < len; ++k, ++s->len)
                s->out[s->len] = s->out[s->len - d];
        }
    }
}

static int fixed_block(bits *s)
{
    huff lit, dist; /* built per block (cheap), so that concurrent reads share nothing */
    unsigned char l[288];
    int k = 0;
    for (; k < 144; ++k) l[k] = 8;
    for (; k < 256; ++k) l[k] = 9;
    for (; k < 280; ++k) l[k] = 7;
    for (; k < 288; ++k) l[k] = 8;
    build(&lit, l, 288);
    for (k = 0; k < 30; ++k) l[k] = 5;
    build(&dist, l, 30);
    return codes(s, &lit, &dist);
}

static int dynamic_block(bits *s)
{
    static const unsigned char order[19] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};
    unsigned nlen, ndist, ncode;
    if (need(s, 5, &nlen) || need(s, 5, &ndist) || need(s, 4, &ncode))
        return -1;
    nlen += 257;
    ndist += 1;
    ncode += 4;
    if (nlen > 286 || ndist > 30)
        return -1;
    unsigned char lengths[320];
    memset(lengths, 0, sizeof lengths);
    for (unsigned k = 0; k < ncode; ++k) {
        unsigned v;
        if (need(s, 3, &v))
            return -1;
        lengths[order[k]] = (unsigned char)v;
    }
    huff lencode, lit, dist;
    if (build(&lencode, lengths, 19) != 0)
        return -1;
    unsigned k = 0;
    while (k < nlen + ndist) {
        int sym = decode(s, &lencode);
        if (sym < 0)
            return -1;
        if (sym < 16) {
            lengths[k++] = (unsigned char)sym;
            continue;
        }
        unsigned rep, v;
        unsigned char val = 0;
        if (sym == 16) {
            if (k == 0 || need(s, 2, &v))
                return -1;
            val = lengths[k - 1];
            rep = 3 + v;
        } else if (sym == 17) {
            if (need(s, 3, &v))
                return -1;
            rep = 3 + v;
        } else {
            if (need(s, 7, &v))
                return -1;
            rep = 11 + v;
        }
        if (k + rep > nlen + ndist)
            return -1;
        while (rep--)
            lengths[k++] = val;
    }
    if (lengths[256] == 0)
        return -1;
    if (build(&lit, lengths, (int)nlen) != 0 || build(&dist, lengths + nlen, (int)ndist) != 0)
        return -1;
    return codes(s, &lit, &dist);
}

int ttd_io_inflate(const unsigned char *in, size_t n, unsigned char *out, size_t cap, size_t *out_len)
{
    bits s = {in, n, 0, 0, 0, out, cap, 0};
    unsigned last, type;
    do {
        if (need(&s, 1, &last) || need(&s, 2, &type))
            return -1;
        if (type == 0) { /* stored: to a byte boundary, LEN and its complement */
            s.buf = 0;
            s.cnt = 0;
            if (n - s.pos < 4)
                return -1;
            unsigned len = in[s.pos] | (unsigned)in[s.pos + 1] << 8, nlen = in[s.pos + 2] | (unsigned)in[s.pos + 3] << 8;
            s.pos += 4;
            if (len != (~nlen & 0xffffu) || len > n - s.pos || len > cap - s.len)
                return -1;
            memcpy(out + s.len, in + s.pos, len);
            s.pos += len;
            s.len += len;
        } else if (type == 1) {
            if (fixed_block(&s) != 0)
                return -1;
        } else if (type == 2) {
            if (dynamic_block(&s) != 0)
                return -1;
        } else {
            return -1;
        }
    } while (!last);
    *out_len = s.len;
    return 0;
}
