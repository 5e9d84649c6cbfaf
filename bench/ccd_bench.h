/* SPDX-License-Identifier: MIT */
/* `ttd bench ccd` (issue 33; docs/ccd.md, section 6): continuous collision on the CCD benchmark's
 * sample queries and generated families, beside a naive floating-point cubic. */
#ifndef TTD_BENCH_CCD_BENCH_H
#define TTD_BENCH_CCD_BENCH_H

/// `ttd bench ccd [options]` (argv[0] is "ccd"); returns the exit status.
int bench_ccd_main(int argc, char **argv);

#endif /* TTD_BENCH_CCD_BENCH_H */
