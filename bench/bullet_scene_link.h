/* SPDX-License-Identifier: MIT */
/* Bullet's contact manifolds beside ttd's (issue 26): runs the C++ program ttd_bullet_scene_bench
 * (bench/bullet/bullet_scene_bench.cpp, built when cmake/TTDBullet.cmake finds Bullet) on the
 * scene workload that bench/fcl_scene_link.h describes and reads its answers back. Bullet 3.24's
 * btCollisionWorld with btDbvtBroadphase and btGImpactCollisionAlgorithm, one btGImpactMeshShape
 * per mesh shared by its bodies, shape margin M/2 (GImpact reports pairs within the sum of the
 * two margins), one thread. The program's output is described at the top of its source. */
#ifndef TTD_BENCH_BULLET_SCENE_LINK_H
#define TTD_BENCH_BULLET_SCENE_LINK_H

#include "fcl_scene_link.h"

#define BENCH_BULLET_SCENE_PROGRAM "ttd_bullet_scene_bench"
/// Environment variable that names the program (overrides the search next to `ttd`).
#define BENCH_BULLET_SCENE_ENV "TTD_BULLET_SCENE_BENCH"

/// Everything one run returns. Free with bench_bullet_scene_result_free().
typedef struct bench_bullet_scene_result {
    char version[64];                /* "3.24 (double)" */
    bench_fcl_scene_time build, manifold, motion; /* manifold.count: points; .candidates: body pairs */
    bench_fcl_scene_pair *pairs;     /* the body pairs with at least one point, sorted */
    uint32_t *pair_points;           /* their point counts */
    uint64_t *step_pairs, *step_points; /* motion: after each step */
    uint32_t steps;
    char error[512];
} bench_bullet_scene_result;

/// Runs program (found by the caller: bench_fcl_find_program with BENCH_BULLET_SCENE_PROGRAM and
/// BENCH_BULLET_SCENE_ENV) on the job (its repetitions and motion runs as given) and reads the
/// result. Returns BENCH_FCL_SCENE_OK or _ERROR; out->error says why.
int bench_bullet_scene_run(const char *program, const bench_fcl_scene_job *job, bench_bullet_scene_result *out);

/// Frees what a run allocated; safe on a zeroed struct.
void bench_bullet_scene_result_free(bench_bullet_scene_result *r);

#endif /* TTD_BENCH_BULLET_SCENE_LINK_H */
