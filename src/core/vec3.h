/* SPDX-License-Identifier: MIT */
/* Small operations on 3-vectors of doubles that several host files used to write each for
 * itself (the hierarchy's build, src/mesh/build.c; the scene's normals and manifold,
 * src/scene/normal_impl.h). TTDW_FN, so device code may share them too. */
#ifndef TTD_CORE_VEC3_H
#define TTD_CORE_VEC3_H

#include "core/device_fn.h"

/* a x b into out (out must not alias a or b). */
TTDW_FN void ttd_cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

#endif
