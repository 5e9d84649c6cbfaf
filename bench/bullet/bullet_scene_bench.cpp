// SPDX-License-Identifier: MIT
// ttd_bullet_scene_bench: Bullet 3.24's mesh-mesh contact manifolds over many bodies (GImpact),
// timed on a scene written by `ttd bench` (bench/fcl_scene_link.c writes the workload, the format
// is in bench/fcl_scene_link.h), so that Bullet and ttd answer the same bodies and poses in one
// run (issue 26).
//
// Usage: ttd_bullet_scene_bench IN
//
// What a Bullet user does for contacts between triangle meshes (docs/anchors.md, "Scenes"): a
// btCollisionWorld with btDbvtBroadphase and btGImpactCollisionAlgorithm registered, one
// btGImpactMeshShape per mesh, shared by every body of that mesh, each body a btCollisionObject.
// GImpact reports a triangle pair when a clipped point lies within margin_a + margin_b of a face
// plane, so each shape's margin is M/2 to match "within M". A query is
// performDiscreteCollisionDetection() (every body's box, the broad phase, the narrow phase); the
// manifolds (at most 4 points each, Bullet's cap) are then read from the dispatcher. Built
// against the Bullet that cmake/TTDBullet.cmake finds (Debian's float build); the first output
// line says which precision.
//
// Output (text on stdout, numbers %.17g, one record a line, the keyword first):
//   # ttd_bullet_scene_bench bullet VERSION precision P bodies N meshes K margin M repetitions R steps S
//   build MED_MS MIN_MS                     shapes (their trees) + objects + the world
//   manifold MED_MS MIN_MS POINTS PAIRS     one query: PAIRS body pairs with at least one point
//   mpair I J NPOINTS                       PAIRS lines, I < J, sorted
//   motion MED_MS MIN_MS STEPS              per step: every body's transform set, then the query
//   step K PAIRS POINTS                     STEPS lines: the answer after step K (the last run)
#include "fcl_scene_link.h"
#include "scene_job.hpp"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <LinearMath/btScalar.h>
#include <btBulletCollisionCommon.h>

#include <memory>
#include <utility>
#include <vector>

namespace {

using namespace scene_job;

// One mesh as Bullet reads it: its arrays (kept alive with the shape) and the shape.
struct Shape {
    std::vector<btScalar> v;
    std::vector<int> t;
    std::unique_ptr<btTriangleIndexVertexArray> array;
    std::unique_ptr<btGImpactMeshShape> shape;
};

struct World {
    std::unique_ptr<btDefaultCollisionConfiguration> config;
    std::unique_ptr<btCollisionDispatcher> dispatcher;
    std::unique_ptr<btDbvtBroadphase> broadphase;
    std::unique_ptr<btCollisionWorld> world;
    std::vector<Shape> shapes;
    std::vector<std::unique_ptr<btCollisionObject>> bodies;
    ~World()
    {   // the objects leave the world before it goes
        for (auto &b : bodies)
            if (world && b)
                world->removeCollisionObject(b.get());
        bodies.clear();
        world.reset();
    }
};

btTransform transform_of(const double *m)
{
    btScalar x[12];
    for (int i = 0; i < 12; ++i)
        x[i] = static_cast<btScalar>(m[i]);
    const btMatrix3x3 R(x[0], x[1], x[2], x[4], x[5], x[6], x[8], x[9], x[10]);
    return btTransform(R, btVector3(x[3], x[7], x[11]));
}

void build_world(const Job &job, World &w)
{
    w.config = std::make_unique<btDefaultCollisionConfiguration>();
    w.dispatcher = std::make_unique<btCollisionDispatcher>(w.config.get());
    btGImpactCollisionAlgorithm::registerAlgorithm(w.dispatcher.get());
    w.broadphase = std::make_unique<btDbvtBroadphase>();
    w.world = std::make_unique<btCollisionWorld>(w.dispatcher.get(), w.broadphase.get(), w.config.get());
    w.shapes.resize(job.meshes.size());
    for (size_t m = 0; m < job.meshes.size(); ++m) {
        const Mesh &g = job.meshes[m];
        Shape &s = w.shapes[m];
        s.v.assign(g.v.begin(), g.v.end());
        s.t.assign(g.t.begin(), g.t.end());
        s.array = std::make_unique<btTriangleIndexVertexArray>(static_cast<int>(g.nt), s.t.data(),
                                                               static_cast<int>(3 * sizeof(int)),
                                                               static_cast<int>(g.nv), s.v.data(),
                                                               static_cast<int>(3 * sizeof(btScalar)));
        s.shape = std::make_unique<btGImpactMeshShape>(s.array.get());
        s.shape->setMargin(static_cast<btScalar>(0.5 * job.margin)); // margin_a + margin_b = M
        s.shape->updateBound();                         // builds the shape's tree
    }
    w.bodies.resize(job.n);
    for (uint64_t b = 0; b < job.n; ++b) {
        w.bodies[b] = std::make_unique<btCollisionObject>();
        btCollisionObject *o = w.bodies[b].get();
        o->setCollisionShape(w.shapes[job.body_mesh[b]].shape.get());
        o->setWorldTransform(transform_of(&job.poses[12 * b]));
        o->setUserIndex(static_cast<int>(b));
        w.world->addCollisionObject(o);
    }
}

void move_all(World &w, const double *poses)
{
    for (size_t b = 0; b < w.bodies.size(); ++b)
        w.bodies[b]->setWorldTransform(transform_of(&poses[12 * b]));
}

// The manifolds of the last query: body pairs (i < j) with their point counts, sorted.
struct Answer {
    std::vector<std::pair<std::pair<uint32_t, uint32_t>, int>> pairs;
    uint64_t points = 0;
};

Answer read_manifolds(const World &w)
{
    Answer a;
    btDispatcher *d = w.world->getDispatcher();
    for (int k = 0; k < d->getNumManifolds(); ++k) {
        const btPersistentManifold *m = d->getManifoldByIndexInternal(k);
        const int n = m->getNumContacts();
        if (n == 0)
            continue;
        uint32_t i = static_cast<uint32_t>(m->getBody0()->getUserIndex());
        uint32_t j = static_cast<uint32_t>(m->getBody1()->getUserIndex());
        if (i > j)
            std::swap(i, j);
        a.pairs.push_back({{i, j}, n});
        a.points += static_cast<uint64_t>(n);
    }
    std::sort(a.pairs.begin(), a.pairs.end());
    return a;
}

void run(const Job &job)
{
    std::printf("# ttd_bullet_scene_bench bullet %d precision %s bodies %" PRIu64 " meshes %zu margin %.17g "
                "repetitions %" PRIu32 " steps %" PRIu32 "\n",
                btGetVersion(), sizeof(btScalar) == 8 ? "double" : "float", job.n, job.meshes.size(), job.margin,
                job.repetitions, job.steps);
    double med, mn;
    {   // the build, timed up to 3 times unless the first is long (the trees take seconds)
        std::vector<double> t;
        for (uint32_t r = 0; r < std::min<uint32_t>(job.repetitions, 3); ++r) {
            World w;
            double a = now_ms();
            build_world(job, w);
            t.push_back(now_ms() - a);
            if (t[0] > 2000.0)
                break;
        }
        std::printf("build %.17g %.17g\n", median_of(t), *std::min_element(t.begin(), t.end()));
    }
    World w;
    build_world(job, w);
    w.world->performDiscreteCollisionDetection(); // warm-up: the pair cache and the manifolds
    time_runs(job.repetitions, [&] { w.world->performDiscreteCollisionDetection(); }, med, mn);
    const Answer a = read_manifolds(w);
    std::printf("manifold %.17g %.17g %" PRIu64 " %zu\n", med, mn, a.points, a.pairs.size());
    for (const auto &p : a.pairs)
        std::printf("mpair %" PRIu32 " %" PRIu32 " %d\n", p.first.first, p.first.second, p.second);

    if (job.motion_runs && job.steps) {
        std::vector<double> total(job.motion_runs);
        std::vector<Answer> steps(job.steps);
        for (uint32_t r = 0; r < job.motion_runs; ++r) {
            move_all(w, job.poses.data()); // back to the start, untimed
            w.world->performDiscreteCollisionDetection();
            double t_all = 0.0;
            for (uint32_t k = 0; k < job.steps; ++k) {
                double s = now_ms();
                move_all(w, &job.motion[12 * job.n * k]);
                w.world->performDiscreteCollisionDetection();
                t_all += now_ms() - s;
                steps[k] = read_manifolds(w);
            }
            total[r] = t_all / job.steps;
        }
        std::printf("motion %.17g %.17g %" PRIu32 "\n", median_of(total), *std::min_element(total.begin(), total.end()),
                    job.steps);
        for (uint32_t k = 0; k < job.steps; ++k)
            std::printf("step %" PRIu32 " %zu %" PRIu64 "\n", k, steps[k].pairs.size(), steps[k].points);
    }
}

} // namespace

int main(int argc, char **argv)
{
    return job_main(argc, argv, "ttd_bullet_scene_bench", "Times Bullet's GImpact contact manifolds", run);
}
