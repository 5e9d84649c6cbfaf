// SPDX-License-Identifier: MIT
// The scene workload that `ttd bench` writes for the programs timed beside it (FCL's,
// bench/fcl/fcl_scene_bench.cpp; Bullet's, bench/bullet/bullet_scene_bench.cpp): its reader,
// with every count and pose checked, and the timing helpers both use. The format is in
// bench/fcl_scene_link.h.
#ifndef TTD_BENCH_SCENE_JOB_HPP
#define TTD_BENCH_SCENE_JOB_HPP

#include "fcl_scene_link.h"

#include <algorithm>
#include <cerrno>
#include <new>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace scene_job {

// FCL and Bullet count vertices, triangles and tree nodes (2 nt - 1) in int.
constexpr uint64_t kMaxCount = UINT64_C(1) << 30;

struct Mesh {
    uint64_t nv = 0, nt = 0;
    std::vector<double> v;
    std::vector<uint32_t> t;
};

struct BadInput : std::runtime_error {
    using std::runtime_error::runtime_error;
};

inline std::string format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
inline std::string format(const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return buf;
}

// Little-endian decoding byte by byte, so that the reader does not depend on the host's order.
class Reader {
public:
    Reader(const unsigned char *p, size_t n) : p_(p), left_(n) {}
    uint64_t left() const { return left_; }
    void need(uint64_t bytes, const char *what) const
    {
        if (bytes > left_)
            throw BadInput(format("truncated: %s needs %" PRIu64 " bytes, %" PRIu64 " left", what, bytes,
                                  left_));
    }
    uint64_t uint(int bytes)
    {
        uint64_t x = 0;
        for (int i = 0; i < bytes; ++i)
            x |= static_cast<uint64_t>(p_[i]) << (8 * i);
        p_ += bytes;
        left_ -= static_cast<uint64_t>(bytes);
        return x;
    }
    uint32_t u32(const char *what) { need(4, what); return static_cast<uint32_t>(uint(4)); }
    uint64_t u64(const char *what) { need(8, what); return uint(8); }
    double f64(const char *what)
    {
        need(8, what);
        uint64_t bits = uint(8);
        double x;
        std::memcpy(&x, &bits, sizeof x);
        return x;
    }
    void bytes(void *out, size_t n) { std::memcpy(out, p_, n); p_ += n; left_ -= n; }

private:
    const unsigned char *p_;
    uint64_t left_;
};

inline void read_mesh(Reader &r, Mesh &m, unsigned name)
{
    std::string w = format("mesh %u", name);
    m.nv = r.u64((w + " vertex count").c_str());
    m.nt = r.u64((w + " triangle count").c_str());
    if (m.nv < 3 || m.nt < 1)
        throw BadInput(format("mesh %u: %" PRIu64 " vertices and %" PRIu64 " triangles; needs >= 3 and >= 1", name,
                              m.nv, m.nt));
    if (m.nv > kMaxCount || m.nt > kMaxCount)
        throw BadInput(format("mesh %u: %" PRIu64 " vertices, %" PRIu64 " triangles: more than FCL's int counts allow",
                              name, m.nv, m.nt));
    r.need(24 * m.nv + 12 * m.nt, (w + " arrays").c_str());
    m.v.resize(3 * m.nv);
    for (uint64_t i = 0; i < 3 * m.nv; ++i) {
        m.v[i] = r.f64("vertex");
        if (!std::isfinite(m.v[i]))
            throw BadInput(format("mesh %u: vertex %" PRIu64 " has a non-finite coordinate", name, i / 3));
    }
    m.t.resize(3 * m.nt);
    for (uint64_t i = 0; i < 3 * m.nt; ++i) {
        m.t[i] = r.u32("triangle");
        if (m.t[i] >= m.nv)
            throw BadInput(format("mesh %u: triangle %" PRIu64 " uses vertex %" PRIu32 ", out of range (%" PRIu64
                                  " vertices)",
                                  name, i / 3, m.t[i], m.nv));
    }
}

inline void check_pose(const double *m, uint64_t k)
{
    for (int i = 0; i < 12; ++i)
        if (!std::isfinite(m[i]))
            throw BadInput(format("pose %" PRIu64 " has a non-finite entry", k));
    double worst = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double dot = m[4 * i] * m[4 * j] + m[4 * i + 1] * m[4 * j + 1] + m[4 * i + 2] * m[4 * j + 2];
            worst = std::max(worst, std::fabs(dot - (i == j ? 1.0 : 0.0)));
        }
    double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
                 m[2] * (m[4] * m[9] - m[5] * m[8]);
    if (worst > 1e-9 || det <= 0.0)
        throw BadInput(format("pose %" PRIu64 ": R is not a rotation (|R R^T - I| = %.3g, det %.17g)", k, worst, det));
}

inline double now_ms()
{
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double, std::milli>(clock::now().time_since_epoch()).count();
}

inline double median_of(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Job {
    uint32_t repetitions = 0, motion_runs = 0, steps = 0;
    double margin = 0.0;
    std::vector<Mesh> meshes;
    uint64_t n = 0;
    std::vector<uint32_t> body_mesh;
    std::vector<double> poses, motion;
};

inline Job read_job(const std::vector<unsigned char> &file)
{
    Reader r(file.data(), file.size());
    r.need(8, "magic");
    char magic[8];
    r.bytes(magic, 8);
    if (std::memcmp(magic, BENCH_FCL_SCENE_MAGIC, 8) != 0)
        throw BadInput("not a ttd scene workload (magic is not TTDSCEN1)");
    Job job;
    job.repetitions = r.u32("repetitions");
    if (job.repetitions < 1 || job.repetitions > 1000)
        throw BadInput(format("repetitions %" PRIu32 " out of range [1, 1000]", job.repetitions));
    job.motion_runs = r.u32("motion runs");
    if (job.motion_runs > 1000)
        throw BadInput(format("motion runs %" PRIu32 " out of range [0, 1000]", job.motion_runs));
    job.margin = r.f64("margin");
    if (!std::isfinite(job.margin) || job.margin <= 0.0)
        throw BadInput(format("margin %g is not a finite number > 0", job.margin));
    uint32_t nm = r.u32("mesh count");
    if (nm < 1 || nm > 1024)
        throw BadInput(format("%" PRIu32 " meshes (1..1024)", nm));
    job.meshes.resize(nm);
    for (uint32_t m = 0; m < nm; ++m)
        read_mesh(r, job.meshes[m], m);
    job.n = r.u64("body count");
    if (job.n < 2 || job.n > r.left() / 100)
        throw BadInput(format("%" PRIu64 " bodies: fewer than 2, or more than the file holds", job.n));
    job.body_mesh.resize(job.n);
    job.poses.resize(12 * job.n);
    for (uint64_t b = 0; b < job.n; ++b) {
        job.body_mesh[b] = r.u32("body mesh");
        if (job.body_mesh[b] >= nm)
            throw BadInput(format("body %" PRIu64 ": mesh %" PRIu32 " out of range", b, job.body_mesh[b]));
        for (int i = 0; i < 12; ++i)
            job.poses[12 * b + i] = r.f64("pose");
        check_pose(&job.poses[12 * b], b);
    }
    job.steps = r.u32("steps");
    if (job.steps > r.left() / (96 * job.n))
        throw BadInput(format("truncated: %" PRIu32 " motion steps", job.steps));
    if (job.steps == 0 && job.motion_runs)
        throw BadInput("motion runs without motion steps");
    job.motion.resize(12 * job.n * job.steps);
    for (auto &x : job.motion)
        x = r.f64("motion pose");
    for (uint64_t k = 0; k < job.n * job.steps; ++k)
        check_pose(&job.motion[12 * k], k);
    if (r.left() != 0)
        throw BadInput(format("%" PRIu64 " bytes after the last pose", r.left()));
    return job;
}

template <class F>
inline void time_runs(uint32_t reps, F run, double &median_ms, double &min_ms)
{
    std::vector<double> t(reps);
    for (uint32_t r = 0; r < reps; ++r) {
        double a = now_ms();
        run();
        t[r] = now_ms() - a;
    }
    median_ms = median_of(t);
    min_ms = *std::min_element(t.begin(), t.end());
}

inline bool read_file(const char *path, std::vector<unsigned char> &out)
{
    FILE *f = std::fopen(path, "rb");
    if (!f)
        return false;
    unsigned char buf[1 << 16];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
        out.insert(out.end(), buf, buf + n);
    bool ok = !std::ferror(f);
    std::fclose(f);
    return ok;
}

// The programs' main: reads IN (the only argument), runs `run` on the job; messages start with
// the program's name. 0, or 1 (bad input, out of memory, a failure), 2 (usage).
template <class F>
inline int job_main(int argc, char **argv, const char *name, const char *what, F run)
{
    if (argc != 2 || argv[1][0] == '-') {
        std::fprintf(stderr, "usage: %s IN\n%s on a scene written by `ttd bench`\n"
                             "(format: bench/fcl_scene_link.h); the answers on stdout.\n",
                     argc > 0 ? argv[0] : name, what);
        return 2;
    }
    std::vector<unsigned char> file;
    if (!read_file(argv[1], file)) {
        std::fprintf(stderr, "%s: %s: %s\n", name, argv[1], std::strerror(errno));
        return 1;
    }
    try {
        const Job job = read_job(file);
        file.clear();
        file.shrink_to_fit();
        run(job);
        if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
            std::fprintf(stderr, "%s: cannot write the output\n", name);
            return 1;
        }
    } catch (const BadInput &e) {
        std::fprintf(stderr, "%s: %s: %s\n", name, argv[1], e.what());
        return 1;
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "%s: out of memory\n", name);
        return 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "%s: %s\n", name, e.what());
        return 1;
    }
    return 0;
}

} // namespace scene_job

#endif // TTD_BENCH_SCENE_JOB_HPP
