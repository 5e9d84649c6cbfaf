/* SPDX-License-Identifier: MIT */
/* The cells of the uniform grids that screen self queries (mesh/self_grid_impl.h for contacts,
 * meshccd/meshccd.c for CCD): shared so that both size their cells by one rule. */
#ifndef TTD_CORE_GRID_CELLS_H
#define TTD_CORE_GRID_CELLS_H

#include <math.h>
#include <stddef.h>

/* side[c]: per axis the largest side of the boxes that go into cells; lo, hi: per axis the least
 * and greatest low corner of those boxes; n: how many. Cells are a little wider than side (two
 * boxes that overlap or lie within the side have cells within 1 of each other despite the
 * rounding of (lo - lo_min) / h), an axis without width takes the largest side, and all grow by
 * 1.5 until there are at most 4 n + 64 cells. Writes the cell widths h and the cells per axis
 * dim; returns the number of cells, or 0 where no finite grid fits (a side of 0, a span that is
 * not finite): the caller keeps its hierarchy. */
static inline size_t ttd_grid_cells(const double side[3], const double lo[3], const double hi[3], size_t n,
                                    double h[3], size_t dim[3])
{
    for (int c = 0; c < 3; ++c)
        h[c] = side[c] * (1 + 0x1p-20);
    const double most = h[0] > h[1] ? (h[0] > h[2] ? h[0] : h[2]) : (h[1] > h[2] ? h[1] : h[2]);
    if (n == 0 || !(most > 0) || !isfinite(most))
        return 0;
    for (int c = 0; c < 3; ++c) {
        h[c] = h[c] > 0 ? h[c] : most;
        if (!isfinite(lo[c]) || !isfinite(hi[c]) || !isfinite(hi[c] - lo[c]))
            return 0;
    }
    /* finite spans and positive h: a span 2^2098 times the cell, the most doubles allow, fits
     * after about 3,590 rounds; the cap only guards that reasoning */
    for (int round = 0;; ++round) {
        double cells = 1;
        for (int c = 0; c < 3; ++c)
            cells *= floor((hi[c] - lo[c]) / h[c]) + 1;
        if (cells <= 4.0 * (double)n + 64)
            break;
        if (round == 4096)
            return 0;
        for (int c = 0; c < 3; ++c)
            h[c] *= 1.5;
    }
    size_t cells = 1;
    for (int c = 0; c < 3; ++c) {
        dim[c] = (size_t)floor((hi[c] - lo[c]) / h[c]) + 1;
        cells *= dim[c];
    }
    return cells;
}

#endif
