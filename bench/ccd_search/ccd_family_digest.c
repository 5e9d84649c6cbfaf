/* SPDX-License-Identifier: MIT */
/* A digest of the primitive search's answers (ttd_ccd_query, src/ccd/) on the tests' generated
 * query families (tests/ccd_families.h), so that two versions of the search can be compared bit for
 * bit, interval counts included, beside ccd_csv_time's digests of the CSV files (docs/ccd-speed.md).
 * Built by hand against one version's src/ccd/:
 *
 *   V=<a tree of that version>; cc -O2 -ffp-contract=off -I$V/src -I$V/include -Itests \
 *      bench/ccd_search/ccd_family_digest.c $V/src/ccd/ccd.c -lm -o ccd_family_digest
 *   ./ccd_family_digest [N [T_STOP]]
 *
 * N queries a family and kind (default 3000), each searched at delta 0 and 1e-6 with t_stop T_STOP
 * (default HUGE_VAL, the whole search). Prints per family and kind the hits, intervals and the
 * FNV-1a digest of every answer (hit, flags, the bits of toi and gap, evals), then the total. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "ccd/ccd.h"
#include "ccd_digest.h"

#define TEST_RAND_SEED 0x2545f4914f6cdd1dull
#include "test_rand.h"
#include "ccd_families.h"

int main(int argc, char **argv)
{
    const size_t n = argc > 1 ? (size_t)atol(argv[1]) : 3000;
    const double t_stop = argc > 2 ? atof(argv[2]) : HUGE_VAL;
    static const double deltas[2] = {0, 1e-6};
    uint64_t all = CCD_DIGEST_START;
    size_t queries = 0;
    for (int fam = 0; fam < F_COUNT; ++fam)
        for (int kind = 1; kind <= 2; ++kind) {
            qset s = make_set(fam, kind, n);
            uint64_t h = CCD_DIGEST_START;
            size_t hits = 0;
            unsigned long long evals = 0;
            for (int d = 0; d < 2; ++d)
                for (size_t q = 0; q < s.n; ++q) {
                    ttd_ccd_params p = ttd_ccd_default_params();
                    p.delta = deltas[d];
                    p.t_stop = t_stop;
                    ttd_ccd_result o;
                    ttd_ccd_query(kind, s.x0 + 12 * q, s.x1 + 12 * q, &p, &o);
                    hits += o.hit;
                    evals += o.evals;
                    h = ccd_digest_answer(h, &o);
                    ++queries;
                }
            printf("%-40s %s: %zu hits, %llu intervals, digest %016llx\n", family_name[fam],
                   kind == TTD_CCD_VF ? "vertex-face" : "edge-edge", hits, evals, (unsigned long long)h);
            all = ccd_fnv(all, &h, sizeof h);
            free(s.x0);
            free(s.x1);
        }
    printf("%zu queries, digest %016llx\n", queries, (unsigned long long)all);
    return 0;
}
