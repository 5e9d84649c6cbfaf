/* SPDX-License-Identifier: MIT */
/* Welding's vertex classes, shared by the public ttd_mesh_weld_d/f (weld.c) and the mesh-file
 * reader's ttd_meshfile_weld (meshfile.c), which carries its float coordinates along. */
#ifndef TTD_IO_WELD_H
#define TTD_IO_WELD_H

#include <stddef.h>
#include <stdint.h>

/// The classes of nv finite vertices (3 doubles each) under "within tol" (include/ttd/ttd.h,
/// ttd_mesh_weld_d), chained: map[i] is vertex i's new index, numbered by each class's smallest
/// old index; rep[j] (nv entries of room) the old index of class j's representative, its
/// lexicographically smallest vertex by value. *nclasses the number of classes. 0, or -1 when
/// memory ran out. nv must be below 2^32 and tol finite and >= 0 (the callers check).
int ttd_weld_classes(const double *v, size_t nv, double tol, uint32_t *map, uint32_t *rep, size_t *nclasses);

#endif
