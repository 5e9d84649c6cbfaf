#!/usr/bin/env bash
# The README's run command: installs what the benchmark needs when it can (FCL to compare
# against, Bullet beside the scene section, gnuplot for the figure), builds ttd in Release (build/, or $TTD_BUILD_DIR), runs
# `ttd bench`, and writes results/ (or $TTD_RESULTS_DIR): bench.txt (the table), bench.json,
# bench.csv, figure.svg/.png and figure-sizes.svg/.png, for the mesh section bench-mesh.csv
# and figure-mesh.svg/.png, and for the scene section bench-scene.csv (it fetches the Stanford
# bunny first with scripts/fetch-bunny.sh when it can: the mesh and scene sections use it). The table is printed as it is run.
# Usage: scripts/bench.sh [ttd bench options]     e.g. scripts/bench.sh --quick
#        TTD_BENCH_NICE=-15 scripts/bench.sh       (raise the benchmark's priority, see below)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${TTD_BUILD_DIR:-build}
out=${TTD_RESULTS_DIR:-results}
jobs=$(nproc 2>/dev/null || echo 2)

# Optional packages: FCL (libfcl-dev), Bullet (libbullet-dev: its GImpact manifolds beside the
# scene section's) and gnuplot (gnuplot-nox). Missing ones are installed with apt-get when this
# runs as root (or with password-less sudo); otherwise we carry on (scripts/install-optional.sh).
missing=()
if ! { [ -f /usr/include/fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h ] ||
       pkg-config --exists fcl 2>/dev/null; }; then
  missing+=(libfcl-dev)
fi
if ! { [ -f /usr/include/bullet/btBulletCollisionCommon.h ] || pkg-config --exists bullet 2>/dev/null; }; then
  missing+=(libbullet-dev)
fi
command -v gnuplot >/dev/null 2>&1 || missing+=(gnuplot-nox)
# The point queries' comparison (ttd bench points): Embree, CGAL and Open3D (Debian's python3).
[ -f /usr/include/embree3/rtcore.h ] || missing+=(libembree-dev)
[ -f /usr/include/CGAL/AABB_tree.h ] || missing+=(libcgal-dev)
{ [ -x /usr/bin/python3 ] && /usr/bin/python3 -c "import open3d" >/dev/null 2>&1; } || missing+=(python3-open3d)
scripts/install-optional.sh bench.sh "${missing[@]}"

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release ${TTD_CMAKE_ARGS:-} >&2
cmake --build "$build" -j "$jobs" >&2
ttd="$build/cli/ttd"
[ -x "$ttd" ] || { echo "bench.sh: $ttd was not built" >&2; exit 1; }

mkdir -p "$out"
# The Stanford bunny for the mesh workloads (npm package bunny, converted to OBJ; cached in
# $build/data). --quick does not use it (generated meshes only) and so does not fetch it; without
# it (no node, npm or network) the benchmark says so and goes on with the generated meshes.
# The scene section uses it too (the bunnies and mixed scenes).
want_bunny=1
case " $* " in
  *" --no-mesh "*" --no-scene "* | *" --no-scene "*" --no-mesh "*) want_bunny=0 ;;
  *" --quick "*) case " $* " in *" --mesh-workloads "* | *" --scene-workloads "*) ;; *) want_bunny=0 ;; esac ;;
esac
if [ "$want_bunny" = 1 ] && [ -z "${TTD_BUNNY:-}" ]; then
  if bunny=$(TTD_DATA_DIR="${TTD_DATA_DIR:-$build/data}" scripts/fetch-bunny.sh); then
    export TTD_BUNNY="$bunny"
  else
    echo "bench.sh: the Stanford bunny could not be fetched; the mesh section goes on without it" >&2
  fi
fi
# On a shared machine other work inflates the timings. TTD_BENCH_NICE=-15 (root only) runs the
# benchmark in its own scheduler autogroup at that priority: with autogroups on, nice alone
# only ranks processes within one session, not against other sessions' processes.
if [ -n "${TTD_BENCH_NICE:-}" ]; then
  setsid bash -c 'if [ -w /proc/self/autogroup ]; then echo "$1" > /proc/self/autogroup; fi; shift; exec nice -n "$0" "$@"' \
    "$TTD_BENCH_NICE" "$TTD_BENCH_NICE" "$ttd" bench --out "$out" "$@"
else
  "$ttd" bench --out "$out" "$@"
fi

# The point queries against Embree, CGAL and Open3D (those found), into points.txt
# (TTD_BENCH_POINTS=0 leaves them out).
if [ "${TTD_BENCH_POINTS:-1}" != 0 ]; then
  points_args=()
  case " $* " in *" --quick "*) points_args=(--quick) ;; esac
  "$ttd" bench points "${points_args[@]}" > "$out/points.txt" || echo "bench.sh: ttd bench points failed" >&2
fi

if command -v gnuplot >/dev/null 2>&1; then
  if [ "$(wc -l < "$out/bench.csv")" -le 1 ]; then
    echo "bench.sh: no pair rows (only mesh workloads were run): figure.svg/.png not drawn" >&2
  elif gnuplot -e "csv='$out/bench.csv'; out='$out/figure'" bench/plot.gp; then
    echo "bench.sh: wrote $out/bench.txt, $out/bench.json, $out/bench.csv and the figure $out/figure.svg/.png" >&2
  else
    echo "bench.sh: gnuplot failed; the figure is missing (results are in $out/)" >&2
  fi
  if [ -s "$out/bench-mesh.csv" ]; then
    if gnuplot -e "csv='$out/bench-mesh.csv'; out='$out/figure-mesh'" bench/plot-mesh.gp; then
      echo "bench.sh: wrote $out/bench-mesh.csv and the mesh figure $out/figure-mesh.svg/.png" >&2
    else
      echo "bench.sh: gnuplot failed on the mesh figure; it is missing (results are in $out/)" >&2
    fi
  fi
else
  echo "bench.sh: gnuplot not found, figure skipped (apt-get install gnuplot-nox); results are in $out/" >&2
fi
