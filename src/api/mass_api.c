/* SPDX-License-Identifier: MIT */
/* The mass-properties entries of include/ttd/ttd.h: the checks (pointers, the mesh's precision,
 * the density), then src/mesh/mass.c. */
#include <math.h>

#include "mesh/mass.h"
#include "mesh/mesh.h"
#include "ttd/ttd.h"

static ttd_status mass_properties(int bytes, const ttd_mesh *mesh, double density, ttd_mass_properties *out)
{
    if (mesh == NULL || out == NULL)
        return TTD_ERR_NULL_POINTER;
    if (mesh->bytes != bytes)
        return TTD_ERR_PRECISION_MISMATCH;
    if (!isfinite(density) || !(density > 0))
        return TTD_ERR_BAD_OPTIONS;
    return ttd_mesh_mass_compute(mesh, density, out);
}

ttd_status ttd_mesh_mass_properties_d(const ttd_mesh *mesh, double density, ttd_mass_properties *out)
{
    return mass_properties(8, mesh, density, out);
}

ttd_status ttd_mesh_mass_properties_f(const ttd_mesh *mesh, double density, ttd_mass_properties *out)
{
    return mass_properties(4, mesh, density, out);
}
