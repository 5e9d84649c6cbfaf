#!/bin/sh
# SPDX-License-Identifier: MIT
# The benchmark's figure (bench/plot.gp) keeps every bar visible: on its logarithmic axis a
# bar grows from the bottom of the range, so the range must lie strictly below the smallest
# time and above the largest. Checked on a made-up CSV whose smallest time sits exactly on a
# decade (100 ns, where autoscaling used to stop), then on a real `ttd bench --quick --csv`;
# gnuplot's GPVAL_* variables of the last panel drawn (random pairs) give the axis range and
# the data range. The same for the mesh figure (bench/plot-mesh.gp) on a made-up bench-mesh.csv
# and on a quick mesh run. Skipped, with a message, where gnuplot is not installed.
# Usage: sh test_plot.sh path/to/ttd
set -u
TTD=${1:?usage: test_plot.sh path/to/ttd}
PLOT=$(cd "$(dirname "$0")/../.." && pwd)/bench/plot.gp
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
if ! command -v gnuplot > /dev/null 2>&1; then
    echo "skip: gnuplot not found (scripts/bench.sh installs gnuplot-nox as root)"
    exit 0
fi

# check NAME CSV: the figure is written and the last panel's axis range has room on both sides.
check() {
    gnuplot -e "csv='$2'; out='$DIR/fig'" "$PLOT" \
        -e 'print GPVAL_Y_MIN, GPVAL_DATA_Y_MIN, GPVAL_Y_MAX, GPVAL_DATA_Y_MAX' > "$DIR/range" 2>&1 ||
        fail "$1: gnuplot failed: $(cat "$DIR/range")"
    [ -s "$DIR/fig.svg" ] && [ -s "$DIR/fig.png" ] || fail "$1: no figure written"
    awk 'END { if (NF != 4 || !($1 < $2 && $3 > $4)) { print "axis " $1 ".." $3 ", data " $2 ".." $4; exit 1 } }' \
        "$DIR/range" || fail "$1: a bar touches the end of the axis: $(tail -n 1 "$DIR/range")"
    echo "ok   $1: $(tail -n 1 "$DIR/range") (axis min, data min, axis max, data max)"
}

H=workload,method,precision,isa,lanes,threads,pairs,samples,ns_per_pair,ns_per_pair_min,pairs_per_s
H=$H,speedup_vs_scalar,lane_fraction,thread_speedup,speedup_vs_fcl,max_rel_err,p999_rel_err,max_abs_err
H=$H,disagree,not_converged,fallback,mean_iterations,occupancy
{
    echo "$H"
    for w in paper random; do
        for row in "double,scalar,1,1000" "double,avx2,4,250" "float,scalar,1,400" "float,avx2,8,100"; do
            echo "$row" | awk -F, -v w=$w '{ printf "%s,exact,%s,%s,%s,1,1000,3,%s,,,,,,,,,,,,,,\n", w, $1, $2, $3, $4 }'
        done
    done
} > "$DIR/decade.csv"
check bar_on_a_decade "$DIR/decade.csv"

"$TTD" bench --quick --csv --quiet --no-probes --no-fcl --workloads paper,random --methods exact,penalty > "$DIR/real.csv" ||
    fail "ttd bench exited with $?"
check real_quick_run "$DIR/real.csv"

# The mesh figure (bench/plot-mesh.gp) from a quick mesh run's bench-mesh.csv: written, and its
# last panel (contacts, closest, builds) has room above and below every bar. A made-up CSV whose
# smallest time is exactly a decade (1 ms) first.
MH=workload,triangles,pose,pose_distance,query,precision,threads,poses,margin,value,ms,ms_min,pair_tests
MH=$MH,node_tests,fcl_ms,fcl_ms_min,fcl_bv_tests,fcl_leaf_tests,speedup_vs_fcl,diff,disagree
{
    echo "$MH"
    echo "m,10,-,,build,double,1,1,,5,1,1,,,10,10,,,10,,0"
    echo "m,10,near,0.01,contacts,double,1,1,0.05,7,2,2,,,100,100,,,50,0,0"
    echo "m,10,near,0.01,distance,double,1,1,,0.01,0.01,0.01,3,4,0.1,0.1,5,6,10,0,0"
} > "$DIR/mesh-decade.csv"
PLOT=$(dirname "$PLOT")/plot-mesh.gp
check mesh_bar_on_a_decade "$DIR/mesh-decade.csv"
"$TTD" bench --quick --quiet --no-probes --no-fcl --mesh-workloads icosphere --out "$DIR/mesh" > /dev/null ||
    fail "ttd bench (mesh) exited with $?"
check mesh_quick_run "$DIR/mesh/bench-mesh.csv"
exit 0
