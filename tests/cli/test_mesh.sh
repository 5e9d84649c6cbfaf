#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd mesh distance | contacts | collide | self-contacts | self-collide` on meshes this script writes (a unit cube A and a
# tetrahedron B, each in OBJ, STL ASCII and binary, PLY ASCII and binary), checked against:
#   - answers known by construction for seven poses (a face gap, vertex-vertex, two rotations, touching,
#     crossing, far): the distance, the closest points, the triangle indices where unique;
#   - properties: p lies on triangle ia of A, q on triangle ib of B moved by the pose, |p - q| = d;
#   - brute force: every triangle pair through `ttd dist --points`, with B's vertices moved by
#     the pose here in awk with the library's arithmetic ((r0 x + r1 y) + r2 z) + t: the minimum,
#     the pair set within a margin, the per-triangle reduction, collision, in double and float;
#   - every format giving the same output; --poses equal to one --pose run per pose; threads
#     and instruction sets giving identical output;
#   - a 64 x 64 grid against itself: 110k contact lines equal to the set of triangles sharing a
#     vertex, built here from the grid's incidence; --count over 20 poses;
#   - float: coordinates and poses rounded once from the text (strtof), not through double;
#   - poses of 16 numbers (4x4) equal their 12; --orthonormalize repairs a rotation printed
#     with 5 digits (the exact rotation's answer) and still refuses one far from a rotation;
#   - OBJ lines that are not statements skipped, counted and said once (--strict refuses them);
#     text taken for a binary STL says so and why;
#   - self-contacts of two stacked grids, one bent through the other: `mesh contacts S S` less the
#     pairs that share a vertex (from the file's incidence); --shared-vertex adds only pairs that
#     share one vertex; --count; self-collide's witness; threads, ISAs, float; its errors;
#   - every error path: missing, malformed and truncated files (the message names file and line
#     or byte offset), bad --pose arguments (exit 2) and poses-file lines (exit 1), poses that are
#     not rotations, bad margins and bounds, unknown options and commands, missing and extra
#     operands; nothing printed on standard output then, and never a crash.
# Only POSIX sh and awk. Usage: sh test_mesh.sh path/to/ttd
set -u
TTD=${1:?usage: test_mesh.sh path/to/ttd}
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

# ---- awk helpers -------------------------------------------------------------------------
# A mesh description is 'v x y z' and 'f i j k [l]' lines (0-based, counter-clockwise seen from
# outside); load() fan-triangulates faces as the reader does: (v0 v1 v2) (v0 v2 v3).
cat > "$DIR/lib.awk" <<'EOF'
function load(m, file,    line, f, n, k) {
    NV[m] = 0; NT[m] = 0
    while ((getline line < file) > 0) {
        n = split(line, f, " ")
        if (f[1] == "v") { VX[m, NV[m]] = f[2] + 0; VY[m, NV[m]] = f[3] + 0; VZ[m, NV[m]] = f[4] + 0; NV[m]++ }
        else if (f[1] == "f")
            for (k = 4; k <= n; k++) { TI[m, NT[m], 0] = f[2]; TI[m, NT[m], 1] = f[k - 1]; TI[m, NT[m], 2] = f[k]; NT[m]++ }
    }
    close(file)
}
function parse_pose(s, P,    f, k) {
    split(s, f, " ")
    for (k = 0; k < 12; k++) P[k] = f[k + 1] + 0
}
# Vertex i of mesh m moved by pose P, as the library computes it, into QX QY QZ.
function apply(P, m, i,    x, y, z) {
    x = VX[m, i]; y = VY[m, i]; z = VZ[m, i]
    QX = ((P[0] * x + P[1] * y) + P[2] * z) + P[3]
    QY = ((P[4] * x + P[5] * y) + P[6] * z) + P[7]
    QZ = ((P[8] * x + P[9] * y) + P[10] * z) + P[11]
}
function abs(x) { return x < 0 ? -x : x }
# Whether (x, y, z) lies on the triangle with corners (ax..cz), within eps.
function on_tri(x, y, z, ax, ay, az, bx, by, bz, cx, cy, cz, eps,    e0x, e0y, e0z, e1x, e1y, e1z, wx, wy, wz, d00, d01, d11, d20, d21, den, v, w, u, rx, ry, rz) {
    e0x = bx - ax; e0y = by - ay; e0z = bz - az; e1x = cx - ax; e1y = cy - ay; e1z = cz - az
    wx = x - ax; wy = y - ay; wz = z - az
    d00 = e0x * e0x + e0y * e0y + e0z * e0z; d01 = e0x * e1x + e0y * e1y + e0z * e1z
    d11 = e1x * e1x + e1y * e1y + e1z * e1z
    d20 = wx * e0x + wy * e0y + wz * e0z; d21 = wx * e1x + wy * e1y + wz * e1z
    den = d00 * d11 - d01 * d01
    if (den == 0) return 0
    v = (d11 * d20 - d01 * d21) / den; w = (d00 * d21 - d01 * d20) / den; u = 1 - v - w
    if (u < -eps || v < -eps || w < -eps) return 0
    rx = ax + v * e0x + w * e1x - x; ry = ay + v * e0y + w * e1y - y; rz = az + v * e0z + w * e1z - z
    return rx * rx + ry * ry + rz * rz <= eps * eps
}
# Float32 bits of x (exactly representable, normal or 0) as 4 little-endian printf escapes.
function f32(x,    s, e, bits) {
    if (x == 0) return u32(0)
    s = 0; if (x < 0) { s = 1; x = -x }
    e = 0; while (x >= 2) { x /= 2; e++ } while (x < 1) { x *= 2; e-- }
    bits = (x - 1) * 8388608
    if (bits != int(bits)) { print "f32: not a float: " x > "/dev/stderr"; exit 3 }
    return u32(s * 2147483648 + (e + 127) * 8388608 + bits)
}
function u32(n,    k, b, out) {
    out = ""
    for (k = 0; k < 4; k++) { b = n % 256; out = out sprintf("\\%03o", b); n = (n - b) / 256 }
    return out
}
function zeros(n,    out) { out = ""; while (n-- > 0) out = out "\\000"; return out }
EOF
LIB=$(cat "$DIR/lib.awk")

# ---- the meshes, in five formats ---------------------------------------------------------
# The unit cube [0,1]^3, vertex x + 2y + 4z at (x, y, z), six quads: bottom (triangles 0, 1),
# top (2, 3), front y=0 (4, 5), back y=1 (6, 7), left x=0 (8, 9), right x=1 (10, 11).
cat > "$DIR/cube.mesh" <<'EOF'
v 0 0 0
v 1 0 0
v 0 1 0
v 1 1 0
v 0 0 1
v 1 0 1
v 0 1 1
v 1 1 1
f 0 2 3 1
f 4 5 7 6
f 0 1 5 4
f 2 6 7 3
f 0 4 6 2
f 1 3 7 5
EOF
# The tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1): triangle 0 is its base z=0, 1 its side y=0,
# 2 its side x=0, 3 the slanted face.
cat > "$DIR/tet.mesh" <<'EOF'
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 0 2 1
f 0 1 3
f 0 3 2
f 1 2 3
EOF

# write_formats NAME: NAME.obj (faces as given, 1-based), NAME.stla, NAME.stlb, NAME.plya (faces
# as given) and NAME.plyb (float32 coordinates, faces fan-triangulated here) from NAME.mesh.
write_formats() {
    m="$DIR/$1"
    awk '$1 == "v" { print "v", $2, $3, $4 } $1 == "f" { s = "f"; for (k = 2; k <= NF; k++) s = s " " ($k + 1); print s }' \
        "$m.mesh" > "$m.obj"
    awk -v file="$m.mesh" "$LIB"'BEGIN { load(1, file); print "solid test"
        for (t = 0; t < NT[1]; t++) { print " facet normal 0 0 0"; print "  outer loop"
            for (c = 0; c < 3; c++) { i = TI[1, t, c]; print "   vertex", VX[1, i], VY[1, i], VZ[1, i] }
            print "  endloop"; print " endfacet" }
        print "endsolid test" }' > "$m.stla"
    printf "$(awk -v file="$m.mesh" "$LIB"'BEGIN { load(1, file); s = ""
        for (k = 0; k < 80; k++) s = s "\\040"
        s = s u32(NT[1])
        for (t = 0; t < NT[1]; t++) { s = s zeros(12)
            for (c = 0; c < 3; c++) { i = TI[1, t, c]; s = s f32(VX[1, i]) f32(VY[1, i]) f32(VZ[1, i]) }
            s = s zeros(2) }
        printf "%s", s }')" > "$m.stlb"
    awk 'BEGIN { print "ply"; print "format ascii 1.0"; print "comment written by test_mesh.sh" }
         $1 == "v" { v[nv++] = $2 " " $3 " " $4 } $1 == "f" { s = NF - 1; for (k = 2; k <= NF; k++) s = s " " $k; f[nf++] = s }
         END { print "element vertex " nv; print "property float x"; print "property float y"; print "property float z"
               print "element face " nf; print "property list uchar int vertex_indices"; print "end_header"
               for (i = 0; i < nv; i++) print v[i]; for (i = 0; i < nf; i++) print f[i] }' "$m.mesh" > "$m.plya"
    awk -v file="$m.mesh" "$LIB"'BEGIN { load(1, file); print "ply"; print "format binary_little_endian 1.0"
        print "element vertex " NV[1]; print "property float x"; print "property float y"; print "property float z"
        print "element face " NT[1]; print "property list uchar int vertex_indices"; print "end_header" }' > "$m.plyb"
    printf "$(awk -v file="$m.mesh" "$LIB"'BEGIN { load(1, file); s = ""
        for (i = 0; i < NV[1]; i++) s = s f32(VX[1, i]) f32(VY[1, i]) f32(VZ[1, i])
        for (t = 0; t < NT[1]; t++) s = s "\\003" u32(TI[1, t, 0]) u32(TI[1, t, 1]) u32(TI[1, t, 2])
        printf "%s", s }')" >> "$m.plyb"
}
write_formats cube
write_formats tet
FORMATS="obj stla stlb plya plyb"
A="$DIR/cube.obj"
B="$DIR/tet.obj"
# The binary files are what they claim: 84 + 50 n bytes, and the PLY header plus its data.
[ "$(wc -c < "$DIR/cube.stlb" | tr -d ' ')" = $((84 + 50 * 12)) ] || fail "cube.stlb has $(wc -c < "$DIR/cube.stlb") bytes"
[ "$(wc -c < "$DIR/tet.plyb" | tr -d ' ')" = $(($(awk '{ n += length($0) + 1 } /end_header/ { print n; exit }' "$DIR/tet.plyb") + 4 * 12 + 4 * 13)) ] ||
    fail "tet.plyb has $(wc -c < "$DIR/tet.plyb") bytes"

# ---- running and checking ----------------------------------------------------------------
# run WANT-STATUS ARGS...: ttd ARGS, stdout in $DIR/out, stderr in $DIR/err; fails on a crash or
# a status other than WANT-STATUS.
run() {
    want=$1; shift
    "$TTD" "$@" > "$DIR/out" 2> "$DIR/err"
    rc=$?
    [ $rc -lt 124 ] || fail "ttd $*: crash (status $rc): $(cat "$DIR/err")"
    [ $rc -eq "$want" ] || fail "ttd $*: status $rc, want $want: $(cat "$DIR/err")"
}
# expect WHAT LINE WANT: the fields of LINE equal WANT's within 1e-12 (relative to 1 + |x|);
# a '*' in WANT matches anything, and a text field (inf, nan, a, b) must match as text.
expect() {
    awk -v what="$1" -v got="$2" -v want="$3" -v tol="${4:-1e-12}" 'BEGIN {
        n = split(got, g, " "); m = split(want, w, " ")
        if (n != m) { print what ": " n " fields in '\''" got "'\'', want " m; exit 1 }
        for (k = 1; k <= n; k++) {
            if (w[k] == "*" || g[k] == w[k]) continue
            if (g[k] !~ /^-?[0-9]/ || w[k] !~ /^-?[0-9]/) { print what ": field " k " is " g[k] ", want " w[k]; exit 1 }
            e = g[k] - w[k]; if (e < 0) e = -e; s = w[k] < 0 ? -w[k] : w[k]
            if (e > tol * (1 + s)) { print what ": field " k " is " g[k] ", want " w[k]; exit 1 } } }' ||
        fail "$1: '$2'"
}
# same_lines WHAT FILE1 FILE2 [TOL]: the same number of lines, each as expect() compares them.
same_lines() {
    awk -v what="$1" -v f1="$2" -v f2="$3" -v tol="${4:-1e-12}" 'BEGIN {
        while ((getline a < f1) > 0) {
            ++line
            if ((getline b < f2) <= 0) { print what ": " f2 " ends at line " line; exit 1 }
            n = split(a, g, " "); m = split(b, w, " ")
            if (n != m) { print what ": line " line ": '\''" a "'\'' against '\''" b "'\''"; exit 1 }
            for (k = 1; k <= n; k++) {
                if (g[k] == w[k]) continue
                e = g[k] - w[k]; if (e < 0) e = -e; s = w[k] < 0 ? -w[k] : w[k]
                if (g[k] !~ /^-?[0-9]/ || w[k] !~ /^-?[0-9]/ || e > tol * (1 + s)) {
                    print what ": line " line ": '\''" a "'\'' against '\''" b "'\''"; exit 1 } } }
        if ((getline b < f2) > 0) { print what ": " f2 " has more lines than " f1 " (" line ")"; exit 1 } }' ||
        fail "$1"
}
# on_triangles WHAT LINE POSE: a distance line 'd p q ia ib': p on triangle ia of the cube, q on
# triangle ib of the tetrahedron moved by POSE, |p - q| = d (1e-12).
on_triangles() {
    awk -v what="$1" -v line="$2" -v pose="$3" -v fa="$DIR/cube.mesh" -v fb="$DIR/tet.mesh" "$LIB"'BEGIN {
        load(1, fa); load(2, fb); parse_pose(pose, P); split(line, r, " ")
        ia = r[8]; ib = r[9]
        if (ia < 0 || ia >= NT[1] || ib < 0 || ib >= NT[2] || ia != int(ia) || ib != int(ib)) { print what ": bad indices"; exit 1 }
        a0 = TI[1, ia, 0]; a1 = TI[1, ia, 1]; a2 = TI[1, ia, 2]
        if (!on_tri(r[2], r[3], r[4], VX[1, a0], VY[1, a0], VZ[1, a0], VX[1, a1], VY[1, a1], VZ[1, a1],
                    VX[1, a2], VY[1, a2], VZ[1, a2], 1e-9)) { print what ": p is not on triangle " ia " of A"; exit 1 }
        for (c = 0; c < 3; c++) { apply(P, 2, TI[2, ib, c]); X[c] = QX; Y[c] = QY; Z[c] = QZ }
        if (!on_tri(r[5], r[6], r[7], X[0], Y[0], Z[0], X[1], Y[1], Z[1], X[2], Y[2], Z[2], 1e-9)) {
            print what ": q is not on triangle " ib " of B"; exit 1 }
        d = sqrt((r[2] - r[5]) ^ 2 + (r[3] - r[6]) ^ 2 + (r[4] - r[7]) ^ 2)
        if (abs(d - r[1]) > 1e-12 * (1 + r[1])) { print what ": |p - q| = " d; exit 1 } }' || fail "$1: '$2'"
}
# brute POSE [float]: every pair (cube triangle i, tetrahedron triangle j) in $DIR/brute, line
# i * 4 + j + 1: 'd px py pz qx qy qz' from `ttd dist --points` on B moved by POSE here.
brute() {
    awk -v pose="$1" -v fa="$DIR/cube.mesh" -v fb="$DIR/tet.mesh" "$LIB"'BEGIN {
        load(1, fa); load(2, fb); parse_pose(pose, P)
        for (i = 0; i < NT[1]; i++) for (j = 0; j < NT[2]; j++) {
            s = ""
            for (c = 0; c < 3; c++) { v = TI[1, i, c]; s = s sprintf("%.17g %.17g %.17g ", VX[1, v], VY[1, v], VZ[1, v]) }
            for (c = 0; c < 3; c++) { apply(P, 2, TI[2, j, c]); s = s sprintf("%.17g %.17g %.17g ", QX, QY, QZ) }
            print s } }' > "$DIR/pairs.txt"
    if [ "${2:-}" = float ]; then prec=float; else prec=double; fi
    "$TTD" dist --points --precision $prec "$DIR/pairs.txt" > "$DIR/brute" || fail "ttd dist on the brute-force pairs"
    [ "$(wc -l < "$DIR/brute" | tr -d ' ')" = 48 ] || fail "brute force: $(wc -l < "$DIR/brute") lines"
}
# brute_contacts MARGIN: the pairs of $DIR/brute within MARGIN, 'ia ib d p q', by ia then ib.
brute_contacts() {
    awk -v m="$1" '$1 <= m + 0 { print int((NR - 1) / 4), (NR - 1) % 4, $0 }' "$DIR/brute"
}
# brute_closest MARGIN: the per-triangle reduction of $DIR/brute (nearest partner within
# MARGIN, ties to the smaller index): 'a ia ib d p q' by ia, then 'b ib ia d q p' by ib.
brute_closest() {
    awk -v m="$1" '{ i = int((NR - 1) / 4); j = (NR - 1) % 4; L[i, j] = $0; D[i, j] = $1 + 0 }
        END { for (i = 0; i < 12; i++) { best = -1
                  for (j = 0; j < 4; j++) if (D[i, j] <= m + 0 && (best < 0 || D[i, j] < D[i, best])) best = j
                  if (best >= 0) print "a", i, best, L[i, best] }
              for (j = 0; j < 4; j++) { best = -1
                  for (i = 0; i < 12; i++) if (D[i, j] <= m + 0 && (best < 0 || D[i, j] < D[best, j])) best = i
                  if (best >= 0) { split(L[best, j], f, " "); print "b", j, best, f[1], f[5], f[6], f[7], f[2], f[3], f[4] } } }' "$DIR/brute"
}

# ---- distance: known answers, properties, brute force, every format ------------------------
# The poses (rows of [R | t]); each with the distance line it must give ('*': not unique, then
# checked by the properties), and the distances known by construction:
P_GAP='1 0 0 0  0 1 0 0  0 0 1 3'            # base of B at z = 3 over A's top z = 1: faces 2 apart
P_VV='1 0 0 2  0 1 0 2  0 0 1 3'             # corner (1,1,1) of A to corner (2,2,3) of B: sqrt 6
P_ROTZ='0 -1 0 3  1 0 0 0.25  0 0 1 0.5'     # 90 degrees about z: vertex (2,.25,.5) of B 1 from A's face x = 1
P_ROTY='0.6 0 0.8 1.5  0 1 0 0.25  -0.8 0 0.6 0.5' # about y: B's edge x = 1.5, z = .5 parallel to A's face x = 1
P_TOUCH='1 0 0 1  0 1 0 0  0 0 1 0'          # B's face x = 0 on A's face x = 1
P_CROSS='1 0 0 0.5  0 1 0 0.5  0 0 1 0.5'    # B's corner inside A
P_FAR='1 0 0 10  0 1 0 0  0 0 1 0'           # 9 apart along x
want_distance() { # want_distance POSE-NAME: the line known by construction
    case $1 in
        GAP) echo '2 * * 1 * * 3 * *' ;;
        VV) echo '2.449489742783178 1 1 1 2 2 3 * *' ;;
        ROTZ) echo '1 1 0.25 0.5 2 0.25 0.5 11 *' ;;
        ROTY) echo '0.5 1 * 0.5 1.5 * 0.5 * *' ;;
        TOUCH) echo '0 1 * * 1 * * * *' ;;
        CROSS) echo '0 * * * * * * * *' ;;
        FAR) echo '9 1 * * 10 * * * *' ;;
    esac
}
pose_of() { eval "echo \"\$P_$1\""; }
POSES="GAP VV ROTZ ROTY TOUCH CROSS FAR"

for name in $POSES; do
    pose=$(pose_of $name)
    run 0 mesh distance "$A" "$B" --pose "$pose"
    line=$(cat "$DIR/out")
    [ "$(wc -l < "$DIR/out" | tr -d ' ')" = 1 ] || fail "distance $name: $(cat "$DIR/out")"
    expect "distance $name" "$line" "$(want_distance $name)"
    on_triangles "distance $name" "$line" "$pose"
    # p = q when they touch or cross; p and q share the coordinates the construction makes equal.
    case $name in
        TOUCH|CROSS) awk -v l="$line" 'BEGIN { split(l, r, " "); exit !(r[2] == r[5] && r[3] == r[6] && r[4] == r[7]) }' ||
            fail "distance $name: p != q: $line" ;;
        GAP) awk -v l="$line" 'BEGIN { split(l, r, " "); exit !(r[2] == r[5] && r[3] == r[6]) }' || fail "distance GAP: $line" ;;
        ROTY) awk -v l="$line" 'BEGIN { split(l, r, " "); exit !(r[3] == r[6] && r[3] >= 0.25 && r[3] <= 1) }' ||
            fail "distance ROTY: $line" ;;
    esac
    # Brute force: the minimum over all pairs, and the reported pair realises it.
    brute "$pose"
    awk -v l="$line" '{ if (NR == 1 || $1 + 0 < min) min = $1 + 0; d[NR - 1] = $1 + 0 }
        END { split(l, r, " "); e = r[1] - min; if (e < 0) e = -e
              if (e > 1e-12 * (1 + min)) { print "minimum " min; exit 1 }
              e = d[r[8] * 4 + r[9]] - r[1]; if (e < 0) e = -e
              if (e > 1e-12 * (1 + min)) { print "the reported pair is at " d[r[8] * 4 + r[9]]; exit 1 } }' "$DIR/brute" ||
        fail "distance $name against brute force: $line"
    # Every format gives the same line, and so does standard input.
    for fmt in $FORMATS; do
        run 0 mesh distance "$DIR/cube.$fmt" "$DIR/tet.$fmt" --pose "$pose"
        [ "$(cat "$DIR/out")" = "$line" ] || fail "distance $name, $fmt: '$(cat "$DIR/out")', obj: '$line'"
    done
    "$TTD" mesh distance - "$B" --pose "$pose" < "$A" > "$DIR/out" || fail "distance from standard input"
    [ "$(cat "$DIR/out")" = "$line" ] || fail "distance $name from standard input: $(cat "$DIR/out")"
done
pass "distance: 7 poses x 5 formats: known answers, points on their triangles, brute force"

# Without a pose, B is used as given: the tetrahedron at the cube's corner, touching it.
run 0 mesh distance "$A" "$B"
expect "identity pose" "$(cat "$DIR/out")" '0 * * * * * * * *'
run 0 mesh distance "$A" "$B" --pose '1 0 0 0 0 1 0 0 0 0 1 0'
[ "$(cat "$DIR/out")" = "$("$TTD" mesh distance "$A" "$B")" ] || fail "no pose differs from the identity"
# A mesh against itself (one path, read once; also '-' twice) shifted by 2.5 along y.
run 0 mesh distance "$A" "$A" --pose '1 0 0 0  0 1 0 2.5  0 0 1 0'
expect "cube against itself" "$(cat "$DIR/out")" '1.5 * 1 * * 2.5 * * *'
"$TTD" mesh distance - - --pose '1 0 0 0  0 1 0 2.5  0 0 1 0' < "$A" > "$DIR/out2" || fail "distance - -"
cmp -s "$DIR/out" "$DIR/out2" || fail "distance - - differs"
pass "distance: identity without a pose, one mesh against itself"

# --upper-bound: exceeded prints the documented line; not exceeded changes nothing.
run 0 mesh distance "$A" "$B" --pose "$P_FAR" --upper-bound 5
[ "$(cat "$DIR/out")" = 'inf nan nan nan nan nan nan -1 -1' ] || fail "upper bound exceeded: $(cat "$DIR/out")"
run 0 mesh distance "$A" "$B" --pose "$P_FAR" --upper-bound=9.5
[ "$(cat "$DIR/out")" = "$("$TTD" mesh distance "$A" "$B" --pose "$P_FAR")" ] || fail "upper bound not exceeded"
# --rel-tol: a pair within the factor, still on its triangles.
run 0 mesh distance "$A" "$B" --pose "$P_VV" --rel-tol 0.5
line=$(cat "$DIR/out")
awk -v l="$line" 'BEGIN { split(l, r, " "); exit !(r[1] >= 2.449489742783178 * (1 - 1e-15) && r[1] <= 1.5 * 2.449489742783178) }' ||
    fail "rel-tol: $line"
on_triangles "rel-tol" "$line" "$P_VV"
pass "distance: --upper-bound, --rel-tol"

# ---- contacts, per-triangle, collide against brute force -----------------------------------
for name in $POSES; do
    pose=$(pose_of $name)
    brute "$pose"
    d=$("$TTD" mesh distance "$A" "$B" --pose "$pose" | cut -d' ' -f1)
    # Margins: a little above the minimum (every format), the minimum itself (its pairs
    # included), and (when d > 0) below it (OBJ and binary STL, a text and a binary reader).
    margins="$(awk -v d="$d" 'BEGIN { printf "%.17g", d + 0.3 }') $d"
    [ "$d" = 0 ] || margins="$margins $(awk -v d="$d" 'BEGIN { printf "%.17g", d * 0.99 }')"
    fmts=$FORMATS
    for m in $margins; do
        brute_contacts "$m" > "$DIR/want"
        for fmt in $fmts; do
            run 0 mesh contacts "$DIR/cube.$fmt" "$DIR/tet.$fmt" --pose "$pose" --margin "$m"
            same_lines "contacts $name margin $m ($fmt)" "$DIR/out" "$DIR/want"
        done
        run 0 mesh contacts "$A" "$B" --pose "$pose" --margin "$m" --count
        [ "$(cat "$DIR/out")" = "$(wc -l < "$DIR/want" | tr -d ' ')" ] || fail "contacts $name --count $m: $(cat "$DIR/out")"
        brute_closest "$m" > "$DIR/want"
        for fmt in $fmts; do
            run 0 mesh contacts "$DIR/cube.$fmt" "$DIR/tet.$fmt" --pose "$pose" --margin "$m" --per-triangle
            same_lines "per-triangle $name margin $m ($fmt)" "$DIR/out" "$DIR/want"
        done
        run 0 mesh contacts "$A" "$B" --pose "$pose" --margin "$m" --per-triangle --count
        [ "$(cat "$DIR/out")" = "$(awk '$1 == "a" { a++ } $1 == "b" { b++ } END { print a + 0, b + 0 }' "$DIR/want")" ] ||
            fail "per-triangle --count $name $m: $(cat "$DIR/out")"
        # collide: 1 exactly when some pair is within the margin, and the witness pair is.
        for fmt in $fmts; do
            run 0 mesh collide "$DIR/cube.$fmt" "$DIR/tet.$fmt" --pose "$pose" --margin "$m"
            awk -v l="$(cat "$DIR/out")" -v m="$m" '{ d[NR - 1] = $1 + 0; if ($1 + 0 <= m + 0) hit = 1 }
                END { n = split(l, r, " ")
                      if (!hit) exit !(n == 1 && r[1] == "0")
                      exit !(n == 3 && r[1] == "1" && r[2] >= 0 && r[2] < 12 && r[3] >= 0 && r[3] < 4 && d[r[2] * 4 + r[3]] <= m + 0) }' \
                "$DIR/brute" || fail "collide $name margin $m ($fmt): $(cat "$DIR/out")"
        done
        fmts="obj stlb"
    done
    # collide without --margin: do they touch or cross?
    run 0 mesh collide "$A" "$B" --pose "$pose"
    case $name in TOUCH|CROSS) want=1 ;; *) want=0 ;; esac
    [ "$(cut -d' ' -f1 "$DIR/out")" = $want ] || fail "collide $name: $(cat "$DIR/out")"
done
pass "contacts, --count, --per-triangle, collide: 7 poses x 2-3 margins x 2-5 formats, equal to brute force"

# A margin that holds every pair; contact lines sorted by ia then ib, with no duplicates.
run 0 mesh contacts "$A" "$B" --pose "$P_CROSS" --margin 100
[ "$(wc -l < "$DIR/out" | tr -d ' ')" = 48 ] || fail "margin 100: $(wc -l < "$DIR/out") pairs"
sort -k1,1n -k2,2n -u "$DIR/out" | cmp -s - "$DIR/out" || fail "contacts not sorted by ia, ib"
pass "contacts: every pair within a large margin, sorted"

# ---- many poses ----------------------------------------------------------------------------
{
    echo '# the seven poses, with blank lines and comments'
    for name in $POSES; do pose_of $name; echo; done
    echo "   $P_VV   # the second again, with a comment"
} > "$DIR/poses.txt"
set -- $POSES VV
k=0
: > "$DIR/want_d"; : > "$DIR/want_c"; : > "$DIR/want_n"; : > "$DIR/want_k"; : > "$DIR/want_t"
for name in "$@"; do
    pose=$(pose_of $name)
    "$TTD" mesh distance "$A" "$B" --pose "$pose" >> "$DIR/want_d"
    "$TTD" mesh collide "$A" "$B" --pose "$pose" --margin 0.6 >> "$DIR/want_c"
    "$TTD" mesh contacts "$A" "$B" --pose "$pose" --margin 0.6 | sed "s/^/$k /" >> "$DIR/want_k"
    "$TTD" mesh contacts "$A" "$B" --pose "$pose" --margin 0.6 --count >> "$DIR/want_n"
    "$TTD" mesh contacts "$A" "$B" --pose "$pose" --margin 0.6 --per-triangle | sed "s/^/$k /" >> "$DIR/want_t"
    k=$((k + 1))
done
run 0 mesh distance "$A" "$B" --poses "$DIR/poses.txt"
cmp -s "$DIR/out" "$DIR/want_d" || fail "distance --poses differs from one --pose per pose"
run 0 mesh collide "$A" "$B" --poses "$DIR/poses.txt" --margin 0.6
cmp -s "$DIR/out" "$DIR/want_c" || fail "collide --poses differs"
run 0 mesh contacts "$A" "$B" --poses "$DIR/poses.txt" --margin 0.6
cmp -s "$DIR/out" "$DIR/want_k" || fail "contacts --poses differs (pose index, then the single-pose lines)"
run 0 mesh contacts "$A" "$B" --poses "$DIR/poses.txt" --margin 0.6 --count
cmp -s "$DIR/out" "$DIR/want_n" || fail "contacts --poses --count differs"
run 0 mesh contacts "$A" "$B" --poses "$DIR/poses.txt" --margin 0.6 --per-triangle
cmp -s "$DIR/out" "$DIR/want_t" || fail "per-triangle --poses differs"
[ "$(wc -l < "$DIR/want_d" | tr -d ' ')" = 8 ] && [ -s "$DIR/want_k" ] || fail "--poses: not 8 poses, or no contacts"
# The poses from standard input; an empty poses file gives no output.
"$TTD" mesh distance "$A" "$B" --poses - < "$DIR/poses.txt" | cmp -s - "$DIR/want_d" || fail "--poses -"
printf '# nothing\n\n' > "$DIR/noposes.txt"
run 0 mesh distance "$A" "$B" --poses "$DIR/noposes.txt"
[ ! -s "$DIR/out" ] || fail "no poses: output '$(cat "$DIR/out")'"
pass "--poses: 8 poses equal to one run per pose (distance, collide, contacts, --count, --per-triangle)"

# Threads and instruction sets: the same output, bit for bit.
for cmd in "distance" "collide --margin 0.6" "contacts --margin 0.6" "contacts --margin 0.6 --per-triangle"; do
    # shellcheck disable=SC2086
    "$TTD" mesh $cmd "$A" "$B" --poses "$DIR/poses.txt" --threads 1 > "$DIR/ref" || fail "$cmd --threads 1"
    for opt in "--threads 2" "--threads 0" "--threads 7"; do
        # shellcheck disable=SC2086
        "$TTD" mesh $cmd "$A" "$B" --poses "$DIR/poses.txt" $opt | cmp -s - "$DIR/ref" || fail "$cmd $opt differs from --threads 1"
    done
    for isa in scalar sse2 avx2 avx512 neon portable; do
        # shellcheck disable=SC2086
        "$TTD" mesh $cmd "$A" "$B" --poses "$DIR/poses.txt" --isa $isa > "$DIR/out" 2> "$DIR/err"
        rc=$?
        if [ $rc -eq 2 ]; then grep -q "not available" "$DIR/err" || fail "--isa $isa: $(cat "$DIR/err")"; continue; fi
        [ $rc -eq 0 ] || fail "$cmd --isa $isa: status $rc"
        cmp -s "$DIR/out" "$DIR/ref" || fail "$cmd --isa $isa differs from the default"
    done
done
pass "threads 1, 2, 0, 7 and every available instruction set give identical output"

# ---- a large output: a 64 x 64 grid against itself ---------------------------------------
# grid N: the unit square as N x N quads in the plane z = 0 (OBJ). shared_pairs FILE: the pairs
# of its triangles that share a vertex, by ia then ib, from the file's own incidence.
grid() {
    awk -v n="$1" 'BEGIN { for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) printf "v %.17g %.17g 0\n", i / n, j / n
        for (j = 0; j < n; j++) for (i = 0; i < n; i++) { a = j * (n + 1) + i + 1; printf "f %d %d %d %d\n", a, a + 1, a + n + 2, a + n + 1 } }'
}
shared_pairs() {
    awk '$1 == "f" { for (k = 3; k < NF; k++) { t = nt++; c[t] = $2 " " $k " " $(k + 1) } }
         END { for (t = 0; t < nt; t++) { split(c[t], v, " "); for (k = 1; k <= 3; k++) inc[v[k]] = inc[v[k]] " " t }
               for (x in inc) { n = split(inc[x], l, " "); for (i = 1; i <= n; i++) for (j = 1; j <= n; j++) pair[l[i] " " l[j]] = 1 }
               for (p in pair) print p }' "$1" | sort -k1,1n -k2,2n
}
# At the identity, margin 0: exactly the pairs of triangles that share a vertex (two triangles
# without a common vertex are at least 1/64/sqrt(2) apart), all at distance 0 with p = q.
grid 64 > "$DIR/grid.obj"
shared_pairs "$DIR/grid.obj" > "$DIR/want"
run 0 mesh contacts "$DIR/grid.obj" "$DIR/grid.obj" --margin 0
cut -d' ' -f1,2 "$DIR/out" | cmp -s - "$DIR/want" || fail "grid: the contact pairs differ from the triangles sharing a vertex"
awk '$3 != 0 || $4 != $7 || $5 != $8 || $6 != $9 { print "line " NR ": " $0; exit 1 }' "$DIR/out" || fail "grid: a pair not at 0 with p = q"
n=$(wc -l < "$DIR/want" | tr -d ' ')
[ "$n" -gt 50000 ] || fail "grid: only $n pairs"
run 0 mesh contacts "$DIR/grid.obj" "$DIR/grid.obj" --margin 0 --count
[ "$(cat "$DIR/out")" = "$n" ] || fail "grid --count: $(cat "$DIR/out"), want $n"
# A 32 x 32 grid under 20 poses 1/2048 .. 20/2048 above, margin 11/1024: the same pairs (now
# at the gap) in every pose, since triangles without a common vertex are at least 1/32/sqrt(2)
# apart in the plane; 20 poses take more than one library call.
grid 32 > "$DIR/grid32.obj"
n32=$(shared_pairs "$DIR/grid32.obj" | wc -l | tr -d ' ')
awk 'BEGIN { for (k = 1; k <= 20; k++) printf "1 0 0 0  0 1 0 0  0 0 1 %.17g\n", k / 2048 }' > "$DIR/gposes.txt"
run 0 mesh contacts "$DIR/grid32.obj" "$DIR/grid32.obj" --poses "$DIR/gposes.txt" --margin 0.0107421875 --count
[ "$(sort -u "$DIR/out")" = "$n32" ] && [ "$(wc -l < "$DIR/out" | tr -d ' ')" = 20 ] || fail "grid, 20 poses --count: $(cat "$DIR/out"), want $n32"
run 0 mesh contacts "$DIR/grid32.obj" "$DIR/grid32.obj" --poses "$DIR/gposes.txt" --margin 0.0107421875 --count --precision float
[ "$(sort -u "$DIR/out")" = "$n32" ] && [ "$(wc -l < "$DIR/out" | tr -d ' ')" = 20 ] || fail "grid, float --count: $(sort -u "$DIR/out")"
pass "grid: $n contact lines equal to the shared-vertex pairs; $n32 pairs in each of 20 poses (--count), double and float"

# ---- float precision -----------------------------------------------------------------------
# Against a float brute force on the poses whose transform is exact in float (all but ROTY):
# the distance line in every format, contacts and per-triangle lines from OBJ and binary STL;
# printed with %.9g.
for name in GAP VV ROTZ TOUCH CROSS FAR; do
    pose=$(pose_of $name)
    brute "$pose" float
    run 0 mesh distance "$A" "$B" --pose "$pose" --precision float
    line=$(cat "$DIR/out")
    expect "float distance $name" "$line" "$(want_distance $name)" 1e-7
    awk -v l="$line" '{ if (NR == 1 || $1 + 0 < min) min = $1 + 0 } END { split(l, r, " "); exit !(r[1] + 0 == min) }' "$DIR/brute" ||
        fail "float distance $name: not the brute-force minimum: $line"
    echo "$line" | awk '{ for (k = 1; k <= 7; k++) if (sprintf("%.9g", $k + 0) != $k) exit 1 }' || fail "float output not %.9g: $line"
    m=$(awk -v l="$line" 'BEGIN { split(l, r, " "); printf "%.9g", r[1] + 0.3 }')
    brute_contacts "$m" > "$DIR/want"
    brute_closest "$m" > "$DIR/want_t"
    for fmt in $FORMATS; do
        run 0 mesh distance "$DIR/cube.$fmt" "$DIR/tet.$fmt" --pose "$pose" --precision float
        [ "$(cat "$DIR/out")" = "$line" ] || fail "float distance $name ($fmt): $(cat "$DIR/out")"
        case $fmt in obj|stlb) ;; *) continue ;; esac
        run 0 mesh contacts "$DIR/cube.$fmt" "$DIR/tet.$fmt" --pose "$pose" --margin "$m" --precision float
        same_lines "float contacts $name ($fmt)" "$DIR/out" "$DIR/want" 1e-7
        run 0 mesh contacts "$DIR/cube.$fmt" "$DIR/tet.$fmt" --pose "$pose" --margin "$m" --precision float --per-triangle
        same_lines "float per-triangle $name ($fmt)" "$DIR/out" "$DIR/want_t" 1e-7
    done
done
run 0 mesh distance "$A" "$B" --pose "$P_ROTY" --precision float
expect "float distance ROTY" "$(cat "$DIR/out")" "$(want_distance ROTY)" 1e-6
pass "float: distance (every format), contacts, per-triangle (OBJ, binary STL) against a float brute force"

# Poses are read with strtof: t_z = 2 + 2^-23 + 1e-32 is just above the midpoint between the
# floats 2 and 2 + 2^-22, so strtof gives 2 + 2^-22 (d = 1 + 2^-22 over the cube's top), where
# strtod then (float) would give 2 (d = 1); in double d = 1 + 2^-23.
tz=2.00000011920928955078125000000001
run 0 mesh distance "$A" "$B" --pose "1 0 0 0  0 1 0 0  0 0 1 $tz" --precision float
awk -v l="$(cat "$DIR/out")" 'BEGIN { split(l, r, " "); e = r[1] - (1 + 2 ^ -22); exit !(e < 2e-8 && e > -2e-8) }' ||
    fail "float pose not parsed by strtof: $(cat "$DIR/out")"
run 0 mesh distance "$A" "$B" --pose "1 0 0 0  0 1 0 0  0 0 1 $tz"
expect "double pose" "$(cat "$DIR/out")" "$(awk 'BEGIN { printf "%.17g", 1 + 2 ^ -23 }') * * 1 * * $tz * *" 1e-16
# Mesh coordinates too: the cube's top at 1.00000005960464477539062500000001 is 1 + 2^-23 in
# float (strtof), 1 via double; B's base at z = 3 is then 2 - 2^-23 away.
sed 's/^v \([01]\) \([01]\) 1$/v \1 \2 1.00000005960464477539062500000001/' "$A" > "$DIR/cubef.obj"
[ "$(grep -c 1.00000005960464477539062500000001 "$DIR/cubef.obj")" = 4 ] || fail "cubef.obj"
run 0 mesh distance "$DIR/cubef.obj" "$B" --pose "$P_GAP" --precision float
awk -v l="$(cat "$DIR/out")" 'BEGIN { split(l, r, " "); e = r[1] - (2 - 2 ^ -23); exit !(e < 2e-8 && e > -2e-8) }' ||
    fail "float coordinates not read by strtof: $(cat "$DIR/out")"
# The margin too: two triangles 1 + 2^-23 apart (a float); the margin text just above the
# midpoint 1 + 2^-24 between the floats 1 and 1 + 2^-23 is 1 + 2^-23 by strtof (they collide)
# and 1 via double (they would not); in double the margin is 1 + 2^-24 (no collision).
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$DIR/lo.obj"
printf 'v 0 0 1.00000011920928955078125\nv 1 0 1.00000011920928955078125\nv 0 1 1.00000011920928955078125\nf 1 2 3\n' > "$DIR/hi.obj"
run 0 mesh collide "$DIR/lo.obj" "$DIR/hi.obj" --margin 1.00000005960464477539062500000001 --precision float
[ "$(cat "$DIR/out")" = "1 0 0" ] || fail "float margin not parsed by strtof: $(cat "$DIR/out")"
run 0 mesh collide "$DIR/lo.obj" "$DIR/hi.obj" --margin 1.00000005960464477539062500000001
[ "$(cat "$DIR/out")" = 0 ] || fail "double margin: $(cat "$DIR/out")"
pass "float: poses, coordinates and margin rounded once from the text"

# ---- errors --------------------------------------------------------------------------------
# no_output WHAT: nothing on standard output.
no_output() { [ ! -s "$DIR/out" ] || fail "$1: printed '$(head -c 200 "$DIR/out")'"; }
err_has() { grep -q -e "$1" "$DIR/err" || fail "$2: no '$1' in: $(cat "$DIR/err")"; }

# Missing and unreadable files.
run 1 mesh distance "$DIR/nothere.obj" "$B"; err_has "nothere.obj" "missing A"; no_output "missing A"
run 1 mesh contacts "$A" "$DIR/nothere.stl" --margin 1; err_has "nothere.stl" "missing B"; no_output "missing B"
run 1 mesh collide "$A" "$DIR"; err_has "$DIR" "a directory"
# Malformed files: the reader's message, naming the file and line or byte offset.
{ head -n 8 "$A"; echo 'f 1 2 3'; echo 'f 1 2 99'; } > "$DIR/bad.obj"
run 1 mesh distance "$DIR/bad.obj" "$B"; err_has "bad.obj:10: face index 99" "bad OBJ index"; no_output "bad OBJ"
printf 'v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n' > "$DIR/nan.obj"
run 1 mesh distance "$A" "$DIR/nan.obj"; err_has "nan.obj:3:" "NaN vertex"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n' > "$DIR/short.obj"
run 1 mesh collide "$DIR/short.obj" "$B"; err_has "short.obj:4:" "2-vertex face"
dd if="$DIR/cube.stlb" of="$DIR/trunc.stl" bs=1 count=300 2> /dev/null
run 1 mesh distance "$DIR/trunc.stl" "$B"; err_has "trunc.stl: truncated" "truncated binary STL"; no_output "truncated STL"
head -n 20 "$DIR/cube.stla" > "$DIR/trunc.stla"
run 1 mesh distance "$DIR/trunc.stla" "$B"; err_has "trunc.stla:[0-9]*: truncated" "truncated ASCII STL"
sed 's/^4 4 5 7 6$/4 4 5 7 9/' "$DIR/cube.plya" > "$DIR/bad.plya"
grep -q '^4 4 5 7 9$' "$DIR/bad.plya" || fail "bad.plya"
run 1 mesh distance "$DIR/bad.plya" "$B"; err_has "bad.plya:[0-9]*: face 1: vertex index 9 out of range" "bad PLY index"
dd if="$DIR/tet.plyb" of="$DIR/trunc.plyb" bs=1 count=$(($(wc -c < "$DIR/tet.plyb") - 3)) 2> /dev/null
run 1 mesh distance "$A" "$DIR/trunc.plyb"; err_has "trunc.plyb" "truncated binary PLY"
: > "$DIR/empty.obj"
run 1 mesh distance "$DIR/empty.obj" "$B"; err_has "empty.obj" "empty file"
dd if="$TTD" of="$DIR/garbage.bin" bs=1000 count=2 2> /dev/null
run 1 mesh contacts "$DIR/garbage.bin" "$B" --margin 1; err_has "garbage.bin" "binary garbage"
pass "errors: missing, malformed, truncated and empty mesh files (exit 1, file and line or offset)"

# OBJ lines that are not OBJ statements (FCL's env.obj begins with "6540 2180"): skipped and
# counted, said once on standard error with the first one's FILE:LINE; the answer is the file's
# without them. --strict refuses them (exit 1, nothing printed).
{ echo "6540 2180"; sed -n '1,3p' "$A"; echo "-12 7"; sed '1,3d' "$A"; echo "@@ not a statement"; } > "$DIR/env.obj"
run 0 mesh distance "$DIR/env.obj" "$B" --pose "$P_GAP"
"$TTD" mesh distance "$A" "$B" --pose "$P_GAP" | cmp -s - "$DIR/out" || fail "env.obj: not the answer of the file without its header"
err_has "env.obj: skipped 3 lines that are not OBJ statements, first at .*env.obj:1 (--strict refuses them)" "skipped lines"
[ "$(grep -c skipped "$DIR/err")" -eq 1 ] || fail "skipped lines: said more than once: $(cat "$DIR/err")"
{ sed -n '1,3p' "$A"; echo "12"; sed '1,3d' "$A"; } > "$DIR/one.obj"
run 0 mesh collide "$DIR/one.obj" "$B" --precision float
err_has "one.obj: skipped 1 line that is not an OBJ statement, first at .*one.obj:4" "one skipped line"
run 0 mesh distance "$A" "$B"; [ ! -s "$DIR/err" ] || fail "a clean OBJ file gave messages: $(cat "$DIR/err")"
run 1 mesh distance "$DIR/env.obj" "$B" --strict; no_output "--strict"
err_has "env.obj:1: unexpected '6540' (not an OBJ statement)" "--strict"
run 0 mesh distance "$A" "$B" --strict
pass "OBJ lines that are not statements: skipped, counted, said once (FILE:LINE of the first); --strict refuses them"

# Text with a byte that text does not hold is taken for a binary STL, and the message says so.
{ printf 'v 0 0 0\nv 1 0 0 # caf\377\nv 0 1 0\nf 1 2 3\n# '; awk 'BEGIN { while (n++ < 61) printf "H"; print "" }'; } > "$DIR/garbage.obj"
run 1 mesh distance "$DIR/garbage.obj" "$B"; no_output "garbage.obj"
err_has "garbage.obj: truncated: 1212696648 facets declared" "garbage.obj"
err_has "(read as a binary STL: byte 21 is 0xff, which text does not hold)" "garbage.obj: why binary STL"
pass "text read as a binary STL: the message names the format and the byte that decided it"

# --pose arguments that are not 12 finite numbers, or not a rotation: exit 2, saying why.
bad_pose() { # bad_pose WHAT POSE PATTERN
    run 2 mesh distance "$A" "$B" --pose "$2"; err_has "$3" "$1"; err_has "--pose" "$1"; no_output "$1"
}
bad_pose "11 numbers" '1 0 0 0 0 1 0 0 0 0 1' 'expected 12 numbers (\[R | t\], 3x4) or 16 (a 4x4 matrix), found 11'
bad_pose "13 numbers" '1 0 0 0 0 1 0 0 0 0 1 0 0' 'expected 12 numbers (\[R | t\], 3x4) or 16 (a 4x4 matrix), found 13'
bad_pose "17 numbers" '1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1' 'expected 12 or 16 numbers, found 17 or more'
bad_pose "bottom row" '1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 2' 'the bottom row of a 4x4 pose must be 0 0 0 1, found 0 0 0 2'
bad_pose "bottom row 2" '1 0 0 0 0 1 0 0 0 0 1 0 0.5 0 0 1' 'the bottom row of a 4x4 pose must be 0 0 0 1, found 0.5 0 0 1'
bad_pose "empty pose" '' 'expected 12 numbers (\[R | t\], 3x4) or 16 (a 4x4 matrix), found 0'
bad_pose "junk" '1 0 0 0 0 1 0 0 0 0 1 x' "field 12 is not a number: 'x'"
bad_pose "comma" '1,0,0,0,0,1,0,0,0,0,1,0' 'field 1 is not a number'
bad_pose "nan" '1 0 0 nan 0 1 0 0 0 0 1 0' 'field 4 is not finite'
bad_pose "inf" '1 0 0 0 0 1 0 0 0 0 inf 0' 'field 11 is not finite'
bad_pose "overflow" '1 0 0 1e999 0 1 0 0 0 0 1 0' 'field 4 is out of range'
bad_pose "scale 2" '2 0 0 0 0 2 0 0 0 0 2 0' 'not orthonormal'
bad_pose "shear" '1 0.001 0 0 0 1 0 0 0 0 1 0' 'not orthonormal'
bad_pose "zero matrix" '0 0 0 0 0 0 0 0 0 0 0 0' 'det R = 0'
bad_pose "reflection" '-1 0 0 0 0 1 0 0 0 0 1 0' 'det R = -1 <= 0 (a reflection)'
run 2 mesh distance "$A" "$B" --pose '1 0 0 1e39 0 1 0 0 0 0 1 0' --precision float
err_has "out of float range" "float pose out of range"
# Within the tolerance (1e-7 off orthonormal) is accepted.
run 0 mesh distance "$A" "$B" --pose '1.0000001 0 0 5  0 1 0 0  0 0 1 0'
expect "near-rotation" "$(cat "$DIR/out")" '4 1 * * 5 * * * *' 1e-6
pass "errors: --pose not 12 or 16 finite numbers, a bottom row not 0 0 0 1, not orthonormal, det <= 0 (exit 2); 1e-7 off accepted"

# 16 numbers: the 4x4 matrix, the same poses as their 12; a poses file may mix them.
for name in GAP VV ROTZ ROTY FAR; do
    pose=$(pose_of $name)
    run 0 mesh distance "$A" "$B" --pose "$pose  0 0 0 1"
    [ "$(cat "$DIR/out")" = "$("$TTD" mesh distance "$A" "$B" --pose "$pose")" ] || fail "4x4 pose $name differs from its 3x4"
done
{ echo "$P_GAP 0 0 0 1"; echo "$P_VV"; echo "$P_ROTZ  0 0 0 1.0 # 4x4"; } > "$DIR/poses16.txt"
{ echo "$P_GAP"; echo "$P_VV"; echo "$P_ROTZ"; } > "$DIR/poses12.txt"
run 0 mesh contacts "$A" "$B" --margin 0.5 --poses "$DIR/poses16.txt"
"$TTD" mesh contacts "$A" "$B" --margin 0.5 --poses "$DIR/poses12.txt" | cmp -s - "$DIR/out" || fail "4x4 poses file differs"
{ echo "$P_GAP"; echo "$P_VV 0 0 1 1"; } > "$DIR/poses16bad.txt"
run 1 mesh distance "$A" "$B" --poses "$DIR/poses16bad.txt"; no_output "4x4 bad bottom row in a file"
err_has "poses16bad.txt:2: pose 1: the bottom row of a 4x4 pose must be 0 0 0 1, found 0 0 1 1" "4x4 bottom row in a file"
pass "poses of 16 numbers (4x4, bottom row 0 0 0 1) equal their 12, in --pose and --poses"

# --orthonormalize: a rotation by 45 degrees printed with 5 digits (defect 9.1e-6) is refused,
# and with the option replaced by the nearest rotation: the exact rotation's answer within
# 1e-12; an exact pose is unchanged but for rounding; more than 1e-2 off, or det <= 0, is still
# refused (with the option's limit named).
C5=0.70711
CX=0.70710678118654752
run 2 mesh distance "$A" "$B" --pose "$C5 -$C5 0 3  $C5 $C5 0 0  0 0 1 0"
err_has "an entry of R^T R - I is 9.1e-06, at most 1e-6 allowed; --orthonormalize replaces R by the nearest rotation" "5 digits refused"
"$TTD" mesh distance "$A" "$B" --pose "$CX -$CX 0 3  $CX $CX 0 0  0 0 1 0" | cut -d' ' -f1-7 > "$DIR/exact" ||
    fail "exact 45 degrees"  # d p q (the triangles of a vertex-to-edge minimum are not unique)
for opts in "--pose" "--pose=4x4"; do
    if [ "$opts" = "--pose" ]; then p="$C5 -$C5 0 3  $C5 $C5 0 0  0 0 1 0"; else p="$C5 -$C5 0 3  $C5 $C5 0 0  0 0 1 0  0 0 0 1"; fi
    run 0 mesh distance "$A" "$B" --orthonormalize --pose "$p"
    expect "orthonormalized ($opts)" "$(cut -d' ' -f1-7 "$DIR/out")" "$(cat "$DIR/exact")" 1e-12
done
printf '%s\n' "$C5 -$C5 0 3  $C5 $C5 0 0  0 0 1 0" "$P_GAP" > "$DIR/poses5.txt"
run 1 mesh collide "$A" "$B" --poses "$DIR/poses5.txt"; err_has "poses5.txt:1: pose 0: not a rotation" "5 digits in a file"
run 0 mesh collide "$A" "$B" --poses "$DIR/poses5.txt" --orthonormalize --precision float
[ "$(wc -l < "$DIR/out")" -eq 2 ] || fail "--orthonormalize on a poses file: $(cat "$DIR/out")"
run 0 mesh distance "$A" "$B" --orthonormalize --pose "$P_ROTY"
expect "orthonormalize an exact pose" "$(cat "$DIR/out")" "$("$TTD" mesh distance "$A" "$B" --pose "$P_ROTY")" 1e-15
run 2 mesh distance "$A" "$B" --orthonormalize --pose '2 0 0 0 0 2 0 0 0 0 2 0'
err_has "an entry of R^T R - I is 3; --orthonormalize repairs at most 0.01" "scale 2 with --orthonormalize"
run 2 mesh distance "$A" "$B" --orthonormalize --pose '-1 0 0 0 0 1 0 0 0 0 1 0'
err_has "det R = -1 <= 0 (a reflection)" "reflection with --orthonormalize"
pass "--orthonormalize: 5-digit rotations repaired (the exact answer within 1e-12), far or reflected R still refused"

# A poses file with bad lines: every one named FILE:LINE with the pose's index, exit 1, nothing
# computed.
{ echo "# poses"; echo "$P_GAP"; echo "1 0 0 0 0 1 0 0 0 0 1"; echo; echo "$P_VV"; echo "1 0 0 0 0 1 0 0 0 0 -1 0"
  echo "2 0 0 0 0 2 0 0 0 0 2 0 # scaled"; echo "$P_FAR"; echo "1 0 0 0 0 1 0 0 0 0 1 abc"; } > "$DIR/badposes.txt"
run 1 mesh distance "$A" "$B" --poses "$DIR/badposes.txt"
no_output "bad poses file"
err_has "badposes.txt:3: pose 1: expected 12 numbers (\[R | t\], 3x4) or 16 (a 4x4 matrix), found 11" "poses line 3"
err_has "badposes.txt:6: pose 3: not a rotation: det R = -1" "poses line 6"
err_has "badposes.txt:7: pose 4: not a rotation: R is not orthonormal" "poses line 7"
err_has "badposes.txt:9: pose 6: field 12 is not a number" "poses line 9"
err_has "4 bad pose lines; nothing computed" "poses summary"
run 1 mesh contacts "$A" "$B" --margin 1 --poses "$DIR/nothere.txt"; err_has "nothere.txt: cannot open" "missing poses file"
awk 'BEGIN { s = "1"; for (i = 0; i < 13; i++) s = s s; print s }' > "$DIR/longpose.txt"
run 1 mesh collide "$A" "$B" --poses "$DIR/longpose.txt"; err_has "longpose.txt:1: pose 0: line longer than 4096 bytes" "overlong pose line"
pass "errors: bad poses-file lines (exit 1, FILE:LINE: pose N: why)"

# Coordinates beyond the mesh queries' range (2^60 in float, 2^508 in double) are refused: a
# mesh file's at build, B's moved there by a pose before anything is computed, the pose named.
# Far but within the range is fine.
printf 'v 1e18 0 0\nv 1e18 1 0\nv 1e18 0 1\nf 1 2 3\n' > "$DIR/big18.obj"
printf 'v 2e18 0 0\nv 2e18 1 0\nv 2e18 0 1\nf 1 2 3\n' > "$DIR/big19.obj"
run 1 mesh distance "$A" "$DIR/big19.obj" --precision float
err_has "cannot build the mesh: a mesh coordinate" "float mesh beyond the range"; no_output "float mesh beyond the range"
run 0 mesh distance "$A" "$DIR/big18.obj" --pose '-1 0 0 1e18  0 -1 0 0  0 0 1 0' --precision float
expect "far in float" "$(cat "$DIR/out")" '0 0 0 0 0 0 0 * *'
run 1 mesh distance "$A" "$DIR/big18.obj" --pose '1 0 0 1e18  0 1 0 0  0 0 1 0' --precision float
err_has "--pose: a mesh coordinate (or one moved by a pose)" "float pose beyond the range"; no_output "float pose beyond the range"
printf '1 0 0 0  0 1 0 0  0 0 1 0\n1 0 0 0  0 1 0 0  0 0 1 1e153\n' > "$DIR/farposes.txt"
run 1 mesh collide "$A" "$A" --poses "$DIR/farposes.txt"
err_has "pose 1: a mesh coordinate (or one moved by a pose)" "double pose beyond the range"; no_output "double pose beyond the range"
printf 'v 1e152 0 0\nv 1e152 1 0\nv 1e152 0 1\nf 1 2 3\n' > "$DIR/big152.obj"
run 0 mesh collide "$A" "$DIR/big152.obj" --pose '1 0 0 -1e152  0 1 0 0  0 0 1 0'
[ "$(cut -d' ' -f1 "$DIR/out")" = 1 ] || fail "big152 moved onto the cube's face x = 0: $(cat "$DIR/out")"
printf 'v 1e160 0 0\nv 1e160 1 0\nv 1e160 0 1\nf 1 2 3\n' > "$DIR/big160.obj"
run 1 mesh collide "$A" "$DIR/big160.obj"; err_has "cannot build the mesh" "double mesh beyond the range"
pass "errors: a mesh or a pose beyond the coordinate range (exit 1)"

# Margins, bounds and other options: exit 2.
for m in -1 -1e-300 nan inf -inf abc '' 1e999; do
    run 2 mesh contacts "$A" "$B" --margin "$m"; err_has "bad value for --margin" "margin '$m'"; no_output "margin '$m'"
    run 2 mesh collide "$A" "$B" --margin="$m"; err_has "bad value for --margin" "collide margin '$m'"
done
run 2 mesh contacts "$A" "$B" --margin 1e39 --precision float; err_has "bad value for --margin" "float margin"
run 2 mesh contacts "$A" "$B"; err_has "--margin M is required" "contacts without --margin"
run 2 mesh contacts "$A" "$B" --margin; err_has "--margin needs a value" "--margin without value"
run 2 mesh distance "$A" "$B" --upper-bound -1; err_has "bad value for --upper-bound" "negative bound"
run 2 mesh distance "$A" "$B" --rel-tol nan; err_has "bad value for --rel-tol" "NaN rel-tol"
run 2 mesh distance "$A" "$B" --margin 1; err_has "--margin is an option of mesh contacts" "--margin on distance"
run 2 mesh collide "$A" "$B" --count; err_has "--count is an option of mesh contacts and mesh self-contacts only" "--count on collide"
run 2 mesh distance "$A" "$B" --per-triangle; err_has "--per-triangle is an option of mesh contacts only" "--per-triangle"
run 2 mesh collide "$A" "$B" --upper-bound 1; err_has "--upper-bound is an option of mesh distance only" "--upper-bound"
run 2 mesh distance "$A" "$B" --pose "$P_GAP" --poses "$DIR/poses.txt"; err_has "do not go together" "--pose and --poses"
run 2 mesh distance - "$B" --poses -; err_has "standard input cannot hold both" "two stdin"
run 2 mesh distance "$A" "$B" --precision half; err_has "bad value for --precision" "--precision"
run 2 mesh distance "$A" "$B" --isa nosuch; err_has "bad value for --isa" "--isa"
run 2 mesh distance "$A" "$B" --threads -1; err_has "bad value for --threads" "--threads"
run 2 mesh distance "$A" "$B" --pose; err_has "--pose needs a value" "--pose without value"
run 2 mesh distance "$A" "$B" --bogus; err_has "unknown option '--bogus'" "unknown option"
run 2 mesh distance "$A"; err_has "the mesh file B is missing" "one operand"
run 2 mesh distance; err_has "the mesh files A and B are missing" "no operand"
run 2 mesh distance "$A" "$B" "$A"; err_has "unexpected argument" "three operands"
run 2 mesh nearest "$A" "$B"; err_has "unknown command 'nearest'" "unknown subcommand"
run 2 mesh; err_has "usage: ttd mesh" "no subcommand"
# an unusable TTD_ISA is ignored with a warning, as in ttd dist (the library's policy)
TTD_ISA=nosuch "$TTD" mesh distance "$A" "$B" > "$DIR/out" 2> "$DIR/err"
[ $? -eq 0 ] || fail "TTD_ISA=nosuch: status not 0"; err_has "warning: TTD_ISA=nosuch" "TTD_ISA"
"$TTD" mesh distance "$A" "$B" | cmp -s - "$DIR/out" || fail "TTD_ISA=nosuch: not the default answer"
run 1 mesh distance "$A" "$B" --poses "$DIR"; err_has "read error" "poses file a directory"
if [ -w /dev/full ]; then
    "$TTD" mesh contacts "$A" "$B" --margin 1 > /dev/full 2> "$DIR/err"
    [ $? -eq 1 ] || fail "output to /dev/full: status not 1"; err_has "error writing the output" "/dev/full"
fi
# Usage errors are found before any file is read.
run 2 mesh distance "$DIR/nothere.obj" "$B" --bogus; err_has "unknown option" "usage before files"
pass "errors: margins, bounds, unknown and misplaced options, operands, commands (exit 2)"

# A file named like an option after --; an operand '-' for standard input.
cp "$A" "$DIR/-cube.obj"
(cd "$DIR" && "$TTD" mesh distance --pose "1 0 0 0  0 1 0 0  0 0 1 3" -- -cube.obj tet.obj) > "$DIR/out" ||
    fail "-- before an operand"
expect "--" "$(cat "$DIR/out")" "$(want_distance GAP)"
pass "operands after --"

# ---- solids --------------------------------------------------------------------------------
# A small tetrahedron in the middle of the unit cube: 0.4 apart as surfaces, 0 as solids.
cat > "$DIR/inner.obj" <<'EOF'
v 0.4 0.4 0.4
v 0.6 0.4 0.4
v 0.4 0.6 0.4
v 0.4 0.4 0.6
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
EOF
run 0 mesh distance "$A" "$DIR/inner.obj"
expect "surfaces" "$(cat "$DIR/out")" '0.4 * * * * * * * *'
run 0 mesh collide "$A" "$DIR/inner.obj"
[ "$(cat "$DIR/out")" = "0" ] || fail "surfaces collide: $(cat "$DIR/out")"
run 0 mesh distance "$A" "$DIR/inner.obj" --solid
expect "solids" "$(cat "$DIR/out")" '0 0.4 0.4 0.4 0.4 0.4 0.4 -1 0'
run 0 mesh collide "$A" "$DIR/inner.obj" --solid
[ "$(cat "$DIR/out")" = "1 -1 0" ] || fail "solids collide: $(cat "$DIR/out")"
run 0 mesh distance "$DIR/inner.obj" "$A" --solid --precision float
expect "solids, the other way, float" "$(cat "$DIR/out")" '0 0.4 0.4 0.4 0.4 0.4 0.4 0 -1' 1e-7
run 0 mesh distance "$A" "$DIR/inner.obj" --solid --pose '1 0 0 5  0 1 0 0  0 0 1 0'
expect "solids apart" "$(cat "$DIR/out")" "$("$TTD" mesh distance "$A" "$DIR/inner.obj" --pose '1 0 0 5  0 1 0 0  0 0 1 0')"
# Not closed: refused, naming why; contacts take no --solid.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$DIR/open.obj"
run 1 mesh distance "$A" "$DIR/open.obj" --solid; err_has "not closed" "--solid with an open mesh"
err_has "mesh B ($DIR/open.obj) is open" "--solid names the open mesh"
run 1 mesh distance "$DIR/open.obj" "$A" --solid; err_has "mesh A ($DIR/open.obj) is open" "--solid names mesh A"
# The inner tetrahedron with one face flipped: inconsistently oriented, named; wound inward
# (every face reversed): the same solid.
sed 's/^f 1 3 2$/f 1 2 3/' "$DIR/inner.obj" > "$DIR/flipped.obj"
run 1 mesh distance "$A" "$DIR/flipped.obj" --solid; err_has "mesh B ($DIR/flipped.obj) is inconsistently oriented" "--solid, inconsistent"
awk '$1 == "f" { print "f", $2, $4, $3; next } { print }' "$DIR/inner.obj" > "$DIR/inward.obj"
run 0 mesh distance "$A" "$DIR/inward.obj" --solid
expect "an inward solid" "$(cat "$DIR/out")" '0 0.4 0.4 0.4 0.4 0.4 0.4 -1 0'
run 0 mesh distance "$DIR/inward.obj" "$A" --solid
expect "inside an inward solid... the other way" "$(cat "$DIR/out")" '0 0.4 0.4 0.4 0.4 0.4 0.4 0 -1'
run 2 mesh contacts "$A" "$DIR/inner.obj" --margin 1 --solid; err_has "--solid" "contacts --solid"
pass "--solid: a mesh inside another at 0 as solids, 0.4 as surfaces (wound inward too); open and inconsistent meshes refused, named"

# ---- --weld ----------------------------------------------------------------------------------
# The cube as an STL soup whose facets write their corners with last-bit differences (1 as
# 1.0000000000000002 or 0.99999999999999989, 0 as -0 or 1e-17, by facet): open as read (no two
# facets share a vertex with the same bits), closed after --weld 1e-9.
awk -v file="$DIR/cube.mesh" "$LIB"'function jit(x, t, c, d,    k) { k = (t * 7 + c * 3 + d) % 3
        if (x == 1) return k == 0 ? "1" : k == 1 ? "1.0000000000000002" : "0.99999999999999989"
        return k == 0 ? "-0" : k == 1 ? "0" : "1e-17" }
    BEGIN { load(1, file); print "solid soup"
        for (t = 0; t < NT[1]; t++) { print " facet normal 0 0 0"; print "  outer loop"
            for (c = 0; c < 3; c++) { i = TI[1, t, c]; print "   vertex", jit(VX[1, i], t, c, 0), jit(VY[1, i], t, c, 1), jit(VZ[1, i], t, c, 2) }
            print "  endloop"; print " endfacet" }
        print "endsolid soup" }' > "$DIR/soup.stl"
run 1 mesh distance "$DIR/soup.stl" "$DIR/inner.obj" --solid; err_has "not closed" "--solid on the unwelded soup"
run 0 mesh distance "$DIR/soup.stl" "$DIR/inner.obj" --solid --weld 1e-9
expect "welded soup, solids" "$(cat "$DIR/out")" '0 0.4 0.4 0.4 0.4 0.4 0.4 -1 0'
run 0 mesh distance "$DIR/soup.stl" "$DIR/inner.obj" --solid --weld=1e-9 --precision float
expect "welded soup, solids, float" "$(cat "$DIR/out")" '0 0.4 0.4 0.4 0.4 0.4 0.4 -1 0' 1e-7
run 0 mesh distance "$A" "$DIR/inner.obj" --weld 0
cmp -s "$DIR/out" "$("$TTD" mesh distance "$A" "$DIR/inner.obj" > "$DIR/out2"; echo "$DIR/out2")" || fail "--weld 0 changed a welded mesh"
run 1 mesh distance "$DIR/soup.stl" "$DIR/inner.obj" --weld 5; err_has "collapses" "--weld larger than the mesh"
run 2 mesh distance "$A" "$B" --weld -1; err_has "--weld" "--weld -1"
run 2 mesh distance "$A" "$B" --weld nan; err_has "--weld" "--weld nan"
printf '0.5 0.5 0.5\n' > "$DIR/mid.txt"
run 0 points signed "$DIR/soup.stl" "$DIR/mid.txt" --weld 1e-9
expect "points signed --weld" "$(cat "$DIR/out")" '-0.5 * * * *'
printf 'mesh c %s\nmesh t %s\nbody c 1 0 0 0  0 1 0 0  0 0 1 0\nbody t 1 0 0 0  0 1 0 0  0 0 1 0\n' \
    "$DIR/soup.stl" "$DIR/inner.obj" > "$DIR/soup.scene"
run 1 scene collide "$DIR/soup.scene" --solid; err_has "closed" "scene --solid on the unwelded soup"
run 0 scene collide "$DIR/soup.scene" --solid --weld 1e-9
[ "$(cat "$DIR/out")" = "0 1 -1 0" ] || fail "scene collide --solid --weld: $(cat "$DIR/out")"
pass "--weld: an STL soup of the cube closed by welding (solids, float, points signed, scene), its errors"

# ---- self-contacts, self-collide ----------------------------------------------------------
# Two 12 x 12 grids 0.01 apart (each its own vertices), the upper one with a corner bent down
# through the lower: self-contacts against `ttd mesh contacts S S` (the same pairs, computed the
# same way, i < j) less the pairs that share a vertex, found here from the file's incidence.
awk 'BEGIN { n = 12
    for (l = 0; l < 2; l++) for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) {
        z = l * 0.01; if (l == 1 && i + j <= 2) z = -0.02 * (3 - i - j)
        printf "v %.17g %.17g %.17g\n", i / n, j / n, z }
    for (l = 0; l < 2; l++) for (j = 0; j < n; j++) for (i = 0; i < n; i++) {
        a = l * (n + 1) * (n + 1) + j * (n + 1) + i + 1; b = a + 1; c = a + n + 2; d = a + n + 1
        print "f " a " " b " " c; print "f " a " " c " " d } }' > "$DIR/sheets.obj"
S="$DIR/sheets.obj"
# not_shared FILE: the lines 'i j ...' of FILE with i < j whose triangles share no vertex
not_shared() {
    awk -v mesh="$S" 'BEGIN { nt = 0; while ((getline line < mesh) > 0) { split(line, f, " "); if (f[1] == "f") { T[nt, 0] = f[2]; T[nt, 1] = f[3]; T[nt, 2] = f[4]; nt++ } } }
        { if ($1 >= $2) next
          s = 0; for (a = 0; a < 3; a++) for (b = 0; b < 3; b++) if (T[$1, a] == T[$2, b]) s++
          if (s == 0) print }' "$1"
}
for m in 0 0.005 0.012 0.03; do
    run 0 mesh self-contacts "$S" --margin "$m"
    cp "$DIR/out" "$DIR/self"
    run 0 mesh contacts "$S" "$S" --margin "$m"
    not_shared "$DIR/out" > "$DIR/want"
    cmp -s "$DIR/self" "$DIR/want" || fail "self-contacts margin $m: not the pairs of contacts S S that share no vertex"
    run 0 mesh self-contacts "$S" --margin "$m" --count
    [ "$(cat "$DIR/out")" = "$(wc -l < "$DIR/want" | tr -d ' ')" ] || fail "self-contacts --count $m: $(cat "$DIR/out")"
    # --shared-vertex: more pairs, each extra one sharing exactly one vertex
    run 0 mesh self-contacts "$S" --margin "$m" --shared-vertex
    awk 'NR == FNR { seen[$1 " " $2] = 1; next } !(($1 " " $2) in seen) { print $1, $2 }' "$DIR/self" "$DIR/out" > "$DIR/extra"
    awk 'NR == FNR { seen[$1 " " $2] = 1; next } !(($1 " " $2) in seen) { bad = 1 } END { exit bad }' "$DIR/out" "$DIR/self" ||
        fail "self-contacts --shared-vertex $m lost pairs"
    awk -v mesh="$S" 'BEGIN { nt = 0; while ((getline line < mesh) > 0) { split(line, f, " "); if (f[1] == "f") { T[nt, 0] = f[2]; T[nt, 1] = f[3]; T[nt, 2] = f[4]; nt++ } } }
        { s = 0; for (a = 0; a < 3; a++) for (b = 0; b < 3; b++) if (T[$1, a] == T[$2, b]) s++; if (s != 1) exit 1 }' "$DIR/extra" ||
        fail "self-contacts --shared-vertex $m: an extra pair does not share exactly one vertex"
done
[ "$(wc -l < "$DIR/self" | tr -d ' ')" -gt 400 ] || fail "self-contacts at 0.03: only $(wc -l < "$DIR/self") pairs"
run 0 mesh self-collide "$S"
set -- $(cat "$DIR/out")
[ "$1" = 1 ] && [ "$2" -lt "$3" ] || fail "self-collide: '$(cat "$DIR/out")'"
"$TTD" mesh self-contacts "$S" --margin 0 | awk -v i="$2" -v j="$3" '$1 == i && $2 == j { f = 1 } END { exit !f }' ||
    fail "self-collide's witness is not a self-contact at margin 0"
# the lower grid alone (the first 288 triangles) does not touch itself
head -n 169 "$S" > "$DIR/lower.obj"; grep '^f' "$S" | head -n 288 >> "$DIR/lower.obj"
run 0 mesh self-collide "$DIR/lower.obj"; [ "$(cat "$DIR/out")" = 0 ] || fail "a flat grid collides with itself"
run 0 mesh self-collide "$DIR/lower.obj" --margin 0.1; [ "$(cut -d' ' -f1 "$DIR/out")" = 1 ] || fail "self-collide --margin"
# threads, instruction sets and float
"$TTD" mesh self-contacts "$S" --margin 0.012 --shared-vertex --threads 1 > "$DIR/t1"
for isa in scalar sse2 avx2 avx512 neon portable; do
    "$TTD" mesh self-contacts "$S" --margin 0.012 --shared-vertex --threads 2 --isa "$isa" > "$DIR/t2" 2> /dev/null || continue
    cmp -s "$DIR/t1" "$DIR/t2" || fail "self-contacts with --isa $isa, 2 threads differ"
done
run 0 mesh self-contacts "$S" --margin 0.012 --precision float
cp "$DIR/out" "$DIR/self"
run 0 mesh contacts "$S" "$S" --margin 0.012 --precision float
not_shared "$DIR/out" > "$DIR/want"
[ -s "$DIR/self" ] && cmp -s "$DIR/self" "$DIR/want" || fail "self-contacts in float: not the pairs of contacts S S that share no vertex"
# errors
run 2 mesh self-contacts "$S"; err_has "--margin" "self-contacts without a margin"
run 2 mesh self-contacts "$S" "$S" --margin 1; err_has "one mesh file" "self-contacts with two files"
run 2 mesh self-contacts "$S" --margin 1 --pose '1 0 0 0 0 1 0 0 0 0 1 0'; err_has "--pose" "self-contacts --pose"
run 2 mesh self-contacts "$S" --margin 1 --per-triangle; err_has "--per-triangle" "self-contacts --per-triangle"
run 2 mesh self-collide "$S" --solid; err_has "--solid" "self-collide --solid"
run 2 mesh self-collide; err_has "missing" "self-collide without a file"
run 2 mesh contacts "$S" "$S" --margin 1 --shared-vertex; err_has "--shared-vertex" "contacts --shared-vertex"
run 2 mesh self-contacts "$S" --margin -1; err_has "--margin" "self-contacts negative margin"
run 1 mesh self-contacts "$DIR/missing.obj" --margin 1
pass "self-contacts and self-collide: the pairs of contacts S S that share no vertex, --shared-vertex, --count, witnesses, threads and ISAs, float, errors"

# ---- help ----------------------------------------------------------------------------------
run 0 mesh --help
for key in "mesh distance A B" "mesh contacts A B --margin M" "mesh collide A B" "d px py pz qx qy qz ia ib" \
           "ia ib d px py pz qx qy qz" "a ia ib d" "b ib ia d" "inf nan nan nan nan nan nan -1 -1" "1 ia ib" \
           "--poses FILE" "--pose P" "--orthonormalize" "--solid" "--strict" "bottom row must be 0 0 0 1" "--precision" "--isa" "--threads" "pose's index" "Exit status"; do
    grep -q -e "$key" "$DIR/out" || fail "mesh --help lacks '$key'"
done
run 0 mesh distance --help
grep -q "d px py pz qx qy qz ia ib" "$DIR/out" && ! grep -q "per-triangle" "$DIR/out" || fail "mesh distance --help"
run 0 mesh contacts --help; grep -q -e "--per-triangle" "$DIR/out" || fail "mesh contacts --help"
run 0 mesh collide -h; grep -q "1 ia ib" "$DIR/out" || fail "mesh collide -h"
run 0 --help; grep -q "mesh distance A B" "$DIR/out" || fail "ttd --help lacks mesh"
pass "help: ttd mesh --help, per command, ttd --help"

# --count counts without holding the pairs: a flat sheet of 4,050 triangles at a margin wider than
# the sheet has 8,175,640 self-contact pairs (every pair sharing no vertex: (4050 choose 2) =
# 8,199,225 less the 23,585 pairs that share one, counted from the grid), and against a copy of itself
# 0.5 above, 4050^2. Held, they would take over 500 MB (64 bytes each); counted, under a 400 MB
# limit on the process's address space they must still come out.
awk 'BEGIN { n = 45; for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) printf "v %g %g 0\n", i / n, j / n;
             for (j = 0; j < n; j++) for (i = 0; i < n; i++) { a = j * (n + 1) + i + 1; b = a + 1; c = a + n + 1;
                 printf "f %d %d %d\nf %d %d %d\n", a, b, c + 1, a, c + 1, c } }' > "$DIR/sheet.obj"
# (A sanitizer build reserves terabytes of address space for its shadow memory: there the counts
# are checked without the limit.)
limit=400000
grep -q '^TTD_SANITIZE:BOOL=ON' "$(dirname "$TTD")/../CMakeCache.txt" 2> /dev/null && limit=unlimited
got=$(ulimit -v $limit 2>/dev/null; "$TTD" mesh self-contacts "$DIR/sheet.obj" --margin 10 --count 2> "$DIR/err") ||
    fail "self-contacts --count under a $limit KB limit: $(cat "$DIR/err")"
[ "$got" = "8175640" ] || fail "self-contacts --count of the sheet: $got"
got=$(ulimit -v $limit 2>/dev/null; "$TTD" mesh contacts "$DIR/sheet.obj" "$DIR/sheet.obj" --margin 10 --count \
    --pose "1 0 0 0  0 1 0 0  0 0 1 0.5" 2> "$DIR/err") || fail "contacts --count under a $limit KB limit: $(cat "$DIR/err")"
[ "$got" = "16402500" ] || fail "contacts --count of the sheets: $got"
pass "--count: 8.2 and 16.4 million pairs counted under an address-space limit of $limit KB"
