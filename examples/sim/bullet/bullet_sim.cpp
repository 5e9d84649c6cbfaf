// SPDX-License-Identifier: MIT
// ttd_sim_bullet: ttd_sim's scenarios in Bullet (btGImpactMeshShape on the same meshes, margin
// M/2 per shape, which is what matches ttd's "within M"; Bullet's own world, broad phase and
// solver), measured by the same code as ttd_sim (examples/sim/measure.c: drift, and
// interpenetration through ttd's scene). Before the run it compares the two engines' contacts
// at the scenario's first placement: points per body pair, normals, depths. docs/simulator.md.
//
//   ttd_sim_bullet                        the four stacks, 10 s at rest
//   ttd_sim_bullet --scenario stack-a --seconds 2 --iterations 50 --jig 0
//
// Bullet runs as its users run it: its solver's defaults (10 iterations, --iterations to change;
// warm starting and split impulse on), one step of dt per call; deactivation (sleeping) is
// switched off, as it would freeze the bodies and hide any drift. Friction: each body's
// coefficient is sqrt(0.6), Bullet multiplying the two. Bodies start where their margins meet
// (gaps M), Bullet's resting place; the contacts are compared at ttd_sim's placement.
//
// --check: exit 1 unless Bullet finds, at ttd_sim's placement, every body pair ttd's manifold
// finds (the twin's margins are set as intended); CTest's ttd.sim.bullet.
#include "sim.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

/// Bullet's world over a sim_world's bodies.
struct BulletWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    std::vector<std::unique_ptr<btTriangleMesh>> meshes;
    std::vector<std::unique_ptr<btGImpactMeshShape>> shapes;
    std::vector<std::unique_ptr<btRigidBody>> bodies;

    ~BulletWorld()
    {
        for (auto &b : bodies)
            world.removeRigidBody(b.get());
    }
};

/// Builds Bullet's twin of w: one GImpact shape per sim_shape, one rigid body per body at its
/// pose. false when a shape's inertia is not diagonal in its frame (Bullet takes a diagonal).
bool build(BulletWorld &bw, const sim_run &run, int iterations)
{
    btGImpactCollisionAlgorithm::registerAlgorithm(&bw.dispatcher);
    const sim_world &w = run.world;
    bw.world.setGravity(btVector3(btScalar(w.set.gravity[0]), btScalar(w.set.gravity[1]), btScalar(w.set.gravity[2])));
    bw.world.getSolverInfo().m_numIterations = iterations;
    for (size_t k = 0; k < run.nshape; ++k) {
        const sim_shape &s = run.shape[k];
        auto mesh = std::make_unique<btTriangleMesh>(true, false);
        for (size_t t = 0; t < s.nt; ++t) {
            btVector3 v[3];
            for (int c = 0; c < 3; ++c) {
                const double *p = s.v + 3 * s.t[3 * t + c];
                v[c] = btVector3(btScalar(p[0]), btScalar(p[1]), btScalar(p[2]));
            }
            mesh->addTriangle(v[0], v[1], v[2]);
        }
        auto shape = std::make_unique<btGImpactMeshShape>(mesh.get());
        shape->setMargin(btScalar(0.5 * w.set.margin));
        shape->updateBound();
        bw.meshes.push_back(std::move(mesh));
        bw.shapes.push_back(std::move(shape));
    }
    for (size_t k = 0; k < w.n; ++k) {
        const sim_body &b = w.body[k];
        size_t shape = size_t(b.shape - run.shape);
        const double *I = b.shape->inertia;
        if (std::fabs(I[1]) + std::fabs(I[2]) + std::fabs(I[5]) > 1e-9 * (I[0] + I[4] + I[8]))
            return false;
        btScalar mass = b.is_static ? 0 : btScalar(b.shape->volume);
        btVector3 inertia = b.is_static ? btVector3(0, 0, 0) : btVector3(btScalar(I[0]), btScalar(I[4]), btScalar(I[8]));
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, bw.shapes[shape].get(), inertia);
        info.m_friction = btScalar(std::sqrt(w.set.friction));
        info.m_restitution = 0;
        auto body = std::make_unique<btRigidBody>(info);
        btTransform tr;
        tr.setOrigin(btVector3(btScalar(b.x[0]), btScalar(b.x[1]), btScalar(b.x[2])));
        tr.setRotation(btQuaternion(btScalar(b.q[1]), btScalar(b.q[2]), btScalar(b.q[3]), btScalar(b.q[0])));
        body->setCenterOfMassTransform(tr);
        body->setUserIndex(int(k));
        body->setActivationState(DISABLE_DEACTIVATION);
        bw.world.addRigidBody(body.get());
        bw.bodies.push_back(std::move(body));
    }
    return true;
}

/// One Bullet step, then its poses copied into the sim_world (and ttd's scene) for measuring.
int bullet_step(void *ctx, sim_world *w)
{
    BulletWorld &bw = *static_cast<BulletWorld *>(ctx);
    bw.world.stepSimulation(btScalar(w->set.dt), 1, btScalar(w->set.dt));
    for (size_t k = 0; k < w->n; ++k) {
        sim_body &b = w->body[k];
        if (b.is_static)
            continue;
        const btTransform &tr = bw.bodies[k]->getCenterOfMassTransform();
        btQuaternion q = tr.getRotation();
        for (int i = 0; i < 3; ++i)
            b.x[i] = double(tr.getOrigin()[i]);
        b.q[0] = double(q.w());
        b.q[1] = double(q.x());
        b.q[2] = double(q.y());
        b.q[3] = double(q.z());
        const btVector3 &v = bw.bodies[k]->getLinearVelocity(), &om = bw.bodies[k]->getAngularVelocity();
        for (int i = 0; i < 3; ++i) {
            b.v[i] = double(v[i]);
            b.w[i] = double(om[i]);
        }
    }
    ++w->steps;
    return sim_world_sync(w);
}

/// One contact point, either engine's: bodies (a < b), normal, depth (M - separation).
struct Point {
    uint32_t a, b;
    double normal[3], depth;
};

/// Per-engine summary of a placement's contacts.
struct Summary {
    size_t pairs = 0, points = 0, at_level = 0, tilted = 0;
    double max_tilt = 0, depth_lo = HUGE_VAL, depth_hi = -HUGE_VAL;
};

/// pts grouped by pair (a, b): points per pair, points within 1e-3 of their pair's deepest (those
/// that hold the weight at rest), the largest tilt of a normal from vertical, pairs with a
/// normal tilted more than 10 degrees, and the depths' range.
Summary summarise(std::vector<Point> pts)
{
    std::stable_sort(pts.begin(), pts.end(), [](const Point &x, const Point &y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    Summary s;
    for (size_t i = 0; i < pts.size();) {
        size_t j = i;
        double deepest = -HUGE_VAL, tilt = 0;
        for (; j < pts.size() && pts[j].a == pts[i].a && pts[j].b == pts[i].b; ++j)
            deepest = std::max(deepest, pts[j].depth);
        for (size_t k = i; k < j; ++k) {
            tilt = std::max(tilt, std::acos(std::min(1.0, std::fabs(pts[k].normal[2]))) * 57.29577951308232);
            s.at_level += pts[k].depth > deepest - 1e-3;
            s.depth_lo = std::min(s.depth_lo, pts[k].depth);
            s.depth_hi = std::max(s.depth_hi, pts[k].depth);
        }
        s.max_tilt = std::max(s.max_tilt, tilt);
        s.tilted += tilt > 10;
        s.points += j - i;
        ++s.pairs;
        i = j;
    }
    return s;
}

void print_summary(const char *engine, const Summary &s)
{
    double pairs = double(std::max<size_t>(s.pairs, 1));
    std::printf("  %-7s %6zu %11.2f %13.2f %12.1f %12zu %9.4f..%.4f\n", engine, s.pairs, double(s.points) / pairs,
                double(s.at_level) / pairs, s.max_tilt, s.tilted, s.depth_lo, s.depth_hi);
}

/// Both engines' contacts at the current placement, summarised (and returned).
int compare_contacts(BulletWorld &bw, sim_world *w, Summary *ttd_summary, Summary *bullet_summary)
{
    std::vector<Point> ttd_pts, bullet_pts;
    ttd_status st = ttd_scene_manifold_d(&w->opt, w->scene, w->set.margin, w->set.max_points, &w->manifold);
    if (st != TTD_OK) {
        std::fprintf(stderr, "ttd_sim_bullet: ttd_scene_manifold_d: %s\n", ttd_status_string(st));
        return -1;
    }
    const ttd_scene_point_d *p = static_cast<const ttd_scene_point_d *>(w->manifold.data);
    for (size_t k = 0; k < w->manifold.count; ++k)
        ttd_pts.push_back({p[k].i, p[k].j, {p[k].normal[0], p[k].normal[1], p[k].normal[2]}, p[k].depth});
    bw.world.performDiscreteCollisionDetection();
    for (int m = 0; m < bw.dispatcher.getNumManifolds(); ++m) {
        const btPersistentManifold *pm = bw.dispatcher.getManifoldByIndexInternal(m);
        uint32_t a = uint32_t(pm->getBody0()->getUserIndex()), b = uint32_t(pm->getBody1()->getUserIndex());
        for (int c = 0; c < pm->getNumContacts(); ++c) {
            const btManifoldPoint &cp = pm->getContactPoint(c);
            // normalWorldOnB points from body 1 to body 0; ours from the smaller id to the larger
            double sign = a < b ? -1 : 1;
            Point q{std::min(a, b), std::max(a, b),
                    {sign * double(cp.m_normalWorldOnB[0]), sign * double(cp.m_normalWorldOnB[1]),
                     sign * double(cp.m_normalWorldOnB[2])},
                    -double(cp.getDistance())};
            bullet_pts.push_back(q);
        }
    }
    std::printf("  %-7s %6s %11s %13s %12s %12s %s\n", "engine", "pairs", "points/pair", "at level/pair", "max tilt deg",
                "pairs >10deg", "depths");
    *ttd_summary = summarise(ttd_pts);
    *bullet_summary = summarise(bullet_pts);
    print_summary("ttd", *ttd_summary);
    print_summary("bullet", *bullet_summary);
    return 0;
}

double number(const char *text)
{
    char *end;
    double x = std::strtod(text, &end);
    return (end != text && *end == 0) ? x : double(NAN);
}

} // namespace

int main(int argc, char **argv)
{
    std::vector<std::string> names;
    double seconds = 10, settle = -1, jig = 1;
    int iterations = 10;
    bool check = false;
    for (int k = 1; k < argc; ++k) {
        std::string a = argv[k];
        if (a == "--check") {
            check = true;
            continue;
        }
        if (a == "--help" || a == "-h" || k + 1 == argc) {
            std::fprintf(a == "--help" || a == "-h" ? stdout : stderr,
                         "usage: ttd_sim_bullet [--scenario NAME]... [--seconds S] [--settle S] [--jig S] [--iterations N] [--check]\n");
            return a == "--help" || a == "-h" ? 0 : 2;
        }
        const char *v = argv[++k];
        double x = number(v);
        if (a == "--scenario") {
            bool known = false;
            for (int i = 0; sim_scenarios[i]; ++i)
                known = known || !std::strcmp(sim_scenarios[i], v);
            if (!known) {
                std::fprintf(stderr, "ttd_sim_bullet: unknown scenario %s\n", v);
                return 2;
            }
            names.push_back(v);
        } else if (a == "--seconds" && x >= 0) {
            seconds = x;
        } else if (a == "--settle" && x >= 0) {
            settle = x;
        } else if (a == "--jig" && std::isfinite(x)) {
            jig = x;
        } else if (a == "--iterations" && x >= 1 && x <= 1000 && x == std::floor(x)) {
            iterations = int(x);
        } else {
            std::fprintf(stderr, "ttd_sim_bullet: bad option or value: %s %s\n", a.c_str(), v);
            return 2;
        }
    }
    if (names.empty())
        names = {"stack-a", "stack-b", "stack-fan", "stack-mixed"};
    sim_settings set = sim_default_settings();
    set.jig = jig;
    std::printf("ttd_sim_bullet (Bullet %d, %s precision, ttd %s): dt %.6g s, margin M %g (GImpact margin M/2 per shape), "
                "friction %g, %d solver iterations, sleeping off, %g s at rest after each scenario settles\n",
                btGetVersion(), sizeof(btScalar) == 8 ? "double" : "single", ttd_version_string(), set.dt, set.margin,
                set.friction, iterations, seconds);
    for (const std::string &name : names) {
        // the contacts at ttd_sim's placement (bodies at its rest gap)
        sim_run run;
        if (sim_run_build(&run, name.c_str(), &set) != 0) {
            std::fprintf(stderr, "ttd_sim_bullet: could not build %s\n", name.c_str());
            return 1;
        }
        int rc = 0;
        {
            BulletWorld bw;
            rc = build(bw, run, iterations) ? 0 : 1;
            if (rc == 0) {
                std::printf("%s: contacts at ttd_sim's first placement (gaps %g; ttd: manifold, K = %zu; Bullet: "
                            "GImpact's manifolds)\n",
                            name.c_str(), set.rest_gap, set.max_points);
                Summary ts, bs;
                rc = compare_contacts(bw, &run.world, &ts, &bs);
                if (rc == 0 && check && bs.pairs != ts.pairs) {
                    std::fprintf(stderr, "ttd_sim_bullet: %s: Bullet found %zu body pairs, ttd %zu\n", name.c_str(),
                                 bs.pairs, ts.pairs);
                    rc = 1;
                }
            }
        }
        sim_run_free(&run);
        // the run: Bullet's bodies rest where their margins (M/2 each) meet, so they start there
        sim_settings at_margin = set;
        at_margin.rest_gap = set.margin;
        if (rc == 0 && sim_run_build(&run, name.c_str(), &at_margin) != 0)
            rc = 1;
        if (rc == 0) {
            BulletWorld bw;
            sim_figures f;
            rc = build(bw, run, iterations) ? 0 : 1;
            if (rc == 0)
                rc = sim_run_window(&run.world, settle >= 0 ? settle : run.settle, seconds, bullet_step, &bw, &f);
            if (rc == 0)
                std::printf("%s in Bullet (placed at gaps %g): drift %.2e of a body's size (centroids %.2e), "
                            "interpenetration %.2e of the margin, kinetic energy %.2e at the end, most pairs touching "
                            "at a sample %zu\n",
                            name.c_str(), at_margin.rest_gap, f.drift, f.centre_drift, f.overlap, f.kinetic, f.touching);
            sim_run_free(&run);
        }
        if (rc != 0) {
            std::fprintf(stderr, "ttd_sim_bullet: %s failed\n", name.c_str());
            return 1;
        }
    }
    return 0;
}
