/* SPDX-License-Identifier: MIT */
/* `ttd bench`: the benchmark behind the README's run command (docs/benchmark.md). The CLI's
 * main routes `ttd bench ...` here with the arguments after "bench". */
#ifndef TTD_BENCH_BENCH_H
#define TTD_BENCH_BENCH_H

/// Runs the benchmark; argv[0] is "bench". Returns the process exit status.
int ttd_bench_main(int argc, char **argv);

#endif /* TTD_BENCH_BENCH_H */
