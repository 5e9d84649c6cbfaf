/* SPDX-License-Identifier: MIT */
/* The mesh-query fuzzer (tests/meshfuzz/) from a fixed seed: every family, both precisions,
 * every available instruction set with 1 and 2 threads, every query against the brute force
 * over all triangle pairs (docs/testing.md). The default run is the CTest ttd.mesh_fuzz; the
 * same program does long runs:
 *
 *   test_mesh_fuzz [--seed S] [--cases N | --checks N] [--first I] [--family NAME] [--verbose]
 *                  [--max-printed M] [--input FILE...]
 *
 * Case i of seed S depends only on (S, i, family), so a failure's "rerun:" line repeats it
 * alone. Without --family, case i has family i mod (number of families). --checks N runs
 * cases until N checks are done. --input runs libFuzzer inputs (tests/fuzz/fuzz_mesh.c) with
 * the small meshes of that target but on every instruction set, one case per file. Exits 1 on any failure. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshfuzz/meshfuzz.h"

static void usage(void)
{
    fprintf(stderr, "usage: test_mesh_fuzz [--seed S] [--cases N | --checks N] [--first I] [--family NAME] "
                    "[--verbose] [--max-printed M] [--input FILE...]\nfamilies:");
    for (int f = 0; f < MF_COUNT; ++f)
        fprintf(stderr, " %s", mf_family_name(f));
    fputc('\n', stderr);
}

/* Each file as one libFuzzer input of fuzz_mesh, small meshes, every instruction set. */
static int run_inputs(mf_run *run, int n, char **files)
{
    run->small = 1;
    run->dump_failures = 1;
    for (int i = 0; i < n; ++i) {
        FILE *f = fopen(files[i], "rb");
        if (!f) {
            perror(files[i]);
            return 2;
        }
        static uint8_t buf[1 << 16];
        const size_t len = fread(buf, 1, sizeof buf, f);
        fclose(f);
        mf_src src;
        mf_src_bytes(&src, buf, len);
        if (mf_run_case(run, &src, -1, 0, (uint64_t)i))
            printf("input %s failed\n", files[i]);
    }
    return mf_summary(run, stdout);
}

int main(int argc, char **argv)
{
    unsigned long long seed = 20261126, cases = 280, first = 0, checks = 0;
    int family = -1;
    mf_run run;
    memset(&run, 0, sizeof run);
    run.allow_big = 1;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--verbose") == 0) {
            run.verbose = 1;
            continue;
        }
        if (strcmp(a, "--input") == 0) { /* the rest are files */
            return run_inputs(&run, argc - i - 1, argv + i + 1);
        }
        if (!v) {
            usage();
            return 2;
        }
        ++i;
        if (strcmp(a, "--seed") == 0)
            seed = strtoull(v, NULL, 0);
        else if (strcmp(a, "--cases") == 0)
            cases = strtoull(v, NULL, 0);
        else if (strcmp(a, "--checks") == 0)
            checks = strtoull(v, NULL, 0), cases = ~0ull;
        else if (strcmp(a, "--first") == 0)
            first = strtoull(v, NULL, 0);
        else if (strcmp(a, "--max-printed") == 0)
            run.max_printed = atoi(v);
        else if (strcmp(a, "--family") == 0) {
            if ((family = mf_family_from_name(v)) < 0) {
                usage();
                return 2;
            }
        } else {
            usage();
            return 2;
        }
    }
    printf("mesh fuzz: seed %llu, cases %llu.. (%s), family %s\n", seed, first,
           checks ? "until the check count" : "count given", family < 0 ? "all in turn" : mf_family_name(family));
    for (unsigned long long i = first; i - first < cases && (!checks || run.checks < checks); ++i) {
        mf_src src;
        mf_src_seeded(&src, seed, i);
        mf_run_case(&run, &src, family >= 0 ? family : (int)(i % MF_COUNT), seed, i);
    }
    return mf_summary(&run, stdout);
}
