/* SPDX-License-Identifier: MIT */
/* A closed mesh's mass properties as a solid of uniform density (docs/mass-properties.md): the
 * entry's checks live in api/mass_api.c. */
#ifndef TTD_MESH_MASS_H
#define TTD_MESH_MASS_H

#include "ttd/ttd.h"

struct ttd_mesh;

/// The mass properties of mesh (checked: not NULL, density finite and > 0) into *out:
/// TTD_OK, TTD_ERR_MESH_NOT_CLOSED (a surface that does not close, or is not oriented
/// consistently, by its vertices' places), TTD_ERR_OUT_OF_MEMORY.
ttd_status ttd_mesh_mass_compute(const struct ttd_mesh *mesh, double density, ttd_mass_properties *out);

#endif /* TTD_MESH_MASS_H */
