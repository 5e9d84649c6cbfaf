/* SPDX-License-Identifier: MIT */
/* The mesh queries in double: mesh/query_impl.h compiled for this precision, and its entries
 * (mesh/mesh.h) written out. */
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TTD_PRECISION_DOUBLE
#include "core/grid_cells.h"
#include "core/precision.h"
#include "engine/dispatch.h"
#include "engine/parallel.h"
#include "mesh/memory.h"
#include "mesh/mesh.h"

typedef ttd_kernels_d ttd_row;
typedef ttd_node_test_d_fn ttd_node_test_fn;
typedef ttd_node_within_d_fn ttd_node_within_fn;
typedef ttd_mesh_result_d ttd_mesh_result;
typedef ttd_contact_d ttd_contact;
typedef ttd_contacts_d ttd_contacts;
#define TTD_ROW ttd_row
#define TTD_KERNEL_FN ttd_kernel_d_fn
#define TTD_DISPATCH_ROW ttd_dispatch_row_d
#define TTD_DISPATCH_KERNEL ttd_dispatch_kernel_d
#include "mesh/query_impl.h"

ttd_status ttd_mesh_query_distance_d(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                     size_t k, const double *poses, const double *poses_a, const double *defects, double upper_bound,
                                     double rel_tol, ttd_mesh_result_d *out)
{
    return query_distance(cfg, a, b, k, poses, poses_a, defects, upper_bound, rel_tol, out);
}

ttd_status ttd_mesh_query_collide_d(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                    size_t k, const double *poses, const double *poses_a, const double *defects, double margin, ttd_collision *out)
{
    return query_collide(cfg, a, b, k, poses, poses_a, defects, margin, out);
}

ttd_status ttd_mesh_query_contacts_d(const ttd_engine_config *cfg, const struct ttd_mesh *a, const struct ttd_mesh *b,
                                     size_t k, const double *poses, const double *poses_a, const double *defects, double margin,
                                     ttd_contacts_d *out)
{
    return query_contacts(cfg, a, b, k, poses, poses_a, defects, margin, out);
}

ttd_status ttd_mesh_query_contacts_count_d(const ttd_engine_config *cfg, const struct ttd_mesh *a,
                                           const struct ttd_mesh *b, size_t k, const double *poses,
                                           const double *defects, double margin, size_t *counts)
{
    return query_contacts_count(cfg, a, b, k, poses, defects, margin, counts);
}

ttd_status ttd_mesh_query_self_contacts_count_d(const ttd_engine_config *cfg, const struct ttd_mesh *m, double margin,
                                                unsigned shared, size_t *count)
{
    return query_self_contacts_count(cfg, m, margin, shared, count);
}

ttd_status ttd_mesh_query_contacts_walk_d(const ttd_engine_config *cfg, const struct ttd_mesh *a,
                                          const struct ttd_mesh *b, const double *pose, const double *pose_a, double defect,
                                          double margin, ttd_contacts_d *out,
                                          uint64_t tests[2])
{
    return query_contacts_walk(cfg, a, b, pose, pose_a, defect, margin, out, tests);
}

ttd_status ttd_mesh_query_contacts_walk_count_d(const ttd_engine_config *cfg, const struct ttd_mesh *a,
                                                const struct ttd_mesh *b, const double *pose, const double *pose_a,
                                                double defect, double margin, size_t *count, uint64_t tests[2])
{
    return query_contacts_walk_count(cfg, a, b, pose, pose_a, defect, margin, count, tests);
}

ttd_status ttd_mesh_query_self_contacts_d(const ttd_engine_config *cfg, const struct ttd_mesh *m, double margin,
                                          unsigned shared, ttd_contacts_d *out)
{
    return query_self_contacts(cfg, m, margin, shared, out);
}

ttd_status ttd_mesh_query_self_contacts_walk_d(const ttd_engine_config *cfg, const struct ttd_mesh *m, double margin,
                                               unsigned shared, ttd_contacts_d *out)
{
    return query_self_contacts_walk(cfg, m, margin, shared, out);
}

ttd_status ttd_mesh_query_self_collide_d(const ttd_engine_config *cfg, const struct ttd_mesh *m, double margin,
                                         unsigned shared, ttd_collision *out)
{
    return query_self_collide(cfg, m, margin, shared, out);
}
