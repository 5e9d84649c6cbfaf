/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the point queries on cases drawn from the input bytes by the point fuzzer's
 * core (tests/pointfuzz/): a small hostile mesh, points on and near it, a bound and a pose; the
 * closest point against the brute force bit for bit, rows and threads against each other, signed
 * distances against it (docs/testing.md). A failure is printed with its case and aborts, so
 * libFuzzer keeps the input; rerun it with `test_points_fuzz --input FILE`. scripts/fuzz.sh. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "pointfuzz/pointfuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pf_src src;
    pf_src_init(&src, data, size, 0);
    if (pf_run_case(&src, stderr, 1, NULL) != 0)
        abort();
    return 0;
}
