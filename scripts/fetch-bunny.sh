#!/usr/bin/env bash
# Fetches the Stanford bunny for ttd's mesh benchmark and prints the path of an OBJ file.
#
# The mesh is the Stanford bunny of the Stanford 3D Scanning Repository (Greg Turk and Marc
# Levoy, 1994; https://graphics.stanford.edu/data/3Dscanrep/), in the reduced version packaged
# by Mikola Lysenko as the npm package `bunny` 1.0.1, whose package.json declares the licence
# "Public Domain". It holds 1,839 vertices and 3,674 triangles. It is installed with npm into a
# cache folder and converted to OBJ by scripts/bunny-to-obj.js; a second run reuses the file.
# Tests never need it (nor the network); the benchmark does.
#
# Usage: scripts/fetch-bunny.sh      (cache: build/data/, or $TTD_DATA_DIR)
# Prints the OBJ's path on standard output; progress and errors go to standard error. Exits 1
# with a message when node or npm is missing or the package cannot be installed (no network).
set -euo pipefail
cd "$(dirname "$0")/.."
data=${TTD_DATA_DIR:-build/data}
obj="$data/bunny.obj"
want_v=1839
want_t=3674

fail() { echo "fetch-bunny.sh: $*" >&2; exit 1; }

counts() { # vertices and triangles of an OBJ written by bunny-to-obj.js
    echo "$(grep -c '^v ' "$1") $(grep -c '^f ' "$1")"
}

if [ -s "$obj" ] && [ "$(counts "$obj")" = "$want_v $want_t" ]; then
    echo "$obj"
    exit 0
fi

command -v node > /dev/null 2>&1 || fail "node is not installed (needed to convert the npm package bunny)"
command -v npm > /dev/null 2>&1 || fail "npm is not installed (needed to fetch the npm package bunny)"
mkdir -p "$data/npm"
echo "fetch-bunny.sh: installing the npm package bunny@1.0.1 into $data/npm" >&2
if ! npm install --prefix "$data/npm" --no-save --no-package-lock --no-audit --no-fund \
        --fetch-retries=1 --fetch-retry-maxtimeout=10000 bunny@1.0.1 \
        > "$data/npm-install.log" 2>&1; then
    tail -n 5 "$data/npm-install.log" >&2
    fail "npm could not install bunny@1.0.1 (no network, or the registry is unreachable); log: $data/npm-install.log"
fi
node scripts/bunny-to-obj.js "$data/npm/node_modules/bunny" "$obj.tmp" ||
    fail "converting the package to OBJ failed"
got=$(counts "$obj.tmp")
[ "$got" = "$want_v $want_t" ] ||
    fail "expected $want_v vertices and $want_t triangles, the package gave $got (a different version?)"
mv "$obj.tmp" "$obj"
echo "$obj"
