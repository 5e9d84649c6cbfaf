#!/bin/sh
# The examples of docs/mesh-files.md and docs/mass-properties.md run as written: every '$ ttd ...'
# line of their fenced blocks is run in docs/examples/ (the files they name live there), and its
# output must be the lines shown after it, up to the next '$' line or the end of the block.
# Usage: test_doc_examples.sh /path/to/ttd
TTD=${1:?usage: test_doc_examples.sh /path/to/ttd}
HERE=$(cd "$(dirname "$0")" && pwd)
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
# doc_examples PAGE MIN: runs the examples of docs/PAGE, which must hold at least MIN.
doc_examples() {
    DOC="$HERE/../../docs/$1"
    rm -f "$DIR"/cmd.* "$DIR"/want.* "$DIR"/got.* "$DIR"/err.*
    # Split the page into DIR/cmd.N (the command, without '$ ttd ') and DIR/want.N.
    awk -v dir="$DIR" '
        /^```/ { inblock = !inblock; n_open = 0; next }
        inblock && /^\$ ttd / { n++; sub(/^\$ ttd /, ""); print > (dir "/cmd." n); printf "" > (dir "/want." n); next }
        inblock && n && !/^\$/ { print >> (dir "/want." n) }
        END { print n + 0 > (dir "/count") }' "$DOC"
    count=$(cat "$DIR/count")
    [ "$count" -ge "$2" ] || fail "found only $count examples in $DOC"
    i=1
    while [ "$i" -le "$count" ]; do
        cmd=$(cat "$DIR/cmd.$i")
        (cd "$HERE/../../docs/examples" && eval "\"\$TTD\" $cmd") > "$DIR/got.$i" 2> "$DIR/err.$i" ||
            fail "ttd $cmd: status $?: $(cat "$DIR/err.$i")"
        cmp -s "$DIR/got.$i" "$DIR/want.$i" || fail "ttd $cmd: printed
$(cat "$DIR/got.$i")
where docs/$1 shows
$(cat "$DIR/want.$i")"
        i=$((i + 1))
    done
    echo "ok   $count examples of docs/$1 print what the page shows"
}
doc_examples mesh-files.md 3
doc_examples mass-properties.md 2

# ---- README.md: every fenced block runs as written ------------------------------------------
# Each block is cut out of the README as it stands. The C blocks are one program, app.c, in
# order; it is built by the README's own link block (an install into a temporary prefix, then
# pkg-config) and run. The shell blocks run with `sh -e` in a folder laid out as the
# repository's (build/ the build under test, docs/examples/ copied, app.c), so each command's
# status must be 0. Not run here: the Python blocks and the Python install and wheel blocks (run by
# python/tests/test_readme.py, which needs the Python package), and the block of the two
# commands scripts/bench.sh and scripts/test.sh (this test is part of the second; the scripts
# must exist and be executable).
README="$HERE/../../README.md"
REPO=$(cd "$HERE/../.." && pwd)
BUILD=$(cd "$(dirname "$TTD")/.." && pwd)
W="$DIR/readme"
mkdir -p "$W/blocks" "$W/work/docs"
awk -v dir="$W/blocks" '
    /^```/ { if (!inblock) { inblock = 1; n++; lang = substr($0, 4); if (lang == "") lang = "sh"
                             file = sprintf("%s/%02d.%s", dir, n, lang); printf "" > file }
             else { inblock = 0; close(file) }
             next }
    inblock { print >> file }
    END { if (inblock) { print "unterminated block" > "/dev/stderr"; exit 1 } }' "$README" || fail "README.md: cannot cut its blocks"
cp -R "$REPO/docs/examples" "$W/work/docs/"
ln -s "$BUILD" "$W/work/build"
cat "$W"/blocks/*.c > "$W/work/app.c"
[ -s "$W/work/app.c" ] || fail "README.md: no C block"
ran=0; deferred=0
for b in "$W"/blocks/*; do
    case $b in
        *.c) continue ;;
        *.python) deferred=$((deferred + 1)); continue ;;
        *.sh) ;;
        *) fail "README.md: block $(basename "$b") in an unknown language" ;;
    esac
    if grep -q '^scripts/bench.sh' "$b"; then
        for s in $(awk '{ print $1 }' "$b"); do [ -x "$REPO/$s" ] || fail "README.md names $s, which is not an executable script"; done
        continue
    fi
    if grep -q 'python3 -m venv\|pip wheel' "$b"; then deferred=$((deferred + 1)); continue; fi
    # The link block as written needs pkg-config, and a plain program cannot link a sanitized
    # library (scripts/test-sanitize.sh leaves ttd.install out for that reason): then app.c is
    # built against the build's archive, with the sanitizers where the build has them.
    san=""
    grep -q '^TTD_SANITIZE:BOOL=ON' "$BUILD/CMakeCache.txt" 2> /dev/null && san="-fsanitize=address,undefined"
    if grep -q 'pkg-config' "$b" && { [ -n "$san" ] || ! command -v pkg-config > /dev/null 2>&1; }; then
        why="pkg-config not installed (apt-get install pkg-config)"
        [ -n "$san" ] && why="a sanitizer build (a plain program cannot link its libttd.so)"
        echo "skip README.md block $(basename "$b"): $why; app.c built against the archive instead"
        # shellcheck disable=SC2086 # no flags or one
        cc $san "$W/work/app.c" -I"$REPO/include" "$(find "$BUILD" -name libttd.a | head -n 1)" -lm -lpthread \
            -o "$W/work/app" || fail "README.md: app.c does not build"
        "$W/work/app" > "$W/out" || fail "README.md: app.c: status $?"
        cp "$W/out" "$W/app.out"
        ran=$((ran + 1)); continue
    fi
    (cd "$W/work" && sh -e "$b") > "$W/out" 2> "$W/err" || fail "README.md block:
$(cat "$b")
exited with status $?: $(cat "$W/err")"
    grep -q 'pkg-config' "$b" && cp "$W/out" "$W/app.out"
    ran=$((ran + 1))
done
[ "$ran" -ge 4 ] && [ "$deferred" -ge 2 ] || fail "README.md: ran $ran shell blocks and left $deferred to Python: fewer than expected"
# app.c printed what its blocks compute: 2 for the pair, 2 and 1 for the batch, the meshes
# crossing (distance 0), the scene's manifold.
[ -f "$W/app.out" ] || fail "README.md: app.c was not run"
grep -q '^2 between (0 0 0) and (0 0 2)$' "$W/app.out" && grep -q '^batch: 2 1$' "$W/app.out" &&
    grep -q '^meshes: distance 0, [1-9][0-9]* contact pairs$' "$W/app.out" && grep -q '^scene: [1-9][0-9]* manifold points$' "$W/app.out" ||
    fail "README.md: app.c printed $(cat "$W/app.out")"
echo "ok   README.md: its C program built and run, $ran shell blocks run, $deferred Python blocks left to python/tests/test_readme.py"

# ---- the documents' index ---------------------------------------------------------------------
# docs/README.md links every document of docs/ (each on its own line), the README's "Where things
# are" names the index and docs/anchors.md, and no document names a program under /tmp (a
# throwaway that is not in the repository: such programs live in the repository, or the page says
# in words what was measured).
DOCS="$REPO/docs"
for d in "$DOCS"/*.md; do
    name=$(basename "$d")
    [ "$name" = README.md ] && continue
    grep -q "](${name})" "$DOCS/README.md" || fail "docs/README.md does not name docs/$name"
done
where=$(sed -n '/^## Where things are/,/^## /p' "$README")
for name in docs/README.md docs/anchors.md; do
    printf '%s\n' "$where" | grep -q "]($name)" || fail "README.md's 'Where things are' does not name $name"
done
tmp_refs=$(grep -n '/tmp/' "$README" "$REPO/python/README.md" "$DOCS"/*.md || true)
[ -z "$tmp_refs" ] || fail "documents name paths under /tmp: $tmp_refs"
echo "ok   docs/README.md names every document; README names it and docs/anchors.md; no /tmp paths in the docs"
