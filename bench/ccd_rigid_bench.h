/* SPDX-License-Identifier: MIT */
/* `ttd bench ccd --rigid` (issue 34; docs/ccd.md section 13): rigid bodies between two poses,
 * ttd's conservative advancement beside FCL 0.7's, and a scene's step. */
#ifndef TTD_BENCH_CCD_RIGID_BENCH_H
#define TTD_BENCH_CCD_RIGID_BENCH_H

/// `ttd bench ccd --rigid [options]` (argv[0] is "ccd"); returns the exit status.
int bench_ccd_rigid_main(int argc, char **argv);

#endif /* TTD_BENCH_CCD_RIGID_BENCH_H */
