/* SPDX-License-Identifier: MIT */
/* `ttd bench points` (issue 24; docs/points.md, docs/benchmark.md): the point queries (closest
 * point in double and float, signed distance) timed beside Embree's rtcPointQuery (a double
 * closest-point callback), CGAL's AABB_tree and Open3D's RaycastingScene on the same meshes and
 * points, one thread and all cores, with the targets printed next to the measured ratios.
 * The other libraries run in their own programs (bench/points/), found next to ttd. */
#ifndef TTD_BENCH_POINTS_BENCH_H
#define TTD_BENCH_POINTS_BENCH_H

/// `ttd bench points [options]` (argv[0] is "points"); returns the exit status.
int bench_points_main(int argc, char **argv);

#endif /* TTD_BENCH_POINTS_BENCH_H */
