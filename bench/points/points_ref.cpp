// SPDX-License-Identifier: MIT
// The closest point of a mesh to many points in another library, for `ttd bench points`
// (bench/points_bench.c, docs/points.md): Embree 3's rtcPointQuery with a closest-point callback
// in double (Embree's tree is float; the callback measures the caller's double triangles, so the
// answers are ttd's to rounding), or CGAL's AABB_tree (double). Built for whichever of the two
// CMake finds (TTD_REF_EMBREE, TTD_REF_CGAL).
//
//   ttd_points_ref LIB FILE THREADS OUT      LIB: embree or cgal
// FILE (written by ttd): uint64 nv, nt, n; nv x 3 doubles; nt x 3 uint32; n x 3 doubles.
// Prints "build_seconds query_seconds" (wall clock, the query the best of 3 runs) and writes the
// n distances (doubles) to OUT. THREADS: the query's threads (points split into equal ranges).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#ifdef TTD_REF_EMBREE
#include <embree3/rtcore.h>
#endif
#ifdef TTD_REF_CGAL
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#endif

namespace {

struct Input {
    std::vector<double> v, p;
    std::vector<uint32_t> t;
};

double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Closest point on triangle (a, b, c) to p, squared distance (Ericson, Real-Time Collision
// Detection 5.1.5), in double.
double tri_dist2(const double *p, const double *a, const double *b, const double *c)
{
    double ab[3], ac[3], ap[3], q[3];
    for (int k = 0; k < 3; ++k) {
        ab[k] = b[k] - a[k];
        ac[k] = c[k] - a[k];
        ap[k] = p[k] - a[k];
    }
    auto dot = [](const double *x, const double *y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    auto set = [&](const double *base, const double *dir, double t) {
        for (int k = 0; k < 3; ++k)
            q[k] = base[k] + t * (dir ? dir[k] : 0);
    };
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    double bp[3], cp[3], bc[3];
    for (int k = 0; k < 3; ++k) {
        bp[k] = p[k] - b[k];
        cp[k] = p[k] - c[k];
        bc[k] = c[k] - b[k];
    }
    const double d3 = dot(ab, bp), d4 = dot(ac, bp), d5 = dot(ab, cp), d6 = dot(ac, cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d1 <= 0 && d2 <= 0)
        set(a, nullptr, 0);
    else if (d3 >= 0 && d4 <= d3)
        set(b, nullptr, 0);
    else if (vc <= 0 && d1 >= 0 && d3 <= 0)
        set(a, ab, d1 / (d1 - d3));
    else if (d6 >= 0 && d5 <= d6)
        set(c, nullptr, 0);
    else if (vb <= 0 && d2 >= 0 && d6 <= 0)
        set(a, ac, d2 / (d2 - d6));
    else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        set(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    else {
        const double den = va + vb + vc;
        if (!(std::fabs(den) > 0)) { // a degenerate triangle: its three edges
            double best = std::numeric_limits<double>::infinity();
            const double *e[3][2] = {{a, b}, {b, c}, {c, a}};
            for (auto &s : e) {
                double d[3], w[3];
                for (int k = 0; k < 3; ++k) {
                    d[k] = s[1][k] - s[0][k];
                    w[k] = p[k] - s[0][k];
                }
                const double dd = dot(d, d);
                const double t = dd > 0 ? std::min(1.0, std::max(0.0, dot(w, d) / dd)) : 0;
                double r2 = 0;
                for (int k = 0; k < 3; ++k)
                    r2 += (w[k] - t * d[k]) * (w[k] - t * d[k]);
                best = std::min(best, r2);
            }
            return best;
        }
        const double v = vb / den, w = vc / den;
        for (int k = 0; k < 3; ++k)
            q[k] = a[k] + ab[k] * v + ac[k] * w;
    }
    double r2 = 0;
    for (int k = 0; k < 3; ++k)
        r2 += (p[k] - q[k]) * (p[k] - q[k]);
    return r2;
}

template <class F> void parallel(size_t n, int threads, F f)
{
    if (threads <= 1) {
        f(0, n);
        return;
    }
    std::vector<std::thread> pool;
    for (int i = 0; i < threads; ++i)
        pool.emplace_back([=] { f(n * (size_t)i / (size_t)threads, n * (size_t)(i + 1) / (size_t)threads); });
    for (auto &t : pool)
        t.join();
}

#ifdef TTD_REF_EMBREE
struct EmbreeQuery {
    const Input *in;
    const double *p;
    double best2;
    float slack;
};

bool embree_closest(RTCPointQueryFunctionArguments *args)
{
    EmbreeQuery *q = static_cast<EmbreeQuery *>(args->userPtr);
    const uint32_t *t = &q->in->t[3 * (size_t)args->primID];
    const double *v = q->in->v.data();
    const double d2 = tri_dist2(q->p, v + 3 * t[0], v + 3 * t[1], v + 3 * t[2]);
    if (d2 < q->best2) {
        q->best2 = d2;
        args->query->radius = (float)std::sqrt(d2) * (1 + 1e-5f) + q->slack;
        return true;
    }
    return false;
}
#endif

} // namespace

int main(int argc, char **argv)
{
    if (argc != 5) {
        std::fprintf(stderr, "usage: ttd_points_ref embree|cgal FILE THREADS OUT\n");
        return 2;
    }
    const std::string lib = argv[1];
    const int threads = std::max(1, std::atoi(argv[3]));
    Input in;
    FILE *f = std::fopen(argv[2], "rb");
    uint64_t h[3];
    if (f == nullptr || std::fread(h, 8, 3, f) != 3) {
        std::fprintf(stderr, "ttd_points_ref: cannot read %s\n", argv[2]);
        return 1;
    }
    in.v.resize(3 * h[0]);
    in.t.resize(3 * h[1]);
    in.p.resize(3 * h[2]);
    if (std::fread(in.v.data(), 8, in.v.size(), f) != in.v.size() || std::fread(in.t.data(), 4, in.t.size(), f) != in.t.size() ||
        std::fread(in.p.data(), 8, in.p.size(), f) != in.p.size()) {
        std::fprintf(stderr, "ttd_points_ref: %s is short\n", argv[2]);
        return 1;
    }
    std::fclose(f);
    const size_t n = h[2];
    std::vector<double> dist(n);
    double build = 0, query = 1e300;
    if (lib == "embree") {
#ifdef TTD_REF_EMBREE
        double t0 = now();
        RTCDevice dev = rtcNewDevice(threads == 1 ? "threads=1" : nullptr);
        RTCScene scene = rtcNewScene(dev);
        rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        float *vb = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), h[0]);
        unsigned *ib = (unsigned *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), h[1]);
        float scale = 0;
        for (size_t i = 0; i < in.v.size(); ++i) {
            vb[i] = (float)in.v[i];
            scale = std::max(scale, std::fabs(vb[i]));
        }
        std::memcpy(ib, in.t.data(), in.t.size() * 4);
        rtcSetGeometryPointQueryFunction(g, embree_closest);
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(scene);
        build = now() - t0;
        for (int rep = 0; rep < 3; ++rep) {
            t0 = now();
            parallel(n, threads, [&](size_t i0, size_t i1) {
                for (size_t i = i0; i < i1; ++i) {
                    RTCPointQueryContext ctx;
                    rtcInitPointQueryContext(&ctx);
                    RTCPointQuery q;
                    q.x = (float)in.p[3 * i];
                    q.y = (float)in.p[3 * i + 1];
                    q.z = (float)in.p[3 * i + 2];
                    q.time = 0;
                    q.radius = std::numeric_limits<float>::infinity();
                    // the float point is within a float ulp of the double one: the slack covers it
                    EmbreeQuery u{&in, &in.p[3 * i], std::numeric_limits<double>::infinity(), 4e-7f * scale};
                    rtcPointQuery(scene, &q, &ctx, nullptr, &u);
                    dist[i] = std::sqrt(u.best2);
                }
            });
            query = std::min(query, now() - t0);
        }
        rtcReleaseScene(scene);
        rtcReleaseDevice(dev);
#else
        std::fprintf(stderr, "ttd_points_ref: built without Embree\n");
        return 3;
#endif
    } else if (lib == "cgal") {
#ifdef TTD_REF_CGAL
        typedef CGAL::Simple_cartesian<double> K;
        typedef std::vector<K::Triangle_3>::const_iterator It;
        typedef CGAL::AABB_triangle_primitive<K, It> Prim;
        typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Prim>> Tree;
        double t0 = now();
        std::vector<K::Triangle_3> tris;
        tris.reserve(h[1]);
        for (size_t i = 0; i < h[1]; ++i) {
            const double *a = &in.v[3 * in.t[3 * i]], *b = &in.v[3 * in.t[3 * i + 1]], *c = &in.v[3 * in.t[3 * i + 2]];
            tris.emplace_back(K::Point_3(a[0], a[1], a[2]), K::Point_3(b[0], b[1], b[2]), K::Point_3(c[0], c[1], c[2]));
        }
        Tree tree(tris.begin(), tris.end());
        tree.accelerate_distance_queries();
        build = now() - t0;
        for (int rep = 0; rep < 3; ++rep) {
            t0 = now();
            parallel(n, threads, [&](size_t i0, size_t i1) {
                for (size_t i = i0; i < i1; ++i)
                    dist[i] = std::sqrt(tree.squared_distance(K::Point_3(in.p[3 * i], in.p[3 * i + 1], in.p[3 * i + 2])));
            });
            query = std::min(query, now() - t0);
        }
#else
        std::fprintf(stderr, "ttd_points_ref: built without CGAL\n");
        return 3;
#endif
    } else {
        std::fprintf(stderr, "ttd_points_ref: unknown library %s\n", lib.c_str());
        return 2;
    }
    FILE *o = std::fopen(argv[4], "wb");
    if (o == nullptr || std::fwrite(dist.data(), 8, n, o) != n || std::fclose(o) != 0) {
        std::fprintf(stderr, "ttd_points_ref: cannot write %s\n", argv[4]);
        return 1;
    }
    std::printf("%.9g %.9g\n", build, query);
    return 0;
}
