/* SPDX-License-Identifier: MIT */
/* Continuous collision of two rigid bodies between two poses each, by conservative advancement
 * (rigid_ccd_api.c), shared by ttd_mesh_ccd_rigid_d/f and the scene's ttd_scene_ccd_d/f. */
#ifndef TTD_API_RIGID_CCD_H
#define TTD_API_RIGID_CCD_H

#include "meshccd/rigid_motion.h"
#include "ttd/ttd.h"

/// One body of a pair: its mesh, its motion, max |x| over the mesh's vertices and its speed bound.
typedef struct rigid_body {
    const struct ttd_mesh *mesh;
    rigid_motion motion;
    double radius, speed;
    double reach; ///< max(|T0|, |T1|): how far from the world origin its own origin goes
} rigid_body;

/// The body's share of a pair's tolerance eta and margin mu (ttd_rigid_ccd_pair: eta = 2^-30 S
/// in double, 2^-14 S in float, mu at most eta / 8, S summed over the pair's bodies), with room
/// for rounding: a pair may answer a hit while its bodies stay this much (summed) beyond delta,
/// so the scene's broad phase widens its test by it.
static inline double rigid_band(const rigid_body *b, int bytes)
{
    return (b->radius + b->reach) * (bytes == 8 ? 0x1p-30 : 0x1p-14) * 1.25;
}

/// The body's motion between two poses (checked already) of 12 reals of bytes each.
void rigid_body_make(rigid_body *body, const struct ttd_mesh *mesh, const void *pose0, const void *pose1, int bytes);

/// The pair's conservative advancement; opt is handed to the mesh distance (its checks done).
ttd_status ttd_rigid_ccd_pair(const ttd_options *opt, const rigid_body *a, const rigid_body *b, int bytes,
                              double delta, ttd_mesh_ccd_rigid_result *out);

#endif /* TTD_API_RIGID_CCD_H */
