// SPDX-License-Identifier: MIT
// ttd_fcl_scene_bench: FCL 0.7's broad phase over many bodies, timed on a scene written by
// `ttd bench` (bench/fcl_scene_link.c), so that FCL and ttd answer the same bodies and poses in
// one run (issue 17, item 5).
//
// Usage: ttd_fcl_scene_bench IN
//
// The input and output formats are in bench/fcl_scene_link.h. What FCL users do today
// (docs/anchors.md, "Scenes"): one BVHModel<OBBRSS<double>> per mesh, shared by every body of
// that mesh, each body a CollisionObject, DynamicAABBTreeCollisionManager<double> as the broad
// phase, one thread. FCL 0.7 has no margin and no contacts, so the queries at a margin are what a
// user writes over FCL's trees:
//   - the broad phase with every object's AABB inflated by margin/2 per side (two boxes within
//     the margin of each other then overlap), set after computeAABB() and passed to the manager
//     by update();
//   - collide at the margin: per candidate, a traversal of the two OBBRSS trees that prunes a node
//     pair whose OBBRSS distance exceeds the margin and stops at the first triangle pair within it
//     (docs/anchors.md's "early-exit traversal", 12-35x faster than fcl::distance per candidate);
//   - contacts: per candidate, the same traversal without the early exit, every triangle pair
//     within the margin (the mesh benchmark's margin traversal, bench/fcl/fcl_mesh_bench.cpp).
// collide at 0 is fcl::collide per candidate (one contact); distance is manager->distance with a
// callback that runs fcl::distance (exact, nearest points) per candidate and keeps the closest
// pair with its bodies (not FCL's DefaultDistanceFunction, whose result is shared across pairs).
#include "fcl_scene_link.h"
#include "scene_job.hpp"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/config.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>
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

using namespace scene_job;

using Model = fcl::BVHModel<fcl::OBBRSSd>;

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

fcl::Transform3d pose_transform(const double *m)
{
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    fcl::Matrix3d R;
    R << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
    tf.linear() = R;
    tf.translation() = fcl::Vector3d(m[3], m[7], m[11]);
    return tf;
}



// A CollisionObject whose box the manager sees may be inflated (FCL 0.7 has no margin of its own;
// `aabb` is the protected member getAABB() returns).
struct Body : fcl::CollisionObjectd {
    Body(const std::shared_ptr<fcl::CollisionGeometryd> &g, uint32_t id) : fcl::CollisionObjectd(g), id(id) {}
    void place(const double *m, double inflate)
    {
        setTransform(pose_transform(m));
        computeAABB();
        if (inflate > 0.0) {
            aabb.min_ -= fcl::Vector3d::Constant(inflate);
            aabb.max_ += fcl::Vector3d::Constant(inflate);
        }
    }
    uint32_t id;
};

struct Scene {
    std::vector<std::shared_ptr<Model>> models;
    std::vector<std::unique_ptr<Body>> bodies;
    std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd> manager;
};

void build_scene(const Job &job, Scene &s)
{
    s = Scene();
    for (const Mesh &m : job.meshes)
        s.models.push_back(build_once(m));
    std::vector<fcl::CollisionObjectd *> objs;
    for (uint64_t b = 0; b < job.n; ++b) {
        s.bodies.emplace_back(new Body(s.models[job.body_mesh[b]], static_cast<uint32_t>(b)));
        s.bodies.back()->place(&job.poses[12 * b], 0.0);
        objs.push_back(s.bodies.back().get());
    }
    s.manager.reset(new fcl::DynamicAABBTreeCollisionManagerd());
    s.manager->registerObjects(objs);
    s.manager->setup();
}

// Places every body at poses (12 each), boxes inflated by inflate, and updates the manager.
void move_all(Scene &s, const double *poses, double inflate)
{
    for (size_t b = 0; b < s.bodies.size(); ++b)
        s.bodies[b]->place(&poses[12 * b], inflate);
    s.manager->update();
}

fcl::Transform3d relative(const fcl::CollisionObjectd *a, const fcl::CollisionObjectd *b)
{
    return a->getTransform().inverse(Eigen::Isometry) * b->getTransform();
}

// The margin traversal of bench/fcl/fcl_mesh_bench.cpp (margin_pairs), with an early exit at the
// first triangle pair within the margin when first_only. Returns the pairs found.
uint64_t margin_traversal(const Model &A, const Model &B, const fcl::Transform3d &tf, double margin, bool first_only,
                          std::vector<std::pair<int, int>> &stack)
{
    uint64_t found = 0;
    stack.clear();
    const fcl::Matrix3d R = tf.linear();
    const fcl::Vector3d T = tf.translation();
    stack.emplace_back(0, 0);
    while (!stack.empty()) {
        const int a = stack.back().first, b = stack.back().second;
        stack.pop_back();
        const fcl::BVNode<fcl::OBBRSSd> &na = A.getBV(a), &nb = B.getBV(b);
        if (fcl::distance(R, T, na.bv, nb.bv) > margin)
            continue;
        const bool la = na.isLeaf(), lb = nb.isLeaf();
        if (la && lb) {
            const fcl::Triangle &x = A.tri_indices[na.primitiveId()], &y = B.tri_indices[nb.primitiveId()];
            fcl::Vector3d p, q;
            const double d = fcl::detail::TriangleDistance<double>::triDistance(
                A.vertices[x[0]], A.vertices[x[1]], A.vertices[x[2]], B.vertices[y[0]], B.vertices[y[1]],
                B.vertices[y[2]], tf, p, q);
            if (d <= margin) {
                ++found;
                if (first_only)
                    return found;
            }
        } else if (lb || (!la && na.bv.size() > nb.bv.size())) {
            stack.emplace_back(na.rightChild(), b);
            stack.emplace_back(na.leftChild(), b);
        } else {
            stack.emplace_back(a, nb.rightChild());
            stack.emplace_back(a, nb.leftChild());
        }
    }
    return found;
}

const Model &model_of(const fcl::CollisionObjectd *o)
{
    return *static_cast<const Model *>(o->collisionGeometry().get());
}

struct CollideData {
    double margin = 0.0;  // 0: fcl::collide; > 0: the early-exit margin traversal
    bool all_pairs = false; // contacts: every triangle pair within the margin
    uint64_t candidates = 0, triangle_pairs = 0;
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    std::vector<std::pair<int, int>> stack;
};

bool collide_cb(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *p)
{
    CollideData &c = *static_cast<CollideData *>(p);
    ++c.candidates;
    uint32_t i = static_cast<Body *>(o1)->id, j = static_cast<Body *>(o2)->id;
    if (i > j)
        std::swap(i, j), std::swap(o1, o2);
    bool hit;
    if (c.margin == 0.0) {
        fcl::CollisionRequestd request(1, false);
        fcl::CollisionResultd result;
        fcl::collide(o1, o2, request, result);
        hit = result.isCollision();
    } else {
        uint64_t n = margin_traversal(model_of(o1), model_of(o2), relative(o1, o2), c.margin, !c.all_pairs, c.stack);
        c.triangle_pairs += n;
        hit = n > 0;
    }
    if (hit)
        c.pairs.emplace_back(i, j);
    return false; // go on
}

struct DistanceData {
    uint64_t calls = 0;
    double d = INFINITY;
    uint32_t i = UINT32_MAX, j = UINT32_MAX;
    int64_t ia = -1, ib = -1;
};

bool distance_cb(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *p, double &dist)
{
    DistanceData &c = *static_cast<DistanceData *>(p);
    ++c.calls;
    uint32_t i = static_cast<Body *>(o1)->id, j = static_cast<Body *>(o2)->id;
    if (i > j)
        std::swap(i, j), std::swap(o1, o2);
    fcl::DistanceRequestd request(true);
    fcl::DistanceResultd result;
    fcl::distance(o1, o2, request, result);
    double d = std::max(result.min_distance, 0.0);
    if (d < c.d || (d == c.d && (i < c.i || (i == c.i && j < c.j)))) {
        c.d = d;
        c.i = i;
        c.j = j;
        c.ia = result.b1;
        c.ib = result.b2;
    }
    dist = c.d;
    return c.d <= 0.0; // a touching pair: nothing can be closer
}


void print_pairs(std::vector<std::pair<uint32_t, uint32_t>> pairs)
{
    std::sort(pairs.begin(), pairs.end());
    for (const auto &q : pairs)
        std::printf("pair %" PRIu32 " %" PRIu32 "\n", q.first, q.second);
}

void run(const Job &job)
{
    std::printf("# ttd_fcl_scene_bench fcl %s bodies %" PRIu64 " meshes %zu margin %.17g repetitions %" PRIu32
                " steps %" PRIu32 "\n",
                FCL_VERSION, job.n, job.meshes.size(), job.margin, job.repetitions, job.steps);
    Scene s;
    double med, mn;
    {   // the build, timed up to 3 times (the first faults pages in)
        std::vector<double> t;
        for (uint32_t r = 0; r < std::min<uint32_t>(job.repetitions, 3) + 1; ++r) {
            double a = now_ms();
            build_scene(job, s);
            t.push_back(now_ms() - a);
            if (r == 0 && t[0] > 2000.0)
                break;
        }
        if (t.size() > 1)
            t.erase(t.begin());
        std::printf("build %.17g %.17g\n", median_of(t), *std::min_element(t.begin(), t.end()));
    }
    const double half = 0.5 * job.margin;
    CollideData c0, cm, cc;
    time_runs(job.repetitions, [&] { c0 = CollideData(); s.manager->collide(&c0, collide_cb); }, med, mn);
    std::printf("collide0 %.17g %.17g %zu %" PRIu64 "\n", med, mn, c0.pairs.size(), c0.candidates);
    print_pairs(c0.pairs);

    DistanceData dd;
    time_runs(job.repetitions, [&] { dd = DistanceData(); s.manager->distance(&dd, distance_cb); }, med, mn);
    std::printf("distance %.17g %.17g %.17g %lld %lld %lld %lld %" PRIu64 "\n", med, mn, dd.d,
                dd.i == UINT32_MAX ? -1LL : static_cast<long long>(dd.i),
                dd.j == UINT32_MAX ? -1LL : static_cast<long long>(dd.j), static_cast<long long>(dd.ia),
                static_cast<long long>(dd.ib), dd.calls);

    move_all(s, job.poses.data(), half);
    time_runs(job.repetitions, [&] {
        cm = CollideData();
        cm.margin = job.margin;
        s.manager->collide(&cm, collide_cb);
    }, med, mn);
    std::printf("collidem %.17g %.17g %zu %" PRIu64 "\n", med, mn, cm.pairs.size(), cm.candidates);
    print_pairs(cm.pairs);

    time_runs(job.repetitions, [&] {
        cc = CollideData();
        cc.margin = job.margin;
        cc.all_pairs = true;
        s.manager->collide(&cc, collide_cb);
    }, med, mn);
    std::printf("contacts %.17g %.17g %" PRIu64 " %zu %" PRIu64 "\n", med, mn, cc.triangle_pairs, cc.pairs.size(),
                cc.candidates);

    if (job.motion_runs && job.steps) {
        std::vector<double> total(job.motion_runs), update(job.motion_runs);
        std::vector<uint64_t> counts(job.steps);
        for (uint32_t r = 0; r < job.motion_runs; ++r) {
            move_all(s, job.poses.data(), half); // back to the start, untimed
            double t_all = 0.0, t_up = 0.0;
            for (uint32_t k = 0; k < job.steps; ++k) {
                const double *poses = &job.motion[12 * job.n * k];
                double a = now_ms();
                move_all(s, poses, half);
                double b = now_ms();
                CollideData cs;
                cs.margin = job.margin;
                s.manager->collide(&cs, collide_cb);
                double e = now_ms();
                t_up += b - a;
                t_all += e - a;
                counts[k] = cs.pairs.size();
            }
            total[r] = t_all / job.steps;
            update[r] = t_up / job.steps;
        }
        double m = median_of(total);
        size_t at = 0;
        for (size_t r = 0; r < total.size(); ++r)
            if (std::fabs(total[r] - m) < std::fabs(total[at] - m))
                at = r;
        std::printf("motion %.17g %.17g %.17g %" PRIu32 "\n", m, *std::min_element(total.begin(), total.end()),
                    update[at], job.steps);
        for (uint32_t k = 0; k < job.steps; ++k)
            std::printf("step %" PRIu32 " %" PRIu64 "\n", k, counts[k]);
    }
}


} // namespace

int main(int argc, char **argv)
{
    return job_main(argc, argv, "ttd_fcl_scene_bench", "Times FCL's broad phase and queries", run);
}
