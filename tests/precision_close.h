/* SPDX-License-Identifier: MIT */
/* Closes a section opened by tests/precision_open.h. */
#undef TTD_PRECISION_DOUBLE
#undef TTD_PRECISION_FLOAT
#undef real
#undef TTD_SFX
#undef ttd_result
#undef TTD_REAL_EPS
#undef TTD_REAL_MIN
#undef TTD_REAL_MAX
#undef TTD_SQRT
#undef TTD_FABS
#undef TTD_FMA
#undef TTD_FREXP
#undef TTD_LDEXP
#undef TTD_NEXTAFTER
