#!/usr/bin/env bash
# Builds the tests that call the library from several threads (test_determinism: six
# concurrent callers with worker threads; test_api: threads_identical; test_scene's queries on
# two threads of a scene's pool, kept across steps and scenes, each body's nearest best first
# on them; test_pool: calls on the pool itself, back to back and after its threads slept;
# test_scene_contacts: manifolds on four threads, their reductions and the meshes' edge
# information made on first use; test_mesh_self: a self query's
# sub-walks on 2 threads; test_mesh_deform: a refit's subtrees on 2 and 9 threads;
# test_points_inside: four threads' first point queries on one fresh mesh and on one moved by
# ttd_mesh_set_vertices, 2 workers each), and Python's threaded point queries against
# Mesh.set_vertices (python/tests/test_deform.py), with ThreadSanitizer, and runs them. Skips with a message where ThreadSanitizer cannot run (some kernels' address
# space layouts make its runtime refuse to start).
# Usage: scripts/test-tsan.sh      (build folder: build-tsan/, or $TTD_TSAN_BUILD_DIR)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${TTD_TSAN_BUILD_DIR:-build-tsan}
jobs=$(nproc 2>/dev/null || echo 2)
probe_dir=$(mktemp -d)
trap 'rm -rf "$probe_dir"' EXIT
printf '#include <pthread.h>\nstatic void *f(void *a) { return a; }\nint main(void) { pthread_t t; pthread_create(&t, 0, f, 0); return pthread_join(t, 0); }\n' > "$probe_dir/p.c"
if ! { cc -fsanitize=thread -pthread "$probe_dir/p.c" -o "$probe_dir/p" && "$probe_dir/p"; } > /dev/null 2>&1; then
    echo "test-tsan.sh: SKIPPED: ThreadSanitizer programs do not build or run on this machine"
    exit 0
fi
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTTD_BUILD_CLI=OFF \
    -DCMAKE_C_FLAGS="-fsanitize=thread" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" > /dev/null
cmake --build "$build" -j "$jobs" --target test_determinism test_api test_scene test_scene_contacts test_mesh_self test_mesh_deform \
    test_points_inside test_ccd test_ccd_lanes test_mesh_ccd test_scene_ccd test_pool
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1}
"$build/tests/test_determinism"
"$build/tests/test_api" threads
"$build/tests/test_scene" collide_across_steps
"$build/tests/test_scene" closest_pair_order
"$build/tests/test_scene" sparse_scene_distances
# the scene's pool itself: calls back to back, after its threads slept, pools destroyed at once
"$build/tests/test_pool"
"$build/tests/test_scene_contacts" edges_made_on_first_use
# self-contacts' sub-walks on 2 threads, and refits of one tree's subtrees on 2 and 9 threads
"$build/tests/test_mesh_self" self_queries_threads
# four self-contact queries at once on one mesh (its kept arrays taken by one at a time)
"$build/tests/test_mesh_self" self_queries_concurrent
"$build/tests/test_mesh_deform" refit_bits
# the point data, winding moments and closedness made on first use by four threads at once, and
# made again by four threads at once after ttd_mesh_set_vertices (a refit, then a rebuild)
"$build/tests/test_points_inside" concurrent_first_use
"$build/tests/test_points_inside" concurrent_after_update
# continuous collision's batches on 1, 2 and all threads
"$build/tests/test_ccd" threads_and_precision
# the batches with the screen in lanes (triangles: 15 sub-queries a pair) on 1, 2 and 3 threads
"$build/tests/test_ccd_lanes" triangles
# mesh CCD's walk on 1, 2, 3 and 8 threads (each worker's hits and earliest, joined at the end)
"$build/tests/test_mesh_ccd" threads
# a scene's rigid CCD: body pairs on 1, 2 and 3 threads of the scene's pool
"$build/tests/test_scene_ccd" against_brute

# Python's threaded test of the point queries against a concurrent Mesh.set_vertices (the binding
# refuses the overlap: python/tests/test_deform.py), its extension built with ThreadSanitizer
# against this folder's library and run in Debian's python with the runtime preloaded (python
# itself is not instrumented: the extension's and the library's accesses are checked, the GIL's
# locks seen through their interceptors). With the binding's guard removed it reports the refit's
# writes racing the point data's reads. Skipped, with a message, where python, numpy or pytest is
# missing or python does not start under the runtime.
py=${TTD_PYTHON:-/usr/bin/python3}
tsan_rt=$(cc -print-file-name=libtsan.so)
if ! "$py" -c "import numpy, pytest, setuptools" > /dev/null 2>&1; then
    echo "test-tsan.sh: SKIPPED the Python threaded test: $py lacks numpy, pytest or setuptools (scripts/test-python.sh installs them)"
elif ! LD_PRELOAD=$tsan_rt "$py" -c "import numpy" > /dev/null 2>&1; then
    echo "test-tsan.sh: SKIPPED the Python threaded test: $py does not start with $tsan_rt preloaded"
else
    build_abs=$(cd "$build" && pwd)
    pybuild=$build_abs/python
    (cd python && TTD_CMAKE_BUILD_DIR="$build_abs" TTD_PYTHON_BUILD_BASE="$pybuild" CFLAGS=-fsanitize=thread \
        LDFLAGS=-fsanitize=thread "$py" setup.py -q build > "$pybuild.log" 2>&1) || { cat "$pybuild.log"; exit 1; }
    # -s: a report goes to standard error before the runtime ends the process (pytest's capture
    # would lose it)
    LD_PRELOAD=$tsan_rt PYTHONPATH=$(echo "$pybuild"/lib.*) PYTHONDONTWRITEBYTECODE=1 \
        "$py" -m pytest -q -s -p no:cacheprovider python/tests/test_deform.py -k point_queries_and_set_vertices
fi
