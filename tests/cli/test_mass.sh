#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd mesh mass A` on meshes this script writes, against values known by construction:
#   - a box a x b x c turned about z by the rotation (3/5, 4/5) and moved away from the origin,
#     density rho: mass rho abc, volume abc ('outward'), area 2(ab + bc + ca), centre R (a, b, c)/2 + t,
#     inertia R diag(m (b^2 + c^2)/12, m (a^2 + c^2)/12, m (a^2 + b^2)/12) R^T, each computed here in
#     awk from the box's sides (not from the mesh) and compared to 1e-12 of the quantity's size;
#   - the same box with every face reversed: volume -abc ('inward'), the same mass, area, centre
#     and inertia; as an ASCII STL (no shared vertices: closed by places) the same output as the OBJ;
#   - --json: one object whose numbers are the text output's, in order (and JSON where python3 is
#     there to parse it); --precision float rounds the coordinates once to float (a cube of side
#     0.1: volume float(0.1)^3, not 0.001); a doubled sheet: volume 0 'flat', centre nan (JSON null);
#   - errors: a missing file, a malformed one (named with its line), an open mesh and one with a
#     face turned ('not closed', exit 1); a density that is nan, inf, 0, negative or not a
#     number, unknown options, a missing or extra operand (exit 2); nothing on standard output
#     then, and --help exits 0.
# Only POSIX sh and awk. Usage: sh test_mass.sh path/to/ttd
set -u
TTD=${1:?usage: test_mass.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

# ---- the box, and its expected values --------------------------------------------------------
# Sides a, b, c; pose x = R q + t, R the rotation about z with cos 3/5, sin 4/5. Corner k of the box
# is q = (a (k & 1), b (k >> 1 & 1), c (k >> 2 & 1)); the six faces are counter-clockwise seen from
# outside (0-based corner numbers). flip=1 writes every face reversed; stl=1 writes an ASCII STL.
A=2 B=0.75 C=1.5 TX=3 TY=-1.25 TZ=0.5 RHO=2.5
box() { # flip stl
    awk -v a=$A -v b=$B -v c=$C -v tx=$TX -v ty=$TY -v tz=$TZ -v flip="$1" -v stl="$2" 'BEGIN {
        for (k = 0; k < 8; k++) {
            qx = a * (k % 2); qy = b * (int(k / 2) % 2); qz = c * int(k / 4)
            X[k] = 0.6 * qx - 0.8 * qy + tx; Y[k] = 0.8 * qx + 0.6 * qy + ty; Z[k] = qz + tz
        }
        split("0 2 3 1|4 5 7 6|0 1 5 4|2 6 7 3|0 4 6 2|1 3 7 5", F, "|")
        if (!stl) for (k = 0; k < 8; k++) printf "v %.17g %.17g %.17g\n", X[k], Y[k], Z[k]
        else print "solid box"
        for (f = 1; f <= 6; f++) {
            split(F[f], q, " ")
            if (flip) { t = q[2]; q[2] = q[4]; q[4] = t }
            if (!stl) { printf "f %d %d %d %d\n", q[1] + 1, q[2] + 1, q[3] + 1, q[4] + 1; continue }
            for (h = 0; h < 2; h++) { # the quad fanned as the OBJ reader does: (0 1 2) (0 2 3)
                printf "facet normal 0 0 0\nouter loop\n"
                printf "vertex %.17g %.17g %.17g\n", X[q[1]], Y[q[1]], Z[q[1]]
                printf "vertex %.17g %.17g %.17g\n", X[q[2 + h]], Y[q[2 + h]], Z[q[2 + h]]
                printf "vertex %.17g %.17g %.17g\n", X[q[3 + h]], Y[q[3 + h]], Z[q[3 + h]]
                printf "endloop\nendfacet\n"
            }
        }
        if (stl) print "endsolid box"
    }'
}
box 0 0 > "$DIR/box.obj"
box 1 0 > "$DIR/inward.obj"
box 0 1 > "$DIR/box.stl"
box 1 1 > "$DIR/inward.stl"
# Expected output lines, as the command prints them (the volume's sign and word by flip).
awk -v a=$A -v b=$B -v c=$C -v tx=$TX -v ty=$TY -v tz=$TZ -v rho=$RHO 'BEGIN {
    v = a * b * c; m = rho * v
    R[0,0] = 0.6; R[0,1] = -0.8; R[0,2] = 0; R[1,0] = 0.8; R[1,1] = 0.6; R[1,2] = 0; R[2,0] = 0; R[2,1] = 0; R[2,2] = 1
    D[0] = m * (b * b + c * c) / 12; D[1] = m * (a * a + c * c) / 12; D[2] = m * (a * a + b * b) / 12
    h[0] = a / 2; h[1] = b / 2; h[2] = c / 2; t[0] = tx; t[1] = ty; t[2] = tz
    printf "mass %.17g\nvolume %.17g\narea %.17g\ncenter", m, v, 2 * (a * b + b * c + c * a)
    for (i = 0; i < 3; i++) printf " %.17g", R[i,0] * h[0] + R[i,1] * h[1] + R[i,2] * h[2] + t[i]
    printf "\n"
    for (i = 0; i < 3; i++) {
        printf "inertia"
        for (j = 0; j < 3; j++) printf " %.17g", R[i,0] * D[0] * R[j,0] + R[i,1] * D[1] * R[j,1] + R[i,2] * D[2] * R[j,2]
        printf "\n"
    }
}' > "$DIR/want"

# Compares got ($1) with want ($2), line by line and number by number: each number within 1e-12
# (or $5) of the largest magnitude of its line (of the tensor for the inertia); the volume's sign
# and word against $3 (outward or inward); $4 names the case.
check() {
    si=$(awk '$1 == "inertia" { for (k = 2; k <= 4; k++) { x = $k < 0 ? -$k : $k; if (x > s) s = x } } END { print s + 0 }' "$2")
    awk -v orient="$3" -v name="$4" -v si="$si" -v tol="${5:-1e-12}" '
        function abs(x) { return x < 0 ? -x : x }
        NR == FNR { wl[FNR] = $0; nlw = FNR; next }
        {
            ng = split($0, g, " "); nw = split(wl[FNR], w, " ")
            if (g[1] != w[1]) { print name ": line " FNR " is \"" $0 "\", want \"" wl[FNR] "\""; bad = 1; exit }
            if (g[1] == "volume") { # the word after the signed volume
                if (ng != 3 || g[3] != orient) { print name ": \"" $0 "\": want the word " orient; bad = 1; exit }
                ng = 2; if (orient == "inward") w[2] = -w[2]
            }
            if (ng != nw) { print name ": \"" $0 "\" has " ng " fields, want " nw; bad = 1; exit }
            size = 0; for (k = 2; k <= nw; k++) if (abs(w[k]) > size) size = abs(w[k])
            if (g[1] == "inertia") size = si # the tensor'"'"'s entries against its largest
            for (k = 2; k <= nw; k++)
                if (!(abs(g[k] - w[k]) <= tol * size)) {
                    printf "%s: %s field %d is %s, want %.17g\n", name, g[1], k - 1, g[k], w[k]; bad = 1; exit
                }
            lines = FNR
        }
        END { if (!bad && lines != nlw) { print name ": " lines " lines, want " nlw; bad = 1 } exit bad }
    ' "$2" "$1" >&2 || fail "$4"
}

# ---- the box, outward and inward, OBJ and STL -----------------------------------------------
"$TTD" mesh mass "$DIR/box.obj" --density $RHO > "$DIR/got" 2> "$DIR/err" || fail "box.obj: status $?: $(cat "$DIR/err")"
[ -s "$DIR/err" ] && fail "box.obj: said on stderr: $(cat "$DIR/err")"
check "$DIR/got" "$DIR/want" outward "box.obj"
pass "box: mass, volume, area, centre and inertia by the formulas"
"$TTD" mesh mass "$DIR/inward.obj" --density=$RHO > "$DIR/got.in" || fail "inward.obj: status $?"
check "$DIR/got.in" "$DIR/want" inward "inward.obj"
# The mass, area and centre are the same bits (the inertia's off-diagonal rounding may differ:
# the terms come in another order), and the volume is negated exactly.
[ "$(grep -v '^volume \|^inertia ' "$DIR/got")" = "$(grep -v '^volume \|^inertia ' "$DIR/got.in")" ] ||
    fail "inward box: mass, area or centre differ from the outward box's"
v_out=$(awk '$1 == "volume" { print $2 }' "$DIR/got"); v_in=$(awk '$1 == "volume" { print $2 }' "$DIR/got.in")
[ "$v_in" = "-$v_out" ] || fail "inward box: volume $v_in, outward $v_out"
pass "box turned inside out: negative volume, 'inward', the same mass, area, centre and inertia"
"$TTD" mesh mass "$DIR/box.stl" --density $RHO > "$DIR/got.stl" || fail "box.stl: status $?"
cmp -s "$DIR/got" "$DIR/got.stl" || fail "box.stl (no shared vertices) differs from box.obj: $(cat "$DIR/got.stl")"
"$TTD" mesh mass "$DIR/inward.stl" --density $RHO > "$DIR/got.stl" || fail "inward.stl: status $?"
cmp -s "$DIR/got.in" "$DIR/got.stl" || fail "inward.stl differs from inward.obj"
"$TTD" mesh mass - --density $RHO < "$DIR/box.obj" > "$DIR/got.stdin" || fail "stdin: status $?"
cmp -s "$DIR/got" "$DIR/got.stdin" || fail "standard input differs from the file"
# The default density is 1: the mass is the volume, the inertia rho times smaller.
"$TTD" mesh mass "$DIR/box.obj" > "$DIR/got.1" || fail "density 1: status $?"
awk -v rho=$RHO '$1 == "mass" || $1 == "inertia" { for (k = 2; k <= NF; k++) $k = sprintf("%.17g", $k / rho) } { print }' "$DIR/want" > "$DIR/want.1"
check "$DIR/got.1" "$DIR/want.1" outward "default density"
pass "ASCII STL (closed by places), standard input, default density"

# ---- --json ------------------------------------------------------------------------------------
"$TTD" mesh mass "$DIR/inward.obj" --json --density $RHO > "$DIR/json" || fail "--json: status $?"
[ "$(wc -l < "$DIR/json")" -eq 1 ] || fail "--json: not one line: $(cat "$DIR/json")"
# Its keys in order, and its numbers those of the text output (density first).
keys=$(tr -c 'a-z"\n' ' ' < "$DIR/json" | tr ' ' '\n' | grep '^"' | tr '\n' ' ')
[ "$keys" = '"density" "mass" "volume" "orientation" "inward" "area" "center" "inertia" ' ] || fail "--json keys: $keys"
nums=$(tr '[]{},:' '      ' < "$DIR/json" | tr ' ' '\n' | grep -v '^"' | grep . | tr '\n' ' ')
text=$( (echo $RHO; awk '{ for (k = 2; k <= NF; k++) if ($k != "inward") print $k }' "$DIR/got.in") | tr '\n' ' ')
[ "$nums" = "$text" ] || fail "--json numbers '$nums', text '$text'"
if command -v python3 > /dev/null 2>&1; then
    python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d["volume"] < 0 and len(d["inertia"]) == 3' "$DIR/json" ||
        fail "--json: not JSON python3 reads: $(cat "$DIR/json")"
fi
pass "--json: the same numbers, in order"

# ---- --precision float ----------------------------------------------------------------------------
# A cube of side 0.1 at the origin: float reads 0.1 as 13421773 / 2^27, so the volume is its cube.
awk 'BEGIN { for (k = 0; k < 8; k++) printf "v %s %s %s\n", (k % 2) ? "0.1" : "0", (int(k / 2) % 2) ? "0.1" : "0", int(k / 4) ? "0.1" : "0"
             print "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6" }' > "$DIR/small.obj"
vf=$("$TTD" mesh mass "$DIR/small.obj" --precision float | awk '$1 == "volume" { print $2 }') || fail "float: status"
vd=$("$TTD" mesh mass "$DIR/small.obj" --precision double | awk '$1 == "volume" { print $2 }') || fail "double: status"
awk -v vf="$vf" -v vd="$vd" 'BEGIN { s = 13421773 / 134217728; e = s * s * s
    if (!((vf - e) / e < 1e-14 && (e - vf) / e < 1e-14)) { print "float volume " vf ", want " e; exit 1 }
    if (!((vd - 0.001) / 0.001 < 1e-14 && (0.001 - vd) / 0.001 < 1e-14)) { print "double volume " vd ", want 0.001"; exit 1 }
    if (vf == vd) { print "float and double gave the same volume " vf; exit 1 } }' >&2 || fail "--precision"
"$TTD" mesh mass "$DIR/box.obj" --density $RHO --precision float > "$DIR/got.f" || fail "box float: status $?"
# The turned box's coordinates (4.2, ...) are not floats: each rounded by at most 2^-24 of 4.2, which
# moves every quantity by less than 1e-6 of its size.
check "$DIR/got.f" "$DIR/want" outward "box.obj --precision float" 1e-6
cmp -s "$DIR/got" "$DIR/got.f" && fail "box.obj: --precision float gave the double output"
pass "--precision float: coordinates rounded once to float"

# ---- a doubled sheet: closed, encloses nothing --------------------------------------------------
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n' > "$DIR/sheet.obj"
"$TTD" mesh mass "$DIR/sheet.obj" > "$DIR/got.sheet" 2> "$DIR/err" || fail "sheet: status $?: $(cat "$DIR/err")"
grep -q '^mass 0$' "$DIR/got.sheet" && grep -q '^volume 0 flat$' "$DIR/got.sheet" && grep -q '^area 1$' "$DIR/got.sheet" &&
    grep -q '^center -\{0,1\}nan -\{0,1\}nan -\{0,1\}nan$' "$DIR/got.sheet" || fail "sheet: $(cat "$DIR/got.sheet")"
"$TTD" mesh mass "$DIR/sheet.obj" --json | grep -q '"orientation": "flat", "area": 1, "center": \[null, null, null\]' ||
    fail "sheet --json: $("$TTD" mesh mass "$DIR/sheet.obj" --json)"
pass "a doubled sheet: volume 0 'flat', centre nan (null in JSON)"

# ---- errors ----------------------------------------------------------------------------------------
# expect STATUS PATTERN ARGS...: the exit status, a message on stderr matching PATTERN, no output.
expect() {
    want=$1 pat=$2; shift 2
    "$TTD" mesh mass "$@" > "$DIR/out" 2> "$DIR/err"
    rc=$?
    [ $rc -eq "$want" ] || fail "mesh mass $*: exit status $rc, want $want ($(cat "$DIR/err"))"
    [ -s "$DIR/out" ] && fail "mesh mass $*: printed $(cat "$DIR/out")"
    grep -q -e "$pat" "$DIR/err" || fail "mesh mass $*: message '$(cat "$DIR/err")', want /$pat/"
}
expect 1 "nonexistent.obj" "$DIR/nonexistent.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 zero\nf 1 2 3\n' > "$DIR/bad.obj"
expect 1 "bad.obj:3" "$DIR/bad.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n' > "$DIR/badindex.obj"
expect 1 "badindex.obj" "$DIR/badindex.obj"
: > "$DIR/empty.obj"
expect 1 "empty.obj" "$DIR/empty.obj"
grep -v '^f 2 4 8 6$' "$DIR/small.obj" > "$DIR/open.obj" # a face taken away
expect 1 "open.obj: mesh mass: the mesh is not closed: " "$DIR/open.obj"
sed 's/^f 2 4 8 6$/f 2 6 8 4/' "$DIR/small.obj" > "$DIR/turned.obj" # one face reversed
expect 1 "turned.obj: mesh mass: the mesh is not closed (inconsistently oriented)" "$DIR/turned.obj"
for d in nan NaN inf -inf 0 -0 -2.5 1e400 abc 2x ''; do
    expect 2 "bad value for --density: '$d' (a finite number > 0)" "$DIR/box.obj" --density "$d"
done
expect 2 "--density needs a value" "$DIR/box.obj" --density
expect 2 "bad value for --precision" "$DIR/box.obj" --precision quad
expect 2 "bad value for --weld" "$DIR/box.obj" --weld -1
expect 2 "unknown option '--margin'" "$DIR/box.obj" --margin 1
expect 2 "the mesh file A is missing" --density 2
expect 2 "unexpected argument" "$DIR/box.obj" "$DIR/box.obj"
out=$("$TTD" mesh mass --help) || fail "--help: exit status $?"
case "$out" in *"usage: ttd mesh mass"*"--density"*"--json"*inward*) ;; *) fail "--help: $out" ;; esac
"$TTD" mesh --help | grep -q "ttd mesh mass" || fail "ttd mesh --help does not name mesh mass"
"$TTD" --help | grep -q "mesh mass" || fail "ttd --help does not name mesh mass"
pass "errors: files (exit 1), options and density (exit 2), nothing printed"
exit 0
