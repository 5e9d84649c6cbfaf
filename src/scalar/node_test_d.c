/* SPDX-License-Identifier: MIT */
/* ttd_node_test_scalar_d: the mesh queries' node test in double, one child at a time (the code
 * is precision-generic, in node_test_impl.h). */
#define TTD_PRECISION_DOUBLE
#include "core/precision.h"
#include "scalar/scalar.h"
#include "scalar/node_test_impl.h"

void ttd_node_test_scalar_d(const ttd_box_query_d *x, const ttd_node_d *y, double lb2[TTD_NODE_WIDTH],
                            double sep[TTD_NODE_WIDTH])
{
    node_test(x, y, lb2, sep);
}

unsigned ttd_node_within_scalar_d(const ttd_box_query_d *x, const ttd_node_d *y, double lim2, double lb2[TTD_NODE_WIDTH],
                              double sep[TTD_NODE_WIDTH])
{
    return node_within(x, y, lim2, lb2, sep);
}
