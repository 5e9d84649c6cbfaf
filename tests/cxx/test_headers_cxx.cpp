// SPDX-License-Identifier: MIT
// The public header and the internal headers that are not precision- or ISA-specific bodies
// compile as C++ (a C++ or CUDA file of a backend, a binding or a test may include them), and
// a C++ program links and calls the library. The build of this file is the first check; main
// is the second (run by CTest as ttd.cxx).
#include "ttd/ttd.h"
#include "ttd/meshfile.h"
#include "ttd/ttd_gpu.h"

#include "core/certified_tol.h"
#include "core/defaults.h"
#include "core/exact_ids.h"
#include "core/kernels.h"
#include "engine/batch.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "engine/runner.h"
#include "scalar/scalar.h"
#include "simd/probe.h"

#define TTD_PRECISION_DOUBLE
#include "core/precision.h"

#include <cstdio>

int main()
{
    // a vertex of T over the face of S at height 2: distance 2 from every row the CPU runs
    const double s[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const double t[9] = {0.25, 0.25, 2, 3, 3, 5, 4, 1, 6};
    real d = -1;  // core/precision.h's type, here double
    int failures = 0;
    for (int i = 1; i < TTD_ISA_COUNT; ++i) {
        const ttd_isa isa = static_cast<ttd_isa>(i);
        if (!ttd_isa_available(isa))
            continue;
        ttd_options opt = ttd_default_options();
        opt.isa = isa;
        ttd_result_d r;
        const ttd_status st = ttd_distance_d(&opt, s, t, &r);
        d = r.distance;
        if (st != TTD_OK || d != 2.0) {
            std::printf("FAIL %s: status %d distance %.17g\n", ttd_isa_name(isa), static_cast<int>(st), d);
            ++failures;
        } else {
            std::printf("ok   %s from C++\n", ttd_isa_name(isa));
        }
    }
    // the GPU library's header and entry points from C++ (a stub without CUDA)
    ttd_gpu_info gi;
    const ttd_gpu_status gs = ttd_gpu_query(&gi);
    std::printf("ok   ttd_gpu_query from C++: %s\n", ttd_gpu_status_string(gs));
    return failures != 0;
}
