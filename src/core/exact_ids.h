/* SPDX-License-Identifier: MIT */
/* What the scalar exact method (scalar/exact_impl.h) and its lane kernel (simd/kernel_exact.h)
 * must agree on, in one place: the numbering of the 39 candidates (the winner is rebuilt from
 * its id and up to three parameters) and the contact threshold. */
#ifndef TTD_CORE_EXACT_IDS_H
#define TTD_CORE_EXACT_IDS_H

enum {
    TTD_EXACT_VE_S = 0,  /* 9: vertex i of S against edge j of T: id = 3i + j, u = t */
    TTD_EXACT_VE_T = 9,  /* 9: vertex j of T against edge i of S: id = 9 + 3j + i, u = t */
    TTD_EXACT_EE = 18,   /* 9: edge i of S, edge j of T: id = 18 + 3i + j, u = s, v = t */
    TTD_EXACT_VF_S = 27, /* 3: vertex i of S on T's face: u = b, v = c */
    TTD_EXACT_VF_T = 30, /* 3: vertex j of T on S's face */
    TTD_EXACT_X_S = 33,  /* 3: edge i of S through T's face: u = tau, v = b, w = c */
    TTD_EXACT_X_T = 36,  /* 3: edge j of T through S's face */
    TTD_EXACT_COUNT = 39
};

/* A distance below this many eps of the pair's extent (~1 after normalisation) is what a
 * contact computes to, not a gap: it is reported as 0 and flagged intersecting. */
#define TTD_EXACT_TOUCH_EPS 4

#endif /* TTD_CORE_EXACT_IDS_H */
