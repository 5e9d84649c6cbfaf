/* SPDX-License-Identifier: MIT */
/* Maps the short lane names a kernel uses onto the translation unit's precision: after
 * core/precision.h, `vreal` is ttdw_vd or ttdw_vf, `vfma` is ttdw_fma_d or ttdw_fma_f, and so
 * on (see lanes.h for what each does). */
#ifndef TTD_SIMD_LANES_PRECISION_H
#define TTD_SIMD_LANES_PRECISION_H

#ifndef TTD_SIMD_LANES_H
#error "include simd/lanes.h first"
#endif

#ifdef TTD_PRECISION_DOUBLE
typedef ttdw_vd vreal;
typedef ttdw_md vmask;
#define TTDW_LANES TTDW_LANES_D
#define vset1 ttdw_set1_d
#define vzero ttdw_zero_d
#define vloadu ttdw_loadu_d
#define vstoreu ttdw_storeu_d
#define vfma ttdw_fma_d
#define vmin ttdw_min_d
#define vmax ttdw_max_d
#define vsqrt ttdw_sqrt_d
#define vabs ttdw_abs_d
#define vpow2 ttdw_pow2_d
#define vlt ttdw_lt_d
#define vle ttdw_le_d
#define vgt ttdw_gt_d
#define vge ttdw_ge_d
#define veq ttdw_eq_d
#define vsel ttdw_sel_d
#define mand ttdw_mand_d
#define mor ttdw_mor_d
#define mandnot ttdw_mandnot_d
#define mtrue ttdw_mtrue_d
#define mnot ttdw_mnot_d
#define mfirst ttdw_mfirst_d
#define mbits ttdw_mbits_d
#define many ttdw_any_d
#define mnone ttdw_none_d
#define vload_aos9 ttdw_load_aos9_d
#else
typedef ttdw_vf vreal;
typedef ttdw_mf vmask;
#define TTDW_LANES TTDW_LANES_F
#define vset1 ttdw_set1_f
#define vzero ttdw_zero_f
#define vloadu ttdw_loadu_f
#define vstoreu ttdw_storeu_f
#define vfma ttdw_fma_f
#define vmin ttdw_min_f
#define vmax ttdw_max_f
#define vsqrt ttdw_sqrt_f
#define vabs ttdw_abs_f
#define vpow2 ttdw_pow2_f
#define vlt ttdw_lt_f
#define vle ttdw_le_f
#define vgt ttdw_gt_f
#define vge ttdw_ge_f
#define veq ttdw_eq_f
#define vsel ttdw_sel_f
#define mand ttdw_mand_f
#define mor ttdw_mor_f
#define mandnot ttdw_mandnot_f
#define mtrue ttdw_mtrue_f
#define mnot ttdw_mnot_f
#define mfirst ttdw_mfirst_f
#define mbits ttdw_mbits_f
#define many ttdw_any_f
#define mnone ttdw_none_f
#define vload_aos9 ttdw_load_aos9_f
#endif

#endif /* TTD_SIMD_LANES_PRECISION_H */
