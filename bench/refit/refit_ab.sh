#!/bin/bash
# A/B refit timings of two builds of bench/refit/refit_steps.c (A and B: the executables):
# the fastest of 5 alternating runs of each at 10k, 100k and 1M triangles (2,000, 200 and 20
# refits), user CPU time less that of the same program with 0 refits (its build), per refit.
#   bench/refit/refit_ab.sh ./refit_steps_old ./refit_steps_new
set -euo pipefail
A=$1 B=$2
cpu() { { /usr/bin/time -f "%U" "$1" "$2" "$3" > /dev/null; } 2>&1; }
for a in "100 2000" "316 200" "1000 20"; do
    set -- $a
    ba=999 bb=999
    for r in 1 2 3 4 5; do
        for v in A B; do
            exe=${!v}
            d=$(echo "($(cpu "$exe" "$1" "$2") - $(cpu "$exe" "$1" 0)) * 1000 / $2" | bc -l)
            if [ "$v" = A ]; then ba=$(echo "if ($d < $ba) $d else $ba" | bc -l); else bb=$(echo "if ($d < $bb) $d else $bb" | bc -l); fi
        done
    done
    printf "nu %s: A %.3f ms, B %.3f ms a refit\n" "$1" "$ba" "$bb"
done
