// SPDX-License-Identifier: MIT
// ttd_fcl_bench: times FCL's triangle distance (fcl::detail::TriangleDistance<S>::triDistance)
// on a workload written by `ttd bench`, so that FCL sees exactly the pairs ttd saw.
//
// Usage: ttd_fcl_bench IN OUT [MIN_SAMPLE_SECONDS [REPEATS]]
// IN  (little-endian, native):  "TTDW", u32 version=1, u32 bytes per real (4|8), u32 pad,
//                               u64 n, then 9n reals for the first triangles, 9n for the second.
// OUT:                          "TTDR", u32 version=1, u32 bytes per real, u32 repeats,
//                               u64 n, f64 median ns per pair, f64 min ns per pair,
//                               then n distances as f64 (FCL's result in the input precision).
// The timing loop mirrors ttd bench: one warm-up pass, then REPEATS samples, each of enough
// passes over the data to last MIN_SAMPLE_SECONDS; the median sample is reported. The
// vertices are copied into Eigen vectors inside the timed loop, as a caller holding plain
// arrays has to do.
#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

struct Header {
    char magic[4];
    uint32_t version;
    uint32_t bytes;
    uint32_t pad;
    uint64_t n;
};

template <typename S>
double run_pass(const std::vector<S> &s, const std::vector<S> &t, uint64_t n, double *dist)
{
    using V = fcl::Vector3<S>;
    double sum = 0.0;
    for (uint64_t i = 0; i < n; ++i) {
        const S *a = &s[9 * i];
        const S *b = &t[9 * i];
        V s1(a[0], a[1], a[2]), s2(a[3], a[4], a[5]), s3(a[6], a[7], a[8]);
        V t1(b[0], b[1], b[2]), t2(b[3], b[4], b[5]), t3(b[6], b[7], b[8]);
        V p, q;
        S d = fcl::detail::TriangleDistance<S>::triDistance(s1, s2, s3, t1, t2, t3, p, q);
        if (dist)
            dist[i] = static_cast<double>(d);
        sum += static_cast<double>(d);
    }
    return sum;
}

double now_s()
{
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

template <typename S>
int bench(FILE *in, uint64_t n, const char *out_path, double min_sample, int repeats)
{
    std::vector<S> s(9 * n), t(9 * n);
    if (std::fread(s.data(), sizeof(S), 9 * n, in) != 9 * n ||
        std::fread(t.data(), sizeof(S), 9 * n, in) != 9 * n) {
        std::fprintf(stderr, "ttd_fcl_bench: input file is truncated\n");
        return 1;
    }
    std::vector<double> dist(n);
    // Warm-up pass, which also records the distances; then double the passes per sample
    // until one sample lasts a quarter of MIN_SAMPLE_SECONDS, and scale up from there.
    volatile double sink = run_pass(s, t, n, dist.data());
    long passes = 1;
    double took = 0.0;
    for (;;) {
        double a = now_s();
        for (long k = 0; k < passes; ++k)
            sink = sink + run_pass(s, t, n, nullptr);
        took = now_s() - a;
        if (took >= 0.25 * min_sample || passes >= (1L << 30))
            break;
        passes *= 2;
    }
    if (took > 0.0 && took < min_sample)
        passes = std::max(passes, static_cast<long>(static_cast<double>(passes) * min_sample / took + 0.5));
    std::vector<double> samples;
    for (int r = 0; r < repeats; ++r) {
        double a = now_s();
        for (long k = 0; k < passes; ++k)
            sink = sink + run_pass(s, t, n, nullptr);
        samples.push_back((now_s() - a) * 1e9 / (static_cast<double>(passes) * static_cast<double>(n)));
    }
    (void)sink;
    std::sort(samples.begin(), samples.end());
    double median = samples[samples.size() / 2];
    if (samples.size() % 2 == 0)
        median = 0.5 * (samples[samples.size() / 2 - 1] + samples[samples.size() / 2]);

    FILE *out = std::fopen(out_path, "wb");
    if (!out) {
        std::perror(out_path);
        return 1;
    }
    Header h;
    std::memcpy(h.magic, "TTDR", 4);
    h.version = 1;
    h.bytes = sizeof(S);
    h.pad = static_cast<uint32_t>(repeats);
    h.n = n;
    double times[2] = {median, samples.front()};
    bool ok = std::fwrite(&h, sizeof h, 1, out) == 1 && std::fwrite(times, sizeof(double), 2, out) == 2 &&
              std::fwrite(dist.data(), sizeof(double), n, out) == n;
    ok = (std::fclose(out) == 0) && ok;
    if (!ok) {
        std::fprintf(stderr, "ttd_fcl_bench: cannot write %s\n", out_path);
        return 1;
    }
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    if (argc < 3 || argc > 5) {
        std::fprintf(stderr, "usage: %s IN OUT [MIN_SAMPLE_SECONDS [REPEATS]]\n"
                             "Times FCL's triDistance on a workload file written by `ttd bench`.\n",
                     argv[0]);
        return 2;
    }
    double min_sample = argc > 3 ? std::atof(argv[3]) : 0.05;
    int repeats = argc > 4 ? std::atoi(argv[4]) : 5;
    if (!(min_sample >= 0.0) || repeats < 1 || repeats > 1000) {
        std::fprintf(stderr, "ttd_fcl_bench: bad MIN_SAMPLE_SECONDS or REPEATS\n");
        return 2;
    }
    FILE *in = std::fopen(argv[1], "rb");
    if (!in) {
        std::perror(argv[1]);
        return 1;
    }
    Header h;
    if (std::fread(&h, sizeof h, 1, in) != 1 || std::memcmp(h.magic, "TTDW", 4) != 0 || h.version != 1 ||
        (h.bytes != 4 && h.bytes != 8) || h.n == 0 || h.n > (UINT64_C(1) << 36)) {
        std::fprintf(stderr, "ttd_fcl_bench: %s is not a ttd workload file\n", argv[1]);
        std::fclose(in);
        return 1;
    }
    int rc = h.bytes == 8 ? bench<double>(in, h.n, argv[2], min_sample, repeats)
                          : bench<float>(in, h.n, argv[2], min_sample, repeats);
    std::fclose(in);
    return rc;
}
