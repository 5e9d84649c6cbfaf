// SPDX-License-Identifier: MIT
// Tight-Inclusion beside ttd in `ttd bench ccd` (optional, C++): ttd writes the queries of one
// file of the CCD benchmark to a temporary file, runs this program on it, and reads back TI's
// answer and time for each query, so that TI is timed on exactly the queries ttd was.
//
// Input (binary, native byte order): the 8 bytes "TTDCCDQ1", int32 kind (1 vertex-face, 2
// edge-edge), int32 reps, uint64 n, then n queries of 24 doubles: the 4 points at t = 0, then at
// t = 1 (vertex-face: v, f0, f1, f2; edge-edge: ea0, ea1, eb0, eb1).
// Output: n records of 3 doubles: hit (0 or 1), toi (inf without a hit), seconds (the fastest
// of reps runs of the query alone).
// TI's settings: err (-1, -1, -1) (its own filter per query), minimum separation 0, tolerance
// 1e-6, t_max 1, max_itr 1e6 (a query reaching it answers hit), its default root finder.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include <tight_inclusion/ccd.hpp>

int main(int argc, char **argv)
{
    if (argc != 3) {
        std::fprintf(stderr, "usage: ttd_ti_ccd_bench IN OUT (run by `ttd bench ccd`)\n");
        return 2;
    }
    std::FILE *in = std::fopen(argv[1], "rb");
    if (!in) {
        std::fprintf(stderr, "ttd_ti_ccd_bench: cannot open %s\n", argv[1]);
        return 1;
    }
    char magic[8];
    int32_t kind = 0, reps = 0;
    uint64_t n = 0;
    if (std::fread(magic, 1, 8, in) != 8 || std::memcmp(magic, "TTDCCDQ1", 8) != 0 ||
        std::fread(&kind, sizeof kind, 1, in) != 1 || std::fread(&reps, sizeof reps, 1, in) != 1 ||
        std::fread(&n, sizeof n, 1, in) != 1 || (kind != 1 && kind != 2) || reps < 1 || n > (1u << 26)) {
        std::fprintf(stderr, "ttd_ti_ccd_bench: %s is not a query file\n", argv[1]);
        std::fclose(in);
        return 1;
    }
    std::vector<double> q(24 * n);
    if (std::fread(q.data(), sizeof(double), q.size(), in) != q.size()) {
        std::fprintf(stderr, "ttd_ti_ccd_bench: %s is short\n", argv[1]);
        std::fclose(in);
        return 1;
    }
    std::fclose(in);
    const ticcd::Array3 err(-1, -1, -1);
    const double ms = 0, tolerance = 1e-6, t_max = 1;
    const long max_itr = 1000000;
    std::vector<double> out(3 * n);
    for (uint64_t i = 0; i < n; ++i) {
        const double *x0 = &q[24 * i], *x1 = x0 + 12;
        auto p = [](const double *x, int j) { return ticcd::Vector3(x[3 * j], x[3 * j + 1], x[3 * j + 2]); };
        double best = std::numeric_limits<double>::infinity(), toi = 0;
        bool hit = false;
        for (int r = 0; r < reps; ++r) {
            double output_tolerance = 0;
            toi = std::numeric_limits<double>::infinity();
            const auto t0 = std::chrono::steady_clock::now();
            if (kind == 1)
                hit = ticcd::vertexFaceCCD(p(x0, 0), p(x0, 1), p(x0, 2), p(x0, 3), p(x1, 0), p(x1, 1), p(x1, 2),
                                           p(x1, 3), err, ms, toi, tolerance, t_max, max_itr, output_tolerance);
            else
                hit = ticcd::edgeEdgeCCD(p(x0, 0), p(x0, 1), p(x0, 2), p(x0, 3), p(x1, 0), p(x1, 1), p(x1, 2),
                                         p(x1, 3), err, ms, toi, tolerance, t_max, max_itr, output_tolerance);
            const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            best = dt < best ? dt : best;
        }
        out[3 * i] = hit ? 1 : 0;
        out[3 * i + 1] = hit ? toi : std::numeric_limits<double>::infinity();
        out[3 * i + 2] = best;
    }
    std::FILE *o = std::fopen(argv[2], "wb");
    if (!o || std::fwrite(out.data(), sizeof(double), out.size(), o) != out.size()) {
        std::fprintf(stderr, "ttd_ti_ccd_bench: cannot write %s\n", argv[2]);
        if (o)
            std::fclose(o);
        return 1;
    }
    return std::fclose(o) == 0 ? 0 : 1;
}
