#!/bin/bash
# A/B refit timings as `ttd bench` takes them (a build before each refit, CPU time of the calling
# thread, page faults included) for two builds of bench/refit/refit_steps.c (A and B): ROUNDS
# alternating runs of each at 10k and 100k triangles (NU 100: 300 refits, NU 316: 60), each run
# printing its medians; then the median over the runs of each.
#   bench/refit/refit_ab_build.sh ./refit_steps_old ./refit_steps_new [ROUNDS]
set -euo pipefail
A=$1 B=$2 ROUNDS=${3:-3}
for a in "100 300" "316 60"; do
    set -- $a
    ra=() rb=() ba=() bb=()
    for ((r = 0; r < ROUNDS; ++r)); do
        for v in A B; do
            out=$("${!v}" "$1" "$2" build)
            refit=$(echo "$out" | sed -E 's/.*refit ([0-9.]+) ms.*/\1/')
            build=$(echo "$out" | sed -E 's/.*build ([0-9.]+) ms.*/\1/')
            if [ "$v" = A ]; then ra+=("$refit") ba+=("$build"); else rb+=("$refit") bb+=("$build"); fi
        done
    done
    med() { printf "%s\n" "$@" | sort -g | awk '{x[NR] = $1} END {print x[int((NR + 1) / 2)]}'; }
    printf "nu %s: A refit %s ms (runs: %s), build %s; B refit %s ms (runs: %s), build %s\n" "$1" \
        "$(med "${ra[@]}")" "${ra[*]}" "$(med "${ba[@]}")" "$(med "${rb[@]}")" "${rb[*]}" "$(med "${bb[@]}")"
done
