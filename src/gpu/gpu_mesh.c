/* SPDX-License-Identifier: MIT */
/* What an upload copies from a ttd_mesh (mesh/mesh.h's struct, read here in C so that the CUDA
 * side never includes the library's internal headers): its arrays as they are, and the height of
 * its hierarchy, which the device walk's fixed stack must hold (gpu_walk_impl.h, GW_STACK). */
#include "gpu/gpu_internal.h"
#include "core/point_layout.h"
#include "mesh/mesh.h"
#include "points/points.h"
#include "gpu/gpu_sign_mode.h"

/* node levels below slot 0 of node n (0: its children are triangles) */
static int32_t tree_height_d(const ttd_node_d *nodes, int32_t n)
{
    int32_t h = 0;
    for (int j = 0; j < nodes[n].count; ++j)
        if (nodes[n].child[j] >= 0) {
            const int32_t c = 1 + tree_height_d(nodes, nodes[n].child[j]);
            h = c > h ? c : h;
        }
    return h;
}

static int32_t tree_height_f(const ttd_node_f *nodes, int32_t n)
{
    int32_t h = 0;
    for (int j = 0; j < nodes[n].count; ++j)
        if (nodes[n].child[j] >= 0) {
            const int32_t c = 1 + tree_height_f(nodes, nodes[n].child[j]);
            h = c > h ? c : h;
        }
    return h;
}

void ttd_gpu_mesh_describe(const ttd_mesh *m, ttd_gpu_mesh_host *d)
{
    d->bytes = m->bytes;
    d->nv = m->nv;
    d->nt = m->nt;
    d->nnodes = m->nnodes;
    d->node_size = m->bytes == 8 ? sizeof(ttd_node_d) : sizeof(ttd_node_f);
    d->verts = m->verts;
    d->tris = m->tris;
    d->nodes = m->nodes;
    for (int i = 0; i < 3; ++i)
        d->origin[i] = m->origin[i];
    d->radius = m->radius;
    d->height = m->bytes == 8 ? tree_height_d(m->nodes, 0) : tree_height_f(m->nodes, 0);
    /* the point data as the CPU made it (published atomically; NULL until a point query ran) */
    const ttd_points_data *pd = __atomic_load_n((ttd_points_data *const *)&m->points, __ATOMIC_ACQUIRE);
    d->pnodes = pd ? pd->pnodes : NULL;
    d->blocks = pd ? pd->blocks : NULL;
    d->npnodes = pd ? pd->nnodes : 0;
    d->pnode_size = sizeof(ttd_pnode);
    d->blocks_bytes = pd ? pd->nblocks * TTD_PT_ROWS * TTD_PT_LANES * (size_t)m->bytes : 0;
    d->pscale = pd ? pd->scale : 0;
    d->pstretch = pd ? pd->stretch : 0;
    /* signed distances: the ray nodes, and how the side is decided (gpu_sign_mode.h) */
    d->rnodes = pd ? pd->rnodes : NULL;
    d->rnode_size = sizeof(ttd_rnode);
    d->coord_max = pd ? pd->coord_max : 0;
    d->sign_mode = ttd_gpu_sign_mode(m, pd);
}
