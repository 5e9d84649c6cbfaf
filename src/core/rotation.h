/* SPDX-License-Identifier: MIT */
/* How far a 3x3 matrix (row-major) is from a rotation, one source for every check of a pose:
 * the C entries' pose check (api/mesh_api.c), its device copy (gpu/gpu_walk_impl.h) and the
 * rigid motion's projection onto a rotation (meshccd/rigid_motion.c). The device must refuse
 * exactly the poses the CPU refuses, so both run these operations in this order. */
#ifndef TTD_CORE_ROTATION_H
#define TTD_CORE_ROTATION_H

#include "core/device_fn.h"

/* max over entries of |R^T R - I| (NaN entries are skipped by the compare, so check finiteness
 * first). */
TTDW_FN double ttd_rotation_defect(const double r[9])
{
    double defect = 0;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            const double g = r[a] * r[b] + r[3 + a] * r[3 + b] + r[6 + a] * r[6 + b];
            const double d = g - (a == b ? 1.0 : 0.0);
            const double dev = d < 0 ? -d : d;
            defect = dev > defect ? dev : defect;
        }
    return defect;
}

/* det R, expanded along the first row. */
TTDW_FN double ttd_rotation_det(const double r[9])
{
    return r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
           r[2] * (r[3] * r[7] - r[4] * r[6]);
}

#endif
