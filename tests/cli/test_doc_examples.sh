#!/bin/sh
# The examples of docs/mesh-files.md run as written: every '$ ttd ...' line of its fenced blocks
# is run in docs/examples/ (the files it names live there), and its output must be the lines
# shown after it, up to the next '$' line or the end of the block.
# Usage: test_doc_examples.sh /path/to/ttd
TTD=${1:?usage: test_doc_examples.sh /path/to/ttd}
HERE=$(cd "$(dirname "$0")" && pwd)
DOC="$HERE/../../docs/mesh-files.md"
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
# Split the page into DIR/cmd.N (the command, without '$ ttd ') and DIR/want.N.
awk -v dir="$DIR" '
    /^```/ { inblock = !inblock; n_open = 0; next }
    inblock && /^\$ ttd / { n++; sub(/^\$ ttd /, ""); print > (dir "/cmd." n); printf "" > (dir "/want." n); next }
    inblock && n && !/^\$/ { print >> (dir "/want." n) }
    END { print n + 0 > (dir "/count") }' "$DOC"
count=$(cat "$DIR/count")
[ "$count" -ge 3 ] || fail "found only $count examples in $DOC"
i=1
while [ "$i" -le "$count" ]; do
    cmd=$(cat "$DIR/cmd.$i")
    (cd "$HERE/../../docs/examples" && eval "\"\$TTD\" $cmd") > "$DIR/got.$i" 2> "$DIR/err.$i" ||
        fail "ttd $cmd: status $?: $(cat "$DIR/err.$i")"
    cmp -s "$DIR/got.$i" "$DIR/want.$i" || fail "ttd $cmd: printed
$(cat "$DIR/got.$i")
where docs/mesh-files.md shows
$(cat "$DIR/want.$i")"
    i=$((i + 1))
done
echo "ok   $count examples of docs/mesh-files.md print what the page shows"
