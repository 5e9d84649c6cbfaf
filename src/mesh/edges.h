/* SPDX-License-Identifier: MIT */
/* The shape of a mesh's surface around each triangle: which triangle lies across each edge, and
 * whether each edge and each corner of a triangle is a real feature of the body (a sharp convex
 * or concave edge, a corner) or lies inside a flat part of it (an edge between coplanar
 * triangles, a vertex all of whose triangles are coplanar). The scene's contact normals read it
 * (docs/scenes.md, section 5): a face's normal where a contact's feature is flat, the normal
 * cone of a real convex edge or corner otherwise.
 *
 * Flat pieces: the triangles joined by flat edges, with their area, so that where two faces
 * meet the larger flat part of a body can be told (the same for any triangulation of a face).
 * Each triangle's unit normal (in float), for the manifold's cheap test of whether two triangles
 * lie face on face.
 *
 * ttd_mesh_edges_build is a function of the vertices and triangles alone (no other state of
 * the mesh), made on the first query that reads it (ttd_mesh_edges_get, mesh/mesh.h), so that a
 * mesh build does not pay for it; a mesh whose vertices change drops it and has it made again. */
#ifndef TTD_MESH_EDGES_H
#define TTD_MESH_EDGES_H

#include <stddef.h>
#include <stdint.h>

/* Edge k of triangle t joins its vertices k and (k + 1) mod 3. Its class, 2 bits at 2k of
 * shape[t]: */
enum {
    TTD_EDGE_FLAT = 0,    /* between two triangles whose normals are within TTD_FLAT_ANGLE */
    TTD_EDGE_CONVEX = 1,  /* a real edge: the neighbour bends away from t's front side */
    TTD_EDGE_CONCAVE = 2, /* a real edge: the neighbour bends towards it */
    TTD_EDGE_OPEN = 3     /* a boundary, more than two triangles, opposite windings, or a
                           * triangle without area on either side */
};
/* The class of vertex k of triangle t, 2 bits at 6 + 2k of shape[t]: */
enum {
    TTD_VERTEX_FLAT = 0,   /* inside a flat part: every triangle around it within TTD_FLAT_ANGLE of
                            * the first, every edge at it flat */
    TTD_VERTEX_CORNER = 1, /* a convex corner: every edge at it convex or flat, at most
                            * TTD_CORNER_MAX triangles around it */
    TTD_VERTEX_OTHER = 2   /* anything else: concave or saddle, on a boundary, or more triangles */
};

/* Two triangles are coplanar for these classes when their normals are within this angle
 * (radians): about 0.06 degrees. Far above the rounding of a flat face's normals in float (a few
 * 1e-7 over the triangle's aspect ratio), far below the angle between neighbours of a curved
 * surface of any realistic tessellation (a 1M-triangle torus's are several 1e-3). */
#define TTD_FLAT_ANGLE 1e-3
/* A flat piece is planar when its vertices lie within this fraction of the mesh's largest
 * coordinate (the scale its vertices are rounded at) of one plane: far above the rounding of a
 * plane's points in double (2^-53), below float's (2^-24: a float mesh's tilted plane is seldom
 * planar, so its flat contacts mostly stay points), far below any gap a contact margin
 * measures. A bump below it counts as flat: the manifold's deepest point can then be that much
 * shallower than the pair's (docs/scenes.md, section 5, step 0). */
#define TTD_PLANAR_TOL 0x1p-36
/* At most this many triangles around a corner (its normal cone has one side per edge). */
#define TTD_CORNER_MAX 16
/* The triangle across an open edge. */
#define TTD_NO_TRIANGLE UINT32_MAX

typedef struct ttd_mesh_edges {
    uint32_t *across;     /* 3 nt: the triangle across edge k of t, or TTD_NO_TRIANGLE */
    uint16_t *shape;      /* nt: the classes of t's edges and vertices (above) */
    uint32_t *weld;       /* nv: each vertex's place, the same for vertices at the same point */
    uint32_t *ring_start; /* nw + 1: ring[ring_start[w] .. ring_start[w + 1]) are the triangles */
    uint32_t *ring;       /* around place w, in triangle order (3 nt entries) */
    size_t nw;            /* places: distinct vertex positions */
    uint32_t *piece;      /* nt: the flat piece of each triangle (triangles joined by flat edges),
                           * numbered by their first triangle's turn */
    double *piece_area;   /* per piece: log2 of its area (-inf for none) */
    unsigned char *piece_planar; /* per piece: 1 when every vertex of its triangles lies within
                                  * TTD_PLANAR_TOL of the plane of its largest triangle (a flat
                                  * piece may bend by up to TTD_FLAT_ANGLE at each flat edge:
                                  * a finely cut cylinder is one piece, not planar) */
    size_t npieces;
    float *normal;        /* 3 nt: each triangle's unit normal in the mesh's frame (0 for none),
                           * for a cheap test of how two triangles face each other */
    int inward;           /* a closed surface wound inward (negative volume): a solid of it is the
                           * solid it bounds, whose outward normals are its triangles' negated */
    uint16_t *shape_solid; /* inward: shape as that solid sees it (convex and concave edges
                            * swapped, its corners), else NULL */
} ttd_mesh_edges;

/* e as a body sees it: a solid body of an inward mesh sees shape_solid (view: scratch). */
static inline const ttd_mesh_edges *ttd_mesh_edges_seen(const ttd_mesh_edges *e, int solid, ttd_mesh_edges *view)
{
    if (!solid || !e->inward)
        return e;
    *view = *e;
    view->shape = e->shape_solid;
    return view;
}

static inline int ttd_edge_class(const ttd_mesh_edges *e, uint32_t t, int k)
{
    return (e->shape[t] >> (2 * k)) & 3;
}

static inline int ttd_vertex_class(const ttd_mesh_edges *e, uint32_t t, int k)
{
    return (e->shape[t] >> (6 + 2 * k)) & 3;
}

/// The edge information of the mesh of nv vertices (3 nv reals of `bytes` bytes each, finite) and
/// nt triangles (indices in range) into *out: 1, or 0 out of memory (*out then holds nothing).
/// Vertices at the same point (bit for bit, +0 and -0 alike) are one place, so a mesh whose
/// faces do not share vertex indices (an STL file's) gets the same answer as one that does.
/// Deterministic: the same input gives the same arrays on any thread count.
int ttd_mesh_edges_build(int bytes, const void *verts, size_t nv, const uint32_t *tris, size_t nt,
                         ttd_mesh_edges *out);

/// Frees what ttd_mesh_edges_build allocated (a zeroed struct is fine) and zeroes it.
void ttd_mesh_edges_free(ttd_mesh_edges *e);

#endif /* TTD_MESH_EDGES_H */
