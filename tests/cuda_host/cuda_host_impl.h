/* SPDX-License-Identifier: MIT */
/* What the cuda-host row's mesh and point entries run, once per precision (cuda_host_d.c and
 * cuda_host_f.c include it after the kernels and the device walks, and export the names): the
 * device walks of src/gpu/ on the CPU's own arrays, one "thread" after another. */

/* The device walk's view of a mesh: the CPU's arrays as they are (src/gpu/ copies them). */
static gw_mesh host_view(const struct ttd_mesh *m)
{
    gw_mesh g = {(const ttd_node *)m->nodes, (const real *)m->verts, m->tris, {m->origin[0], m->origin[1], m->origin[2]},
                 m->radius, 0};
    g.height = gw_tree_height(g.nodes, 0);
    return g;
}

static void host_mesh_distance(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const real *poses,
                               real upper_bound, uint64_t vote, gw_mesh_result *out)
{
    const gw_mesh ga = host_view(a), gb = host_view(b);
    for (size_t i = 0; i < k; ++i) /* what thread i of src/gpu/'s pose kernel runs */
        gw_distance_pose(&ga, &gb, poses + 12 * i, upper_bound, vote ? vote + i : 0, &out[i]);
}

static void host_mesh_collide(const struct ttd_mesh *a, const struct ttd_mesh *b, size_t k, const real *poses, real margin,
                              uint64_t vote, ttd_collision *out)
{
    const gw_mesh ga = host_view(a), gb = host_view(b);
    for (size_t i = 0; i < k; ++i)
        gw_collide_pose(&ga, &gb, poses + 12 * i, margin, vote ? vote + i : 0, &out[i]);
}

static int host_closest(const struct ttd_mesh *m, size_t n, const real *points, real upper_bound, gp_point_result *out)
{
    const ttd_points_data *pd = ttd_points_data_get(m, 1); /* the CPU's point data, as an upload would copy */
    if (pd == NULL)
        return -1;
    const gp_mesh g = {pd->pnodes, (const real *)pd->blocks, {m->origin[0], m->origin[1], m->origin[2]}, m->radius,
                       pd->scale, pd->stretch};
    for (size_t i = 0; i < n; ++i) /* what thread i of a device point kernel would run */
        gp_closest(&g, points + 3 * i, upper_bound, &out[i]);
    return 0;
}

/* ---- signed distances (src/gpu/gpu_signed_impl.h) ---- */

static int host_signed(const struct ttd_mesh *m, size_t n, const real *points, real upper_bound, real *distance,
                       gp_point_result *out)
{
    const ttd_points_data *pd = ttd_points_data_get(m, 1);
    if (pd == NULL)
        return -1;
    const int mode = ttd_gpu_sign_mode(m, pd); /* as the upload chooses it */
    if (mode == TTD_GPU_SIGN_NONE)
        return 0;
    gs_mesh g;
    g.closest = (gp_mesh){pd->pnodes, (const real *)pd->blocks, {m->origin[0], m->origin[1], m->origin[2]}, m->radius,
                          pd->scale, pd->stretch};
    g.ray = (ttd_ray_mesh){pd->rnodes, m->verts, m->tris, m->bytes, {m->origin[0], m->origin[1], m->origin[2]},
                           m->radius, pd->scale, pd->coord_max};
    g.mode = mode;
    for (size_t i = 0; i < n; ++i) /* what thread i of the device's signed kernel runs */
        gs_signed(&g, points + 3 * i, upper_bound, distance ? distance + i : NULL, &out[i]);
    return mode;
}
