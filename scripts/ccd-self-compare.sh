#!/bin/sh
# Old against new on the self-CCD closing steps of `ttd bench ccd` (docs/ccd-speed.md, issue 34):
# runs two ttd binaries in turn, ROUNDS times, on the same arguments, and prints each run's mean CPU
# time a closing step, the ratio old/new of the sums, and whether every step's digest (toi and the
# pair list, bit for bit) agrees. The load is printed before and after (timings on a shared machine).
#   scripts/ccd-self-compare.sh OLD_TTD NEW_TTD [ROUNDS [bench args...]]
# default bench args: --closing-only --reps 1 (the 60 closing steps of the 100,352-triangle sheet).
set -eu
old=$1
new=$2
rounds=${3:-3}
shift 2
[ $# -gt 0 ] && shift
[ $# -gt 0 ] || set -- --closing-only --reps 1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
i=1
while [ "$i" -le "$rounds" ]; do
    "$old" bench ccd "$@" >"$tmp/old.$i"
    "$new" bench ccd "$@" >"$tmp/new.$i"
    o=$(sed -n 's/^mean of the .* closing steps: .* wall, \([0-9.]*\) ms CPU.*/\1/p' "$tmp/old.$i" | head -1)
    n=$(sed -n 's/^mean of the .* closing steps: .* wall, \([0-9.]*\) ms CPU.*/\1/p' "$tmp/new.$i" | head -1)
    echo "round $i: old $o ms, new $n ms CPU a closing step (mean)"
    echo "$o $n" >>"$tmp/sums"
    i=$((i + 1))
done
awk '{o += $1; n += $2} END {printf "old/new (sums over the rounds): %.2f\n", o / n}' "$tmp/sums"
# the digest column: the last field of each step row
awk '/ -> / {print $1, $3, $NF}' "$tmp/old.1" >"$tmp/dig.old"
awk '/ -> / {print $1, $3, $NF}' "$tmp/new.1" >"$tmp/dig.new"
if cmp -s "$tmp/dig.old" "$tmp/dig.new"; then
    echo "digests: every step the same ($(wc -l <"$tmp/dig.new") steps)"
else
    echo "digests DIFFER:"
    diff "$tmp/dig.old" "$tmp/dig.new" || true
fi
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
