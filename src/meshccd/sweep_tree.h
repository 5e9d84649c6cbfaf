/* SPDX-License-Identifier: MIT */
/* A bounding-volume hierarchy over swept boxes, for continuous collision of deforming meshes
 * (meshccd.c). A swept box is the axis-aligned box of a primitive's vertices at t = 0 and t = 1:
 * a vertex moving on a straight line stays in the box of its two ends, so a triangle's swept box
 * holds the triangle at every t in [0, 1]. Boxes are made from the coordinates by min and max
 * alone (exact); the tree's boxes are widened by delta with outward rounding, so that a box test
 * that fails proves the two primitives more than delta apart along an axis at every t.
 *
 * Binary tree, leaves of up to `leaf` boxes (SWEEP_LEAF for a walk per leaf of the other mesh's
 * tree, SWEEP_LEAF_SELF for the tree against itself), built per call: the boxes in Morton order of
 * their centres (a radix sort, stable), split in halves. Each node covers a range of that order. */
#ifndef TTD_MESHCCD_SWEEP_TREE_H
#define TTD_MESHCCD_SWEEP_TREE_H

#include <stddef.h>
#include <stdint.h>

#define SWEEP_LEAF 4
/* The self walk tests two leaves' boxes against each other in turn, in order and without
 * branches, which costs less than the node pairs that smaller leaves add (docs/ccd-speed.md). */
#define SWEEP_LEAF_SELF 8

/// A box: lo[3], hi[3].
typedef struct sweep_box {
    double lo[3], hi[3];
} sweep_box;

/// A node covers order[begin, end); an inner node's children are nodes left and left + 1.
typedef struct sweep_node {
    sweep_box box;
    uint32_t begin, end;
    uint32_t left; /* 0 for a leaf (node 0 is the root, never a child) */
    uint32_t pad;
} sweep_node;

typedef struct sweep_tree {
    sweep_node *nodes;
    uint32_t *order; /* box indices in Morton order */
    size_t n, nnodes;
} sweep_tree;

/// The box of the two ends x0, x1 of a moving point (exact).
static inline void sweep_point_box(const double *x0, const double *x1, sweep_box *b)
{
    for (int k = 0; k < 3; ++k) {
        b->lo[k] = x0[k] < x1[k] ? x0[k] : x1[k];
        b->hi[k] = x0[k] < x1[k] ? x1[k] : x0[k];
    }
}

/// b grown to hold c.
static inline void sweep_box_join(sweep_box *b, const sweep_box *c)
{
    for (int k = 0; k < 3; ++k) {
        b->lo[k] = c->lo[k] < b->lo[k] ? c->lo[k] : b->lo[k];
        b->hi[k] = c->hi[k] > b->hi[k] ? c->hi[k] : b->hi[k];
    }
}

/// b widened by delta on every side, rounded outward: lo <= lo - delta and hi >= hi + delta exactly.
void sweep_box_widen(sweep_box *b, double delta);

/// Whether a and the widened box w overlap (closed): 0 proves that on some axis the exact gap
/// between a and the unwidened box exceeds delta.
static inline int sweep_overlap(const sweep_box *a, const sweep_box *w)
{
    return a->lo[0] <= w->hi[0] && w->lo[0] <= a->hi[0] && a->lo[1] <= w->hi[1] && w->lo[1] <= a->hi[1] &&
           a->lo[2] <= w->hi[2] && w->lo[2] <= a->hi[2];
}

/// Builds the tree over n >= 1 boxes (kept by pointer: they must outlive the tree), leaves of
/// up to leaf >= 1 boxes. 0 on success, -1 out of memory (*t zeroed).
int sweep_tree_build(const sweep_box *boxes, size_t n, uint32_t leaf, sweep_tree *t);
void sweep_tree_free(sweep_tree *t);

#endif /* TTD_MESHCCD_SWEEP_TREE_H */
