/* SPDX-License-Identifier: MIT */
/* The scalar reference of continuous collision (ccd/ccd.h): the search itself is
 * ccd_search_impl.h, one source for the CPU and the device (src/gpu/gpu_ccd.cu); here its C
 * entries. */
#include "ccd/ccd_search_impl.h"

ttd_ccd_params ttd_ccd_default_params(void)
{
    return ccd_params_default();
}

int ttd_ccd_screen(int kind, const double x0[12], const double x1[12], double delta, double t_max)
{
    return ccd_screen_one(kind, x0, x1, delta, t_max);
}

void ttd_ccd_query(int kind, const double x0[12], const double x1[12], const ttd_ccd_params *p,
                   ttd_ccd_result *out)
{
    ccd_query_one(kind, x0, x1, p, out);
}
