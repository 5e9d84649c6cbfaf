// SPDX-License-Identifier: MIT
// ttd_fcl_mesh_bench: FCL 0.7's mesh-vs-mesh queries, timed on a workload written by `ttd bench`
// (bench/fcl_mesh_link.c), so that FCL and ttd answer the same meshes and poses in one run.
//
// Usage: ttd_fcl_mesh_bench IN [--pairs FILE]
//
// IN (little-endian):
//   char magic[8] "TTDMESH1"; uint32 query (0 distance, 1 collision, 2 pairs within margin);
//   uint32 repetitions (>= 1); double margin;
//   uint64 nvA, ntA; double vA[3*nvA]; uint32 tA[3*ntA];
//   uint64 nvB, ntB; double vB[3*nvB]; uint32 tB[3*ntB];
//   uint64 K; double pose[12*K], each [R | t] row by row with x_A = R x_B + t (A at identity).
// Every count is checked against the file size before anything is allocated; indices must be in
// range, numbers finite, R a rotation (|R R^T - I| <= 1e-9, det > 0), and nothing may follow.
//
// Output on stdout (numbers %.17g):
//   build_ms A B
//   # ttd_fcl_mesh_bench fcl VERSION query NAME repetitions N margin M poses K
//   # <the row's field names>
//   query 0: pose median_ms min_ms distance px py pz qx qy qz ia ib bv_tests leaf_tests
//   query 1: pose median_ms min_ms collide ia ib bv_tests leaf_tests margin
//   query 2: pose median_ms min_ms pairs bv_tests leaf_tests
// --pairs FILE (query 2): "TTDPAIR1", uint64 K, then per pose uint64 n and n records
// {uint32 ia, uint32 ib, double d}, sorted by (ia, ib). bench/fcl_mesh_link.h says the same.
//
// What is timed: each query `repetitions` times per pose (median and fastest reported), with the
// collision objects made once and only moved (setTransform + computeAABB) between poses, as a
// caller looping over poses does. The build is timed from the caller's arrays to endModel().
#include "fcl_mesh_link.h"

#include <fcl/config.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>
#include <fcl/narrowphase/detail/traversal/collision/mesh_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/collision_node.h>
#include <fcl/narrowphase/detail/traversal/distance/mesh_distance_traversal_node.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using Model = fcl::BVHModel<fcl::OBBRSSd>;

// FCL counts vertices, triangles and tree nodes (2 nt - 1) in int.
constexpr uint64_t kMaxCount = UINT64_C(1) << 30;

struct Mesh {
    uint64_t nv = 0, nt = 0;
    std::vector<double> v;
    std::vector<uint32_t> t;
};

struct Job {
    uint32_t query = 0, repetitions = 0;
    double margin = 0.0;
    Mesh a, b;
    uint64_t k = 0;
    std::vector<double> poses;
};

struct BadInput : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char *fmt, ...)
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

void read_mesh(Reader &r, Mesh &m, char name)
{
    std::string w = format("mesh %c", name);
    m.nv = r.u64((w + " vertex count").c_str());
    m.nt = r.u64((w + " triangle count").c_str());
    if (m.nv < 3 || m.nt < 1)
        throw BadInput(format("mesh %c: %" PRIu64 " vertices and %" PRIu64 " triangles; needs >= 3 and >= 1", name,
                              m.nv, m.nt));
    if (m.nv > kMaxCount || m.nt > kMaxCount)
        throw BadInput(format("mesh %c: %" PRIu64 " vertices, %" PRIu64 " triangles: more than FCL's int counts allow",
                              name, m.nv, m.nt));
    r.need(24 * m.nv + 12 * m.nt, (w + " arrays").c_str());
    m.v.resize(3 * m.nv);
    for (uint64_t i = 0; i < 3 * m.nv; ++i) {
        m.v[i] = r.f64("vertex");
        if (!std::isfinite(m.v[i]))
            throw BadInput(format("mesh %c: vertex %" PRIu64 " has a non-finite coordinate", name, i / 3));
    }
    m.t.resize(3 * m.nt);
    for (uint64_t i = 0; i < 3 * m.nt; ++i) {
        m.t[i] = r.u32("triangle");
        if (m.t[i] >= m.nv)
            throw BadInput(format("mesh %c: triangle %" PRIu64 " uses vertex %" PRIu32 ", out of range (%" PRIu64
                                  " vertices)",
                                  name, i / 3, m.t[i], m.nv));
    }
}

void check_pose(const double *m, uint64_t k)
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

Job read_job(const std::vector<unsigned char> &file)
{
    Reader r(file.data(), file.size());
    r.need(8, "magic");
    char magic[8];
    r.bytes(magic, 8);
    if (std::memcmp(magic, BENCH_FCL_MESH_MAGIC, 8) != 0)
        throw BadInput("not a ttd mesh workload (magic is not TTDMESH1)");
    Job job;
    job.query = r.u32("query");
    if (job.query >= BENCH_FCL_MESH_QUERY_COUNT)
        throw BadInput(format("query %" PRIu32 " unknown (0 distance, 1 collision, 2 pairs, 3 refit)", job.query));
    job.repetitions = r.u32("repetitions");
    if (job.repetitions < 1 || job.repetitions > 1000000)
        throw BadInput(format("repetitions %" PRIu32 " out of range [1, 1000000]", job.repetitions));
    job.margin = r.f64("margin");
    if (!std::isfinite(job.margin) || job.margin < 0.0)
        throw BadInput(format("margin %g is not a finite number >= 0", job.margin));
    read_mesh(r, job.a, 'A');
    read_mesh(r, job.b, 'B');
    if (job.query == BENCH_FCL_MESH_REFIT &&
        (job.a.nv != job.b.nv || job.a.nt != job.b.nt || job.a.t != job.b.t))
        throw BadInput("refit: B must hold A's triangles (and as many vertices), moved");
    job.k = r.u64("pose count");
    if (job.k < 1)
        throw BadInput("no poses");
    if (job.k > r.left() / 96)
        throw BadInput(format("truncated: %" PRIu64 " poses need %" PRIu64 " bytes or more, %" PRIu64 " left", job.k,
                              job.k > UINT64_MAX / 96 ? UINT64_MAX : 96 * job.k, r.left()));
    job.poses.resize(12 * job.k);
    for (auto &x : job.poses)
        x = r.f64("pose");
    for (uint64_t k = 0; k < job.k; ++k)
        check_pose(&job.poses[12 * k], k);
    if (r.left() != 0)
        throw BadInput(format("%" PRIu64 " bytes after the last pose", r.left()));
    return job;
}

double now_ms()
{
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double, std::milli>(clock::now().time_since_epoch()).count();
}

double median_of(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::shared_ptr<Model> build_once(const Mesh &m)
{
    std::vector<fcl::Vector3d> ps(m.nv);
    for (uint64_t i = 0; i < m.nv; ++i)
        ps[i] = fcl::Vector3d(m.v[3 * i], m.v[3 * i + 1], m.v[3 * i + 2]);
    std::vector<fcl::Triangle> ts(m.nt);
    for (uint64_t i = 0; i < m.nt; ++i)
        ts[i] = fcl::Triangle(m.t[3 * i], m.t[3 * i + 1], m.t[3 * i + 2]);
    auto model = std::make_shared<Model>();
    if (model->beginModel(static_cast<int>(m.nt), static_cast<int>(m.nv)) != fcl::BVH_OK ||
        model->addSubModel(ps, ts) != fcl::BVH_OK || model->endModel() != fcl::BVH_OK)
        throw std::runtime_error("FCL could not build a BVHModel<OBBRSS>");
    return model;
}

// A build of a second or more is timed once. A shorter one is taken as a warm-up (its first
// allocations fault pages in, which made the first mesh's build 1.6x slower than the second's
// on the same mesh) and timed again up to 5 times or 0.5 s, the median reported.
std::shared_ptr<Model> build(const Mesh &m, double &ms)
{
    double a = now_ms();
    std::shared_ptr<Model> model = build_once(m);
    ms = now_ms() - a;
    if (ms >= 1000.0)
        return model;
    std::vector<double> t;
    double total = 0.0;
    do {
        model.reset();
        a = now_ms();
        model = build_once(m);
        t.push_back(now_ms() - a);
        total += t.back();
    } while (t.size() < 5 && total < 500.0);
    ms = median_of(t);
    return model;
}

fcl::Transform3d pose_transform(const double *m)
{
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    fcl::Matrix3d R;
    R << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
    tf.linear() = R;
    tf.translation() = fcl::Vector3d(m[3], m[7], m[11]);
    return tf;
}

template <class F>
void time_runs(uint32_t reps, F run, double &median_ms, double &min_ms)
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

// Query 0. fcl::distance returns no traversal counts, so FCL's own traversal node for OBBRSS
// meshes (the one fcl::distance runs) is run once more, untimed, with enable_statistics; its
// distance and triangle ids are checked against the timed call. FCL also tests one triangle
// pair (0, 0) before descending, to seed the bound, without counting it: leaf_tests adds it.
//
// Frame of the nearest points: in FCL 0.7 the leaf tests compute both points in A's frame and
// postprocess() maps them by A's transform, so they come back in the world frame (earlier
// versions returned each in its own object's frame). Checked in the source
// (distancePostprocessOrientedNode in mesh_distance_traversal_node-inl.h) and by a run with A
// rotated and moved, where both points came back in world coordinates. A is at the identity
// here, so the world frame is A's frame and no conversion is needed; tests/fcl checks that p and
// q lie on triangles ia of A and ib of B (mapped by the pose) and are `distance` apart.
void run_distance(const Job &job, const std::shared_ptr<Model> &A, const std::shared_ptr<Model> &B)
{
    std::printf("# pose median_ms min_ms distance px py pz qx qy qz ia ib bv_tests leaf_tests\n");
    fcl::CollisionObjectd oa(A), ob(B);
    fcl::DistanceRequestd request(true); // nearest points; rel_err = abs_err = 0: exact
    const fcl::Transform3d identity = fcl::Transform3d::Identity();
    for (uint64_t k = 0; k < job.k; ++k) {
        const fcl::Transform3d tf = pose_transform(&job.poses[12 * k]);
        ob.setTransform(tf);
        ob.computeAABB();
        fcl::DistanceResultd result;
        double med, mn;
        time_runs(job.repetitions, [&] {
            result.clear();
            fcl::distance(&oa, &ob, request, result);
        }, med, mn);

        fcl::detail::MeshDistanceTraversalNodeOBBRSS<double> node;
        fcl::DistanceResultd counted;
        if (!fcl::detail::initialize(node, *A, identity, *B, tf, request, counted))
            throw std::runtime_error("FCL's distance traversal did not initialise");
        node.enable_statistics = true;
        fcl::detail::distance(&node);
        if (counted.min_distance != result.min_distance || counted.b1 != result.b1 || counted.b2 != result.b2)
            std::fprintf(stderr, "ttd_fcl_mesh_bench: pose %" PRIu64 ": the counted traversal found %.17g (%lld, %lld), "
                                 "fcl::distance %.17g (%lld, %lld)\n",
                         k, counted.min_distance, static_cast<long long>(counted.b1), static_cast<long long>(counted.b2),
                         result.min_distance, static_cast<long long>(result.b1), static_cast<long long>(result.b2));
        const fcl::Vector3d &p = result.nearest_points[0], &q = result.nearest_points[1];
        std::printf("%" PRIu64 " %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %lld %lld %d %d\n", k, med, mn,
                    result.min_distance, p[0], p[1], p[2], q[0], q[1], q[2], static_cast<long long>(result.b1),
                    static_cast<long long>(result.b2), node.num_bv_tests,
                    node.num_leaf_tests + 1);
    }
}

// Query 1. FCL 0.7's CollisionRequest has no security margin (no security_margin or
// distance_upper_bound field; the OBBRSS traversal tests plain OBB overlap and triangle
// intersection), so a margin > 0 is answered as plain collision and the row says
// "unsupported". Counts come from FCL's own traversal node, run once untimed, as for query 0.
void run_collide(const Job &job, const std::shared_ptr<Model> &A, const std::shared_ptr<Model> &B)
{
    std::printf("# pose median_ms min_ms collide ia ib bv_tests leaf_tests margin\n");
    const char *margin = job.margin > 0.0 ? "unsupported" : "ok";
    fcl::CollisionObjectd oa(A), ob(B);
    fcl::CollisionRequestd request(1, false); // one contact, no contact geometry
    const fcl::Transform3d identity = fcl::Transform3d::Identity();
    for (uint64_t k = 0; k < job.k; ++k) {
        const fcl::Transform3d tf = pose_transform(&job.poses[12 * k]);
        ob.setTransform(tf);
        ob.computeAABB();
        fcl::CollisionResultd result;
        double med, mn;
        time_runs(job.repetitions, [&] {
            result.clear();
            fcl::collide(&oa, &ob, request, result);
        }, med, mn);

        fcl::detail::MeshCollisionTraversalNodeOBBRSS<double> node;
        fcl::CollisionResultd counted;
        if (!fcl::detail::initialize(node, *A, identity, *B, tf, request, counted))
            throw std::runtime_error("FCL's collision traversal did not initialise");
        node.enable_statistics = true;
        fcl::detail::collide(&node);
        if (counted.isCollision() != result.isCollision())
            std::fprintf(stderr, "ttd_fcl_mesh_bench: pose %" PRIu64 ": the counted traversal disagrees with "
                                 "fcl::collide\n", k);
        long long ia = -1, ib = -1;
        if (result.isCollision()) {
            ia = static_cast<long long>(result.getContact(0).b1);
            ib = static_cast<long long>(result.getContact(0).b2);
        }
        std::printf("%" PRIu64 " %.17g %.17g %d %lld %lld %d %d %s\n", k, med, mn, result.isCollision() ? 1 : 0, ia, ib,
                    node.num_bv_tests, node.num_leaf_tests, margin);
    }
}

struct Hit {
    uint32_t ia, ib;
    double d;
};

struct MarginCounts {
    uint64_t bv_tests = 0, leaf_tests = 0;
};

// Query 2, which FCL lacks: the traversal an FCL user writes on FCL's own trees. A node pair
// is pruned when FCL's OBBRSS distance under the relative transform (the bound its distance
// query uses) exceeds the margin; otherwise the bigger node is split (FCL's rule: split A
// unless it is a leaf, or B is a leaf, or B is bigger), and a leaf pair is kept when FCL's
// triangle distance of A's triangle and B's transformed triangle is <= margin. Explicit stack,
// so that deep trees cannot overflow the call stack.
void margin_pairs(const Model &A, const Model &B, const fcl::Transform3d &tf, double margin, std::vector<Hit> &out,
                  std::vector<std::pair<int, int>> &stack, MarginCounts &c)
{
    out.clear();
    stack.clear();
    c = MarginCounts();
    const fcl::Matrix3d R = tf.linear();
    const fcl::Vector3d T = tf.translation();
    stack.emplace_back(0, 0);
    while (!stack.empty()) {
        const int a = stack.back().first, b = stack.back().second;
        stack.pop_back();
        const fcl::BVNode<fcl::OBBRSSd> &na = A.getBV(a), &nb = B.getBV(b);
        ++c.bv_tests;
        if (fcl::distance(R, T, na.bv, nb.bv) > margin)
            continue;
        const bool la = na.isLeaf(), lb = nb.isLeaf();
        if (la && lb) {
            ++c.leaf_tests;
            const int ta = na.primitiveId(), tb = nb.primitiveId();
            const fcl::Triangle &x = A.tri_indices[ta], &y = B.tri_indices[tb];
            fcl::Vector3d p, q;
            const double d = fcl::detail::TriangleDistance<double>::triDistance(
                A.vertices[x[0]], A.vertices[x[1]], A.vertices[x[2]], B.vertices[y[0]], B.vertices[y[1]],
                B.vertices[y[2]], tf, p, q);
            if (d <= margin)
                out.push_back(Hit{static_cast<uint32_t>(ta), static_cast<uint32_t>(tb), d});
        } else if (lb || (!la && na.bv.size() > nb.bv.size())) {
            stack.emplace_back(na.rightChild(), b); // the left child is visited first
            stack.emplace_back(na.leftChild(), b);
        } else {
            stack.emplace_back(a, nb.rightChild());
            stack.emplace_back(a, nb.leftChild());
        }
    }
}

void write_u64(FILE *f, uint64_t x)
{
    unsigned char b[8];
    for (int i = 0; i < 8; ++i)
        b[i] = static_cast<unsigned char>(x >> (8 * i));
    std::fwrite(b, 1, 8, f);
}

void write_hits(FILE *f, const std::vector<Hit> &hits)
{
    write_u64(f, hits.size());
    for (const Hit &h : hits) {
        uint64_t bits;
        std::memcpy(&bits, &h.d, sizeof bits);
        unsigned char b[16];
        for (int i = 0; i < 4; ++i) {
            b[i] = static_cast<unsigned char>(h.ia >> (8 * i));
            b[4 + i] = static_cast<unsigned char>(h.ib >> (8 * i));
        }
        for (int i = 0; i < 8; ++i)
            b[8 + i] = static_cast<unsigned char>(bits >> (8 * i));
        std::fwrite(b, 1, 16, f);
    }
}

void run_pairs(const Job &job, const std::shared_ptr<Model> &A, const std::shared_ptr<Model> &B, FILE *pairs)
{
    std::printf("# pose median_ms min_ms pairs bv_tests leaf_tests\n");
    if (pairs) {
        std::fwrite(BENCH_FCL_MESH_PAIRS_MAGIC, 1, 8, pairs);
        write_u64(pairs, job.k);
    }
    std::vector<Hit> hits;
    std::vector<std::pair<int, int>> stack;
    for (uint64_t k = 0; k < job.k; ++k) {
        const fcl::Transform3d tf = pose_transform(&job.poses[12 * k]);
        MarginCounts c;
        double med, mn;
        time_runs(job.repetitions, [&] { margin_pairs(*A, *B, tf, job.margin, hits, stack, c); }, med, mn);
        std::printf("%" PRIu64 " %.17g %.17g %zu %" PRIu64 " %" PRIu64 "\n", k, med, mn, hits.size(), c.bv_tests,
                    c.leaf_tests);
        if (pairs) {
            std::sort(hits.begin(), hits.end(),
                      [](const Hit &x, const Hit &y) { return x.ia != y.ia ? x.ia < y.ia : x.ib < y.ib; });
            write_hits(pairs, hits);
        }
    }
}

// FCL's refit (BVHModel::beginUpdateModel / updateSubModel / endUpdateModel, bottom-up): A's
// model to B's vertices and back in turn, so that every timed run moves it.
void run_refit(const Job &job, const std::shared_ptr<Model> &A)
{
    std::printf("# pose median_ms min_ms\n");
    std::vector<fcl::Vector3d> va(job.a.nv), vb(job.b.nv);
    for (uint64_t i = 0; i < job.a.nv; ++i) {
        va[i] = fcl::Vector3d(job.a.v[3 * i], job.a.v[3 * i + 1], job.a.v[3 * i + 2]);
        vb[i] = fcl::Vector3d(job.b.v[3 * i], job.b.v[3 * i + 1], job.b.v[3 * i + 2]);
    }
    bool to_b = true, ok = true;
    double med, mn;
    time_runs(job.repetitions, [&] {
        ok &= A->beginUpdateModel() == fcl::BVH_OK && A->updateSubModel(to_b ? vb : va) == fcl::BVH_OK &&
              A->endUpdateModel(true, true) == fcl::BVH_OK;
        to_b = !to_b;
    }, med, mn);
    if (!ok)
        throw std::runtime_error("FCL's refit (beginUpdateModel / updateSubModel / endUpdateModel) failed");
    std::printf("0 %.17g %.17g\n", med, mn);
}

bool read_file(const char *path, std::vector<unsigned char> &out)
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

const char *query_name(uint32_t q)
{
    return q == BENCH_FCL_MESH_DISTANCE ? "distance" : q == BENCH_FCL_MESH_COLLIDE ? "collide"
         : q == BENCH_FCL_MESH_PAIRS     ? "pairs"
                                         : "refit";
}

} // namespace

int main(int argc, char **argv)
{
    const char *in_path = nullptr, *pairs_path = nullptr;
    bool usage = false;
    for (int i = 1; i < argc && !usage; ++i) {
        if (std::strcmp(argv[i], "--pairs") == 0 && i + 1 < argc && !pairs_path)
            pairs_path = argv[++i];
        else if (!in_path && argv[i][0] != '-')
            in_path = argv[i];
        else
            usage = true;
    }
    if (usage || !in_path) {
        std::fprintf(stderr, "usage: %s IN [--pairs FILE]\n"
                             "Times FCL's mesh queries on a workload file written by `ttd bench`\n"
                             "(format: bench/fcl_mesh_link.h); one line per pose on stdout.\n",
                     argc > 0 ? argv[0] : "ttd_fcl_mesh_bench");
        return 2;
    }
    std::vector<unsigned char> file;
    if (!read_file(in_path, file)) {
        std::fprintf(stderr, "ttd_fcl_mesh_bench: %s: %s\n", in_path, std::strerror(errno));
        return 1;
    }
    try {
        const Job job = read_job(file);
        file.clear();
        file.shrink_to_fit();
        if (pairs_path && job.query != BENCH_FCL_MESH_PAIRS)
            throw BadInput("--pairs is only for query 2 (pairs within a margin)");
        FILE *pairs = nullptr;
        if (pairs_path && !(pairs = std::fopen(pairs_path, "wb"))) {
            std::fprintf(stderr, "ttd_fcl_mesh_bench: %s: %s\n", pairs_path, std::strerror(errno));
            return 1;
        }
        double ms_a = 0.0, ms_b = 0.0;
        const bool refit = job.query == BENCH_FCL_MESH_REFIT; /* B is A moved: not built */
        std::shared_ptr<Model> A = build(job.a, ms_a), B = refit ? nullptr : build(job.b, ms_b);
        std::printf("build_ms %.17g %.17g\n", ms_a, ms_b);
        std::printf("# ttd_fcl_mesh_bench fcl %s query %s repetitions %" PRIu32 " margin %.17g poses %" PRIu64 "\n",
                    FCL_VERSION, query_name(job.query), job.repetitions, job.margin, job.k);
        if (refit)
            run_refit(job, A);
        else if (job.query == BENCH_FCL_MESH_DISTANCE)
            run_distance(job, A, B);
        else if (job.query == BENCH_FCL_MESH_COLLIDE)
            run_collide(job, A, B);
        else
            run_pairs(job, A, B, pairs);
        bool ok = true;
        if (pairs)
            ok = !std::ferror(pairs) && std::fclose(pairs) == 0;
        if (!ok) {
            std::fprintf(stderr, "ttd_fcl_mesh_bench: cannot write %s\n", pairs_path);
            return 1;
        }
        if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
            std::fprintf(stderr, "ttd_fcl_mesh_bench: cannot write the output\n");
            return 1;
        }
    } catch (const BadInput &e) {
        std::fprintf(stderr, "ttd_fcl_mesh_bench: %s: %s\n", in_path, e.what());
        return 1;
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "ttd_fcl_mesh_bench: out of memory\n");
        return 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ttd_fcl_mesh_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
