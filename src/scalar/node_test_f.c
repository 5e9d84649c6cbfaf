/* SPDX-License-Identifier: MIT */
/* ttd_node_test_scalar_f: the mesh queries' node test in float, one child at a time (the code
 * is precision-generic, in node_test_impl.h). */
#define TTD_PRECISION_FLOAT
#include "core/precision.h"
#include "scalar/scalar.h"
#include "scalar/node_test_impl.h"

void ttd_node_test_scalar_f(const ttd_box_query_f *x, const ttd_node_f *y, float lb2[TTD_NODE_WIDTH],
                            float sep[TTD_NODE_WIDTH])
{
    node_test(x, y, lb2, sep);
}

unsigned ttd_node_within_scalar_f(const ttd_box_query_f *x, const ttd_node_f *y, float lim2, float lb2[TTD_NODE_WIDTH],
                              float sep[TTD_NODE_WIDTH])
{
    return node_within(x, y, lim2, lb2, sep);
}
