/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the mesh queries on cases drawn from the input bytes by the mesh fuzzer's
 * core (tests/meshfuzz/): the first byte picks the family, the next ones the precision, the
 * triangle kinds, counts, coordinates and poses; past the input's end the draws continue from a
 * stream seeded by its hash. Every query, on the scalar row and the automatic choice with 1 and
 * 2 threads, is checked against the brute force over all triangle pairs (docs/testing.md); any failure is
 * printed and aborts, so libFuzzer keeps the input. Meshes stay small (at most 24 triangles,
 * grids of up to 32) so that the sanitizers' run does many cases. Build and run:
 * scripts/fuzz.sh; a saved input reruns with `fuzz_mesh FILE`, or on every instruction set
 * without the sanitizers with `test_mesh_fuzz --input FILE`. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "meshfuzz/meshfuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    mf_run run = {0};
    run.small = 1;
    run.one_isa = 1; /* the scalar row and the automatic choice: the sanitizers make every call slow */
    run.dump_failures = 1; /* failures come with the case's meshes and poses */
    run.out = stderr;
    mf_src src;
    mf_src_bytes(&src, data, size);
    if (mf_run_case(&run, &src, -1, 0, 0) != 0) {
        mf_summary(&run, stderr);
        abort();
    }
    return 0;
}
