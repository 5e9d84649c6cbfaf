/* SPDX-License-Identifier: MIT */
/* The points of a batch in spatial order (points/points.h): the closest-point walk and the winding
 * number's go in that order, so that consecutive points share nodes in the cache (and the closest
 * point's walk its seed). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "points/points.h"

/* The points' order along a Morton curve over the mesh's box (10 bits an axis, the walk nodes'
 * frame [-1, 1]^3; points outside are clamped, a NaN point goes first), sorted stably by
 * three passes of radix sort: consecutive points are near each other, so the previous point's
 * answer seeds the next walk and the nodes they share stay in cache. NULL when out of memory
 * (the points then go in input order: the same results). */
size_t *ttd_points_order(const struct ttd_mesh *m, const ttd_points_data *pd, size_t n, const void *points, int bytes)
{
    size_t *order = malloc(2 * n * sizeof *order);
    uint32_t *code = malloc(2 * n * sizeof *code);
    size_t *count = calloc(1024, sizeof *count);
    if (order == NULL || code == NULL || count == NULL) {
        free(order), free(code), free(count);
        return NULL;
    }
    for (size_t i = 0; i < n; ++i) {
        uint32_t c = 0;
        for (int a = 0; a < 3; ++a) {
            const size_t at = 3 * i + (size_t)a;
            const double p = bytes == 8 ? ((const double *)points)[at] : (double)((const float *)points)[at];
            const double x = (p - m->origin[a]) * pd->scale;
            const double g = (x + 1) * 512; /* NaN fails both tests below: cell 0 */
            uint32_t q = g > 0 ? (g < 1023 ? (uint32_t)g : 1023u) : 0u;
            q = (q | q << 16) & 0x030000FFu; /* the bits of q spread to every third place */
            q = (q | q << 8) & 0x0300F00Fu;
            q = (q | q << 4) & 0x030C30C3u;
            q = (q | q << 2) & 0x09249249u;
            c |= q << a;
        }
        code[i] = c;
        order[i] = i;
    }
    size_t *src = order, *dst = order + n;
    uint32_t *csrc = code, *cdst = code + n;
    for (int pass = 0; pass < 3; ++pass) {
        const int sh = 10 * pass;
        memset(count, 0, 1024 * sizeof *count);
        for (size_t i = 0; i < n; ++i)
            ++count[csrc[i] >> sh & 1023u];
        size_t sum = 0;
        for (int b = 0; b < 1024; ++b) {
            const size_t c = count[b];
            count[b] = sum;
            sum += c;
        }
        for (size_t i = 0; i < n; ++i) {
            const size_t at = count[csrc[i] >> sh & 1023u]++;
            dst[at] = src[i];
            cdst[at] = csrc[i];
        }
        size_t *t = src;
        src = dst, dst = t;
        uint32_t *ct = csrc;
        csrc = cdst, cdst = ct;
    }
    /* three passes: the sorted order is in the second half */
    memmove(order, src, n * sizeof *order);
    free(code), free(count);
    return order;
}
