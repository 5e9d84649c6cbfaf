/* SPDX-License-Identifier: MIT */
/* Per-method facts the engine acts on, kept beside the kernel contract (core/kernels.h) so that
 * the engine asks the method instead of testing which method it is. */
#include "core/kernels.h"

static const ttd_method_traits ttd_traits[TTD_METHOD_COUNT] = {
    [TTD_METHOD_EXACT] = {.may_not_converge = 0},
    [TTD_METHOD_PENALTY] = {.may_not_converge = 1},
    [TTD_METHOD_PENALTY_REFERENCE] = {.may_not_converge = 1},
    [TTD_METHOD_BARRIER] = {.may_not_converge = 1},
    /* the certified mode never leaves a pair unconverged: it falls back to the exact method */
    [TTD_METHOD_CERTIFIED] = {.may_not_converge = 0},
};

const ttd_method_traits *ttd_method_traits_of(ttd_method method)
{
    return &ttd_traits[method];
}
