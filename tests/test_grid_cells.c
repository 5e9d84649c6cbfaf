/* SPDX-License-Identifier: MIT */
/* The self grids' cell rule (src/core/grid_cells.h), against construction: boxes whose low corners
 * lie within one side of each other get cells within 1 of each other on every axis, the count
 * stays at most 4 n + 64, an axis without width takes the largest side, and no grid is made where
 * none is finite (a side of 0, an infinite or overflowing span) or there are no boxes. */
#include <float.h>
#include <math.h>
#include <stdint.h>

#include "core/grid_cells.h"
#include "test_macros.h"

static size_t cell_of(double x, double lo, double h, size_t dim)
{
    size_t q = (size_t)floor((x - lo) / h);
    return q < dim ? q : dim - 1;
}

/* pairs of corners one side apart (and a rounding step less), at scales 2^-60 .. 2^60 and offsets
 * far from the origin: their cells differ by at most 1 */
static int neighbours_within_one_cell(void)
{
    uint64_t seed = 12345;
    for (int k = 0; k < 20000; ++k) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        const double scale = ldexp(1.0, (int)(seed >> 58) * 4 - 60 + (int)((seed >> 40) & 3));
        const double off = ((double)(seed >> 11 & 0xffff) - 32768.0) * scale * 1e3;
        const double side[3] = {scale * (1 + (double)(seed & 7)), scale, k % 3 ? scale * 0.5 : 0.0};
        /* every other case a grid that needs no growth (spans of a few sides, many boxes), where
         * the cell is the side widened by the rule alone */
        const int tight = k & 1;
        const double lo[3] = {off, off * 0.5, -off};
        const double hi[3] = {off + scale * (tight ? 10 : 900), off * 0.5 + scale * (tight ? 9 : 37), -off + scale};
        double h[3];
        size_t dim[3];
        const size_t n = tight ? 4096 : 1 + (size_t)(seed >> 20 & 1023);
        const size_t cells = ttd_grid_cells(side, lo, hi, n, h, dim);
        ENSURE(cells > 0);
        ENSURE(cells == dim[0] * dim[1] * dim[2]);
        ENSURE((double)cells <= 4.0 * (double)n + 64);
        for (int c = 0; c < 3; ++c) {
            ENSURE(h[c] >= (side[c] > 0 ? side[c] : side[0]));
            /* corners spread over the span and corners just below a cell's upper edge (where a
             * cell narrower than the side puts the corner one side further two cells on), each
             * against the corner one side further: cells within 1 */
            const double step = side[c] > 0 ? side[c] : side[0];
            double xs[16];
            for (int m = 0; m < 8; ++m) {
                xs[m] = lo[c] + (hi[c] - lo[c]) * m / 8;
                xs[8 + m] = lo[c] + (double)(m + 1) * h[c] * (1 - 0x1p-40);
            }
            for (int m = 0; m < 16; ++m) {
                const double x = xs[m];
                if (!(x + step <= hi[c]))
                    continue;
                const size_t a = cell_of(x, lo[c], h[c], dim[c]), b = cell_of(x + step, lo[c], h[c], dim[c]);
                ENSURE_MSG(b - a <= 1, "axis %d: cells %zu and %zu for corners %.17g apart (h %.17g)", c, a, b,
                           step, h[c]);
            }
        }
    }
    return 0;
}

static int no_grid_where_none_is_finite(void)
{
    double h[3];
    size_t dim[3];
    const double one[3] = {1, 1, 1}, zero[3] = {0, 0, 0}, lo[3] = {0, 0, 0}, hi[3] = {10, 10, 10};
    ENSURE(ttd_grid_cells(one, lo, hi, 0, h, dim) == 0);        /* no boxes */
    ENSURE(ttd_grid_cells(zero, lo, hi, 5, h, dim) == 0);       /* every box a point */
    const double inf_side[3] = {1, INFINITY, 1};
    ENSURE(ttd_grid_cells(inf_side, lo, hi, 5, h, dim) == 0);
    const double wide_lo[3] = {-DBL_MAX, 0, 0}, wide_hi[3] = {DBL_MAX, 1, 1}; /* the span overflows */
    ENSURE(ttd_grid_cells(one, wide_lo, wide_hi, 5, h, dim) == 0);
    const double inf_hi[3] = {INFINITY, 1, 1};
    ENSURE(ttd_grid_cells(one, lo, inf_hi, 5, h, dim) == 0);
    /* the largest finite span over the smallest side: grows to a fit, finite */
    const double tiny[3] = {0x1p-1074, 0x1p-1074, 0x1p-1074}, big_lo[3] = {-0x1p1022, 0, 0},
                 big_hi[3] = {0x1p1022, 0, 0};
    const size_t cells = ttd_grid_cells(tiny, big_lo, big_hi, 3, h, dim);
    ENSURE(cells > 0 && cells <= 4 * 3 + 64 && isfinite(h[0]));
    return 0;
}

int main(int argc, char **argv)
{
    TEST_MAIN_BEGIN(argc, argv);
    RUN_TEST(neighbours_within_one_cell);
    RUN_TEST(no_grid_where_none_is_finite);
    TEST_MAIN_END();
}
