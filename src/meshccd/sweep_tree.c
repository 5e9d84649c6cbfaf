/* SPDX-License-Identifier: MIT */
/* The swept-box hierarchy (sweep_tree.h): Morton order by a stable radix sort, then halves. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "meshccd/sweep_tree.h"

void sweep_box_widen(sweep_box *b, double delta)
{
    if (delta == 0)
        return; /* x - 0 is exact */
    for (int k = 0; k < 3; ++k) {
        /* Rounded to nearest, then one step outward: the result is beyond the exact value. */
        b->lo[k] = nextafter(b->lo[k] - delta, -HUGE_VAL);
        b->hi[k] = nextafter(b->hi[k] + delta, HUGE_VAL);
    }
}

/* Spreads the 10 low bits of v to every third bit. */
static uint32_t spread3(uint32_t v)
{
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

/* Morton codes of the boxes' centres on a 1024^3 grid over the centres' bounding box. Any order
 * gives a correct tree (the boxes hold what they hold); this one makes it a good one. */
static void morton_codes(const sweep_box *boxes, size_t n, uint32_t *code)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            const double c = 0.5 * boxes[i].lo[k] + 0.5 * boxes[i].hi[k];
            lo[k] = c < lo[k] ? c : lo[k];
            hi[k] = c > hi[k] ? c : hi[k];
        }
    double scale[3];
    for (int k = 0; k < 3; ++k) {
        const double ext = hi[k] - lo[k]; /* inf for extreme boxes: then every code is 0 there */
        scale[k] = ext > 0 && isfinite(ext) ? 1023.0 / ext : 0.0;
    }
    uint32_t spread[1024]; /* spread3 of every 10-bit value: three lookups a box in place of the shifts */
    for (uint32_t v = 0; v < 1024; ++v)
        spread[v] = spread3(v);
    for (size_t i = 0; i < n; ++i) {
        uint32_t q[3];
        for (int k = 0; k < 3; ++k) {
            const double c = 0.5 * boxes[i].lo[k] + 0.5 * boxes[i].hi[k];
            double g = (c - lo[k]) * scale[k];
            g = g > 1023.0 ? 1023.0 : (g >= 0 ? g : 0.0); /* also catches NaN */
            q[k] = (uint32_t)g;
        }
        code[i] = spread[q[0]] | (spread[q[1]] << 1) | (spread[q[2]] << 2);
    }
}

/* order[] sorted by code, ties by index (stable LSD radix sort, 2 passes of 15 bits: the codes
 * have 30; a stable sort's result does not depend on the digits' width). */
enum { RADIX_BITS = 15, RADIX = 1u << RADIX_BITS };
static int radix_order(const uint32_t *code, size_t n, uint32_t *order)
{
    uint32_t *tmp = malloc(n * sizeof *tmp);
    size_t *count = malloc((RADIX + 1) * sizeof *count);
    if (tmp == NULL || count == NULL) {
        free(tmp);
        free(count);
        return -1;
    }
    for (size_t i = 0; i < n; ++i)
        order[i] = (uint32_t)i;
    uint32_t *src = order, *dst = tmp;
    for (int pass = 0; pass < 2; ++pass) {
        const int shift = RADIX_BITS * pass;
        memset(count, 0, (RADIX + 1) * sizeof *count);
        for (size_t i = 0; i < n; ++i)
            ++count[((code[src[i]] >> shift) & (RADIX - 1)) + 1];
        for (uint32_t d = 0; d < RADIX; ++d)
            count[d + 1] += count[d];
        for (size_t i = 0; i < n; ++i)
            dst[count[(code[src[i]] >> shift) & (RADIX - 1)]++] = src[i];
        uint32_t *s = src;
        src = dst;
        dst = s;
    }
    if (src != order)
        memcpy(order, src, n * sizeof *order);
    free(tmp);
    free(count);
    return 0;
}

/* Node idx over order[begin, end), its children allocated from *used. */
static void build_node(sweep_tree *t, const sweep_box *boxes, uint32_t leaf, uint32_t idx, uint32_t begin,
                       uint32_t end, size_t *used)
{
    sweep_node *nd = &t->nodes[idx];
    nd->begin = begin;
    nd->end = end;
    nd->pad = 0;
    if (end - begin <= leaf) {
        nd->left = 0;
        nd->box = boxes[t->order[begin]];
        for (uint32_t k = begin + 1; k < end; ++k)
            sweep_box_join(&nd->box, &boxes[t->order[k]]);
        return;
    }
    const uint32_t left = (uint32_t)*used;
    *used += 2;
    const uint32_t mid = begin + (end - begin) / 2;
    build_node(t, boxes, leaf, left, begin, mid, used);
    build_node(t, boxes, leaf, left + 1, mid, end, used);
    nd = &t->nodes[idx]; /* (the array does not move; kept for clarity after the calls) */
    nd->left = left;
    nd->box = t->nodes[left].box;
    sweep_box_join(&nd->box, &t->nodes[left + 1].box);
}

int sweep_tree_build(const sweep_box *boxes, size_t n, uint32_t leaf, sweep_tree *t)
{
    memset(t, 0, sizeof *t);
    if (leaf < 1)
        leaf = 1;
    /* A binary tree whose leaves hold at least one box each has at most 2 n - 1 nodes. */
    const size_t cap = 2 * n + 1;
    t->nodes = malloc(cap * sizeof *t->nodes);
    t->order = malloc(n * sizeof *t->order);
    uint32_t *code = malloc(n * sizeof *code);
    if (t->nodes == NULL || t->order == NULL || code == NULL) {
        free(code);
        sweep_tree_free(t);
        return -1;
    }
    morton_codes(boxes, n, code);
    if (radix_order(code, n, t->order) != 0) {
        free(code);
        sweep_tree_free(t);
        return -1;
    }
    free(code);
    size_t used = 1;
    build_node(t, boxes, leaf, 0, 0, (uint32_t)n, &used);
    t->nnodes = used;
    t->n = n;
    return 0;
}

void sweep_tree_free(sweep_tree *t)
{
    free(t->nodes);
    free(t->order);
    memset(t, 0, sizeof *t);
}
