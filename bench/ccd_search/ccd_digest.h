/* SPDX-License-Identifier: MIT */
/* The digest ccd_csv_time.c and ccd_family_digest.c print, in one place so that their digests of
 * the same answers stay comparable: FNV-1a (64-bit) over each answer's hit, flags, the bits of toi
 * and gap, and evals. Include after "ccd/ccd.h". */
#ifndef TTD_BENCH_CCD_DIGEST_H
#define TTD_BENCH_CCD_DIGEST_H

#include <stddef.h>
#include <stdint.h>

#define CCD_DIGEST_START 0xcbf29ce484222325ull

static uint64_t ccd_fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < n; ++i)
        h = (h ^ c[i]) * 0x100000001b3ull;
    return h;
}

static uint64_t ccd_digest_answer(uint64_t h, const ttd_ccd_result *o)
{
    h = ccd_fnv(h, &o->hit, sizeof o->hit);
    h = ccd_fnv(h, &o->flags, sizeof o->flags);
    h = ccd_fnv(h, &o->toi, sizeof o->toi);
    h = ccd_fnv(h, &o->gap, sizeof o->gap);
    return ccd_fnv(h, &o->evals, sizeof o->evals);
}

#endif
