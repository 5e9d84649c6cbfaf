#!/bin/sh
# SPDX-License-Identifier: MIT
# `ttd scene collide | distance | contacts | manifold` on scene files this script writes (a unit
# cube in OBJ, a tetrahedron in ASCII STL in a subfolder, a wedge in PLY and in binary STL),
# checked against an independent computation: each body's mesh moved into the world here in awk
# with the library's arithmetic (((r0 x + r1 y) + r2 z) + t, in double), written as an OBJ file,
# and `ttd mesh contacts | distance` run on every pair of those world meshes at the identity pose.
# The scene's lines must equal what those give, digit for digit:
#   - contacts: the mesh contacts of every body pair, 'i j' in front;
#   - collide: the body pairs that have a contact within the margin, each witness one of them;
#   - distance: the smallest contact distance over all pairs (also the `ttd mesh distance`
#     minimum), ties to the smallest (i, j) then (ia, ib), its points;
#   - manifold: at most K points per body pair, each a mesh contact's midpoint with its d and
#     depth or a corner of flat contact (a vertex, or two edges' closest points, at distance d,
#     checked here in awk to 1e-9), unit normals, no two points within 1e-3 of the smaller mesh
#     radius (which points are kept: tests/test_scene.c; the normal rule:
#     tests/test_scene_contacts.c);
#   - filter and exclude statements: every query equal to the unfiltered scene's lines less the
#     body pairs that the group/mask rule (computed here in awk) or an exclusion removes; body
#     names (referred to by name or number; --names prints them for i and j);
#   - --count; --stats and --repeat (same lines; the stats' results are the lines); --margin on distance as a bound; --max-points; --motion over 3 steps equal to a
#     scene file per step, with and without 'step' lines (their counts checked); blanks past the
#     4096-byte line limit; --precision float on a scene whose world coordinates are exact in
#     float (against `ttd mesh --precision float`); --threads 1, 2, 0 and every instruction set
#     identical; 16-number poses; --orthonormalize; standard input; an empty scene;
#   - every error path: the scene file's (unknown statement, missing fields, unknown and duplicate
#     mesh and body names, bad numbers, poses that are not rotations, unreadable and malformed mesh
#     files with the reader's message, coordinates beyond the range, bad filter and exclude
#     lines), the motion file's (wrong count of numbers, bad rotation, a trailing partial step, a
#     step whose pose count is not the bodies', misnumbered or mixed 'step' lines), the options'; FILE:LINE in the message,
#     a non-zero status, nothing on standard output.
# Only POSIX sh and awk. Usage: sh test_scene.sh path/to/ttd
set -u
TTD=${1:?usage: test_scene.sh path/to/ttd}
case $TTD in /*) ;; *) TTD=$(pwd)/$TTD ;; esac  # some checks run in other folders
DIR=$(mktemp -d) || exit 1
trap 'rm -rf "$DIR"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok   $*"; }

# ---- meshes ------------------------------------------------------------------------------
# A mesh description is 'v x y z' and 'f i j k [l]' lines (0-based); load() fan-triangulates as
# the reader does: (v0 v1 v2) (v0 v2 v3).
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
function u32(n,    k, b, out) {
    out = ""
    for (k = 0; k < 4; k++) { b = n % 256; out = out sprintf("\\%03o", b); n = (n - b) / 256 }
    return out
}
function f32(x,    s, e, bits) {
    if (x == 0) return u32(0)
    s = 0; if (x < 0) { s = 1; x = -x }
    e = 0; while (x >= 2) { x /= 2; e++ } while (x < 1) { x *= 2; e-- }
    bits = (x - 1) * 8388608
    if (bits != int(bits)) { print "f32: not a float: " x > "/dev/stderr"; exit 3 }
    return u32(s * 2147483648 + (e + 127) * 8388608 + bits)
}
function zeros(n,    out) { out = ""; while (n-- > 0) out = out "\\000"; return out }
EOF
LIB=$(cat "$DIR/lib.awk")
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
# A wedge: a triangular prism 0.5 long along x over the right triangle (0,0) (0.75,0) (0,0.5).
cat > "$DIR/wedge.mesh" <<'EOF'
v 0 0 0
v 0 0.75 0
v 0 0 0.5
v 0.5 0 0
v 0.5 0.75 0
v 0.5 0 0.5
f 0 2 1
f 3 4 5
f 0 1 4 3
f 0 3 5 2
f 1 2 5 4
EOF
mkdir -p "$DIR/sub"
awk '$1 == "v" { print "v", $2, $3, $4 } $1 == "f" { s = "f"; for (k = 2; k <= NF; k++) s = s " " ($k + 1); print s }' \
    "$DIR/cube.mesh" > "$DIR/cube.obj"
awk -v file="$DIR/tet.mesh" "$LIB"'BEGIN { load(1, file); print "solid tet"
    for (t = 0; t < NT[1]; t++) { print " facet normal 0 0 0"; print "  outer loop"
        for (c = 0; c < 3; c++) { i = TI[1, t, c]; print "   vertex", VX[1, i], VY[1, i], VZ[1, i] }
        print "  endloop"; print " endfacet" }
    print "endsolid tet" }' > "$DIR/sub/tet.stl"
awk 'BEGIN { print "ply"; print "format ascii 1.0" }
     $1 == "v" { v[nv++] = $2 " " $3 " " $4 } $1 == "f" { s = NF - 1; for (k = 2; k <= NF; k++) s = s " " $k; f[nf++] = s }
     END { print "element vertex " nv; print "property double x"; print "property double y"; print "property double z"
           print "element face " nf; print "property list uchar int vertex_indices"; print "end_header"
           for (i = 0; i < nv; i++) print v[i]; for (i = 0; i < nf; i++) print f[i] }' "$DIR/wedge.mesh" > "$DIR/wedge.ply"
printf "$(awk -v file="$DIR/wedge.mesh" "$LIB"'BEGIN { load(1, file); s = ""
    for (k = 0; k < 80; k++) s = s "\\040"
    s = s u32(NT[1])
    for (t = 0; t < NT[1]; t++) { s = s zeros(12)
        for (c = 0; c < 3; c++) { i = TI[1, t, c]; s = s f32(VX[1, i]) f32(VY[1, i]) f32(VZ[1, i]) }
        s = s zeros(2) }
    printf "%s", s }')" > "$DIR/wedge.stl"
[ "$(wc -c < "$DIR/wedge.stl" | tr -d ' ')" = $((84 + 50 * 8)) ] || fail "wedge.stl has $(wc -c < "$DIR/wedge.stl") bytes"

# ---- running and checking ----------------------------------------------------------------
run() { # run WANT-STATUS ARGS...: stdout in $DIR/out, stderr in $DIR/err
    want=$1; shift
    "$TTD" "$@" > "$DIR/out" 2> "$DIR/err"
    rc=$?
    [ $rc -lt 124 ] || fail "ttd $*: crash (status $rc): $(cat "$DIR/err")"
    [ $rc -eq "$want" ] || fail "ttd $*: status $rc, want $want: $(cat "$DIR/err")"
}
no_output() { [ ! -s "$DIR/out" ] || fail "$1: printed '$(head -c 200 "$DIR/out")'"; }
err_has() { grep -q -e "$1" "$DIR/err" || fail "$2: no '$1' in: $(cat "$DIR/err")"; }
same() { cmp -s "$1" "$2" || fail "$3: $(diff "$1" "$2" | head -5)"; }
# A scene: which mesh each body is (by name), and its pose. The mesh names map to the files
# above and to their descriptions for the reference.
mesh_desc() { case $1 in cube) echo "$DIR/cube.mesh" ;; tet) echo "$DIR/tet.mesh" ;; wedge|wedgeb) echo "$DIR/wedge.mesh" ;; esac; }
SCENE_HEAD='# meshes, in three formats (one of them in a subfolder), and a binary STL
mesh cube cube.obj
mesh tet   sub/tet.stl     # ASCII STL
mesh wedge wedge.ply
mesh wedgeb wedge.stl'
# write_scene FILE BODIES: BODIES holds 'NAME 12 numbers' lines; writes the scene file.
write_scene() {
    { echo "$SCENE_HEAD"; echo; echo "$2" | sed 's/^/body /'; } > "$1"
}
# world BODIES: $DIR/world/K.obj, body K's mesh moved by its pose (double arithmetic, %.17g).
world() {
    rm -rf "$DIR/world"; mkdir "$DIR/world"
    k=0
    echo "$1" | while read -r name rest; do
        [ -n "$name" ] || continue
        awk -v file="$(mesh_desc "$name")" -v pose="$rest" "$LIB"'BEGIN { load(1, file); split(pose, P, " ")
            for (i = 0; i < NV[1]; i++) { x = VX[1, i]; y = VY[1, i]; z = VZ[1, i]
                printf "v %.17g %.17g %.17g\n", ((P[1] * x + P[2] * y) + P[3] * z) + P[4],
                       ((P[5] * x + P[6] * y) + P[7] * z) + P[8], ((P[9] * x + P[10] * y) + P[11] * z) + P[12] }
            for (t = 0; t < NT[1]; t++) printf "f %d %d %d\n", TI[1, t, 0] + 1, TI[1, t, 1] + 1, TI[1, t, 2] + 1 }' \
            > "$DIR/world/$k.obj"
        k=$((k + 1))
    done
}
# ref_contacts N MARGIN [PREC]: 'i j ia ib d p q' over every pair of the N world meshes.
ref_contacts() {
    i=0
    while [ $i -lt "$1" ]; do
        j=$((i + 1))
        while [ $j -lt "$1" ]; do
            "$TTD" mesh contacts "$DIR/world/$i.obj" "$DIR/world/$j.obj" --margin "$2" --precision "${3:-double}" |
                sed "s/^/$i $j /" || fail "mesh contacts $i $j"
            j=$((j + 1))
        done
        i=$((i + 1))
    done
}
# ref_distance N [PREC]: the minimum of `ttd mesh distance` over every pair (its d only).
ref_distance_d() {
    i=0
    while [ $i -lt "$1" ]; do
        j=$((i + 1))
        while [ $j -lt "$1" ]; do
            "$TTD" mesh distance "$DIR/world/$i.obj" "$DIR/world/$j.obj" --precision "${2:-double}" | cut -d' ' -f1
            j=$((j + 1))
        done
        i=$((i + 1))
    done | awk 'NR == 1 || $1 + 0 < m + 0 { m = $1 } END { print m }'
}
# check_manifold GOT MARGIN K BODIES WHAT < contacts: GOT's manifold lines against the contact
# lines (double) and the world meshes ($DIR/world), per body pair: at most K lines (all kept where
# K = 0), at least one; each point either a contact's midpoint with its d and depth M - d, or a
# corner of flat contact (docs/scenes.md 5, step 0), checked here in double to 1e-9: a vertex of
# one body at d/2 from the point whose mirror image lies on the other body, or the midpoint of
# two edges' closest points (inside both) at distance d; a unit normal; no two points within the
# merge tolerance (1e-3 of the smaller mesh radius: from the vertices' bounding-box centre to the
# farthest vertex). Which points the reduction keeps is checked against brute force in
# tests/test_scene.c.
check_manifold() {
    echo "$4" > "$DIR/bodies.txt"
    awk -v m="$2" -v K="$3" -v got="$1" -v bodies="$DIR/bodies.txt" -v cube="$DIR/cube.mesh" -v tet="$DIR/tet.mesh" \
        -v wedge="$DIR/wedge.mesh" -v world="$DIR/world" "$LIB"'
    function radius(k,    v, r, lo, hi, c, d2, best) {
        for (r = 0; r < 3; r++) { lo[r] = 1e300; hi[r] = -1e300 }
        for (v = 0; v < NV[k]; v++) { X[0] = VX[k, v]; X[1] = VY[k, v]; X[2] = VZ[k, v]
            for (r = 0; r < 3; r++) { if (X[r] < lo[r]) lo[r] = X[r]; if (X[r] > hi[r]) hi[r] = X[r] } }
        for (r = 0; r < 3; r++) c[r] = 0.5 * lo[r] + 0.5 * hi[r]
        best = 0
        for (v = 0; v < NV[k]; v++) { X[0] = VX[k, v]; X[1] = VY[k, v]; X[2] = VZ[k, v]
            d2 = 0; for (r = 0; r < 3; r++) d2 += (X[r] - c[r]) * (X[r] - c[r]); if (d2 > best) best = d2 }
        return sqrt(best) * (1 + 4 * 2.220446049250313e-16) }
    function wload(b,    file, line, f) { file = world "/" b ".obj"; WN[b] = 0; WNT[b] = 0
        while ((getline line < file) > 0) { split(line, f, " ")
            if (f[1] == "v") { WX[b, WN[b], 0] = f[2] + 0; WX[b, WN[b], 1] = f[3] + 0; WX[b, WN[b], 2] = f[4] + 0; WN[b]++ }
            else if (f[1] == "f") { WF[b, WNT[b], 0] = f[2] - 1; WF[b, WNT[b], 1] = f[3] - 1; WF[b, WNT[b], 2] = f[4] - 1; WNT[b]++ } }
        close(file) }
    function clamp01(x) { return x < 0 ? 0 : x > 1 ? 1 : x }
    # the distance from point P[0..2] to segment A B (arrays), and its parameter in SPAR
    function pseg(P, A, B,    r, ab, ap, L, t, d2) { L = 0; t = 0
        for (r = 0; r < 3; r++) { ab[r] = B[r] - A[r]; ap[r] = P[r] - A[r]; L += ab[r] * ab[r]; t += ab[r] * ap[r] }
        t = L > 0 ? clamp01(t / L) : 0; SPAR = t; d2 = 0
        for (r = 0; r < 3; r++) d2 += (ap[r] - t * ab[r]) ^ 2
        return sqrt(d2) }
    # the distance between segments A B and C D (Ericson: the closest points of two segments)
    function segseg(A, B, C, D,    r, d1, d2, w, a, e, f, c, b, den, s, t, x) {
        a = e = f = c = b = 0
        for (r = 0; r < 3; r++) { d1[r] = B[r] - A[r]; d2[r] = D[r] - C[r]; w[r] = A[r] - C[r]
            a += d1[r] * d1[r]; e += d2[r] * d2[r]; f += d2[r] * w[r]; c += d1[r] * w[r]; b += d1[r] * d2[r] }
        den = a * e - b * b; s = den > 1e-30 * a * e ? clamp01((b * f - c * e) / den) : 0
        t = (b * s + f) / e
        if (t < 0) { t = 0; s = clamp01(-c / a) } else if (t > 1) { t = 1; s = clamp01((b - c) / a) }
        x = 0; for (r = 0; r < 3; r++) x += (w[r] + s * d1[r] - t * d2[r]) ^ 2
        return sqrt(x) }
    # the distance from point P to triangle u of body b, as the largest of its distances to the
    # plane (inside the triangle) or the smallest to its edges
    function ptri(P, b, u,    r, k, A, B, C, e1, e2, n, ln, h, w, best, x, s0, s1, s2) {
        for (r = 0; r < 3; r++) { A[r] = WX[b, WF[b, u, 0], r]; B[r] = WX[b, WF[b, u, 1], r]; C[r] = WX[b, WF[b, u, 2], r]
            e1[r] = B[r] - A[r]; e2[r] = C[r] - A[r]; w[r] = P[r] - A[r] }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1]; n[1] = e1[2] * e2[0] - e1[0] * e2[2]; n[2] = e1[0] * e2[1] - e1[1] * e2[0]
        ln = sqrt(n[0] ^ 2 + n[1] ^ 2 + n[2] ^ 2); h = (w[0] * n[0] + w[1] * n[1] + w[2] * n[2]) / ln
        s0 = side(A, B, P, n); s1 = side(B, C, P, n); s2 = side(C, A, P, n)
        if (s0 >= 0 && s1 >= 0 && s2 >= 0) return h < 0 ? -h : h
        best = pseg(P, A, B); x = pseg(P, B, C); if (x < best) best = x; x = pseg(P, C, A); if (x < best) best = x
        return best }
    function side(A, B, P, n,    ab, ap, c) {
        ab[0] = B[0] - A[0]; ab[1] = B[1] - A[1]; ab[2] = B[2] - A[2]; ap[0] = P[0] - A[0]; ap[1] = P[1] - A[1]; ap[2] = P[2] - A[2]
        c[0] = ab[1] * ap[2] - ab[2] * ap[1]; c[1] = ab[2] * ap[0] - ab[0] * ap[2]; c[2] = ab[0] * ap[1] - ab[1] * ap[0]
        return c[0] * n[0] + c[1] * n[1] + c[2] * n[2] }
    # whether point X at distance d is a corner of body pair (bi, bj): a vertex or two edges
    function corner(X, d, bi, bj,    sd, b, o, v, r, V, Q, u, best, x, ti, tj, k, l, A, B, C, D, pa, pb) {
        for (sd = 0; sd < 2; sd++) { b = sd ? bj : bi; o = sd ? bi : bj
            for (v = 0; v < WN[b]; v++) { x = 0
                for (r = 0; r < 3; r++) { V[r] = WX[b, v, r]; Q[r] = 2 * X[r] - V[r]; x += (X[r] - V[r]) ^ 2 }
                if ((sqrt(x) - d / 2) ^ 2 > 1e-18) continue
                best = 1e300; for (u = 0; u < WNT[o]; u++) { x = ptri(Q, o, u); if (x < best) best = x }
                if (best <= 1e-9) return 1 } }
        for (ti = 0; ti < WNT[bi]; ti++) for (k = 0; k < 3; k++) {
            for (r = 0; r < 3; r++) { A[r] = WX[bi, WF[bi, ti, k], r]; B[r] = WX[bi, WF[bi, ti, (k + 1) % 3], r] }
            x = pseg(X, A, B); pa = SPAR; if ((x - d / 2) ^ 2 > 1e-18 || pa <= 1e-12 || pa >= 1 - 1e-12) continue
            for (tj = 0; tj < WNT[bj]; tj++) for (l = 0; l < 3; l++) {
                for (r = 0; r < 3; r++) { C[r] = WX[bj, WF[bj, tj, l], r]; D[r] = WX[bj, WF[bj, tj, (l + 1) % 3], r] }
                x = pseg(X, C, D); pb = SPAR; if ((x - d / 2) ^ 2 > 1e-18 || pb <= 1e-12 || pb >= 1 - 1e-12) continue
                if ((segseg(A, B, C, D) - d) ^ 2 <= 1e-18) return 1 } }
        return 0 }
    BEGIN { load(1, cube); load(2, tet); load(3, wedge); for (k = 1; k <= 3; k++) RAD[k] = radius(k); nb = 0
        while ((getline line < bodies) > 0) { n = split(line, f, " "); if (n < 13) continue
            wload(nb); MB[nb++] = f[1] == "cube" ? 1 : f[1] == "tet" ? 2 : 3 }
        while ((getline line < got) > 0) { split(line, f, " "); key = f[1] " " f[2]
            G[key, NG[key]++] = line; if (!(key in SEEN)) { SEEN[key] = 1; gorder[ng++] = key } } }
    { key = $1 " " $2; if (!(key in N)) { order[np++] = key; N[key] = 0 }
      L[key, N[key]++] = $0
      OWN[key, sprintf("%.17g %.17g %.17g %.17g %.17g", 0.5 * ($6 + 0) + 0.5 * ($9 + 0), 0.5 * ($7 + 0) + 0.5 * ($10 + 0),
                       0.5 * ($8 + 0) + 0.5 * ($11 + 0), $5 + 0, m - $5)] = 1 }
    END {
        for (q = 0; q < ng; q++) if (!(gorder[q] in N)) { print "points for pair " gorder[q] " without contacts"; exit 1 }
        for (q = 0; q < np; q++) { key = order[q]; n = N[key]; split(key, ij, " ")
            ri = RAD[MB[ij[1]]]; rj = RAD[MB[ij[2]]]; tol = 1e-3 * (ri < rj ? ri : rj)
            if (NG[key] < 1 || (K > 0 && NG[key] > K)) { print "pair " key ": " NG[key] " points, K " K; exit 1 }
            for (a = 0; a < NG[key]; a++) { split(G[key, a], f, " ")
                if (!((key, f[3] " " f[4] " " f[5] " " f[9] " " f[10]) in OWN)) {
                    X[0] = f[3] + 0; X[1] = f[4] + 0; X[2] = f[5] + 0
                    if (!(f[9] + 0 <= m && f[10] + 0 == m - f[9]) || !corner(X, f[9] + 0, ij[1], ij[2])) {
                        print "pair " key ": neither a contact nor a corner: " G[key, a]; exit 1 }
                    ++CORNERS }
                l = f[6] * f[6] + f[7] * f[7] + f[8] * f[8]
                if (l < 1 - 1e-12 || l > 1 + 1e-12) { print "normal not unit: " G[key, a]; exit 1 }
                # the points of both bodies: the point their midpoint, their distance |d|; the key 16 hex digits
                l = 0; for (r = 0; r < 3; r++) { l += (f[11 + r] - f[14 + r]) ^ 2
                    if ((0.5 * f[11 + r] + 0.5 * f[14 + r] - f[3 + r]) ^ 2 > 1e-24) { print "point not the midpoint of the points of its bodies: " G[key, a]; exit 1 } }
                if ((sqrt(l) - (f[9] < 0 ? -f[9] : f[9])) ^ 2 > 1e-18 || length(f[17]) != 16 || f[17] !~ /^[0-9a-f]+$/) { print "points of the bodies or key: " G[key, a]; exit 1 }
                for (b = 0; b < a; b++) { split(G[key, b], g, " "); d2 = 0
                    for (r = 3; r <= 5; r++) d2 += (f[r] - g[r]) * (f[r] - g[r])
                    if (sqrt(d2) <= tol * (1 - 1e-9)) { print "pair " key ": two points within " tol; exit 1 } } } }
        print CORNERS + 0 >> (world "/../corners") }' \
        > "$DIR/diff" || fail "$5: $(cat "$DIR/diff")"
}

# ---- the double scene --------------------------------------------------------------------
# Six bodies: a cube at the origin; a tetrahedron turned about y near its face x = 1 (0.2 off,
# by construction below); the wedge turned about z near its back face y = 1; a cube turned by a
# general rotation, crossing the first; a tetrahedron far away; the binary-STL wedge touching
# the first cube's bottom corner (z = -0.5 .. 0, d = 0) from below.
BODIES='cube   1 0 0 0  0 1 0 0  0 0 1 0
tet    0.6 0 0.8 1.2  0 1 0 0.25  -0.8 0 0.6 0.3
wedge  0 -1 0 0.75  1 0 0 1.1  0 0 1 0.2
cube   0.36 0.48 -0.8 0.3  -0.8 0.6 0 0.4  0.48 0.64 0.6 0.9
tet    1 0 0 5  0 1 0 5  0 0 1 5
wedgeb 1 0 0 0  0 1 0 0  0 0 1 -0.5'
NB=6
write_scene "$DIR/scene.txt" "$BODIES"
world "$BODIES"
rm -f "$DIR/corners"
for m in 0 0.15 0.35; do
    ref_contacts $NB $m > "$DIR/want"
    [ -s "$DIR/want" ] || fail "reference: no contacts at margin $m"
    run 0 scene contacts "$DIR/scene.txt" --margin $m
    same "$DIR/out" "$DIR/want" "contacts --margin $m against the world meshes' mesh contacts"
    run 0 scene contacts "$DIR/scene.txt" --margin $m --count
    [ "$(cat "$DIR/out")" = "$(wc -l < "$DIR/want" | tr -d ' ')" ] || fail "contacts --count $m: $(cat "$DIR/out")"
    # counted without holding the contacts: the same number on 1 and 2 threads, in float too
    for t in 1 2; do
        run 0 scene contacts "$DIR/scene.txt" --margin $m --count --threads $t
        [ "$(cat "$DIR/out")" = "$(wc -l < "$DIR/want" | tr -d ' ')" ] || fail "contacts --count --threads $t $m: $(cat "$DIR/out")"
    done
    "$TTD" scene contacts "$DIR/scene.txt" --margin $m --precision float | wc -l | tr -d ' ' > "$DIR/want_f"
    run 0 scene contacts "$DIR/scene.txt" --margin $m --count --precision float
    cmp -s "$DIR/out" "$DIR/want_f" || fail "contacts --count --float $m: $(cat "$DIR/out") against $(cat "$DIR/want_f")"
    # collide: the body pairs with contacts, each witness among them
    cut -d' ' -f1,2 "$DIR/want" | uniq > "$DIR/want_pairs"
    run 0 scene collide "$DIR/scene.txt" --margin $m
    cut -d' ' -f1,2 "$DIR/out" | cmp -s - "$DIR/want_pairs" || fail "collide --margin $m: pairs $(cut -d' ' -f1,2 "$DIR/out" | tr '\n' ,)"
    awk 'NR == FNR { w[$1 " " $2 " " $3 " " $4] = 1; next } NF != 4 || !(($1 " " $2 " " $3 " " $4) in w) { print; exit 1 }' \
        "$DIR/want" "$DIR/out" > /dev/null || fail "collide --margin $m: a witness not within the margin"
    run 0 scene collide "$DIR/scene.txt" --margin $m --count
    [ "$(cat "$DIR/out")" = "$(wc -l < "$DIR/want_pairs" | tr -d ' ')" ] || fail "collide --count $m"
    # --stats and --repeat: the same answer, and the library's stats of the last run on stderr
    # (its results are the lines printed; every result was a pair given to the kernel)
    run 0 scene contacts "$DIR/scene.txt" --margin $m --repeat 3 --stats
    same "$DIR/out" "$DIR/want" "contacts --margin $m --repeat 3 --stats"
    awk -v n="$(wc -l < "$DIR/want" | tr -d ' ')" '/candidate body pairs/ {
            if ($11 + 0 < $15 + 0 || $15 + 0 != n || $4 + 0 < 1) exit 1; found = 1 }
        END { exit !found }' "$DIR/err" || fail "contacts --stats $m: $(cat "$DIR/err")"
    # manifold, K = 4 (default), 2 and 0 (all)
    for k in 4 2 0; do
        if [ $k = 4 ]; then run 0 scene manifold "$DIR/scene.txt" --margin $m; else run 0 scene manifold "$DIR/scene.txt" --margin $m --max-points $k; fi
        cp "$DIR/out" "$DIR/got_m"
        check_manifold "$DIR/got_m" $m $k "$BODIES" "manifold --margin $m --max-points $k against the mesh contacts" < "$DIR/want"
        run 0 scene manifold "$DIR/scene.txt" --margin $m --max-points $k --count
        [ "$(cat "$DIR/out")" = "$(wc -l < "$DIR/got_m" | tr -d ' ')" ] || fail "manifold --count $m $k"
    done
done
# The expected pairs at 0.35: (0,1) 0.2 apart, (0,2) 0.1 apart, (0,3) crossing, (0,5) touching;
# never the far body 4.
cut -d' ' -f1,2 "$DIR/want" | uniq | tr '\n' , > "$DIR/pairs"
for p in "0 1," "0 2," "0 3," "0 5,"; do grep -q "$p" "$DIR/pairs" || fail "scene pairs at 0.35 lack $p: $(cat "$DIR/pairs")"; done
! grep -q "4" "$DIR/pairs" || fail "scene pairs at 0.35 include the far body: $(cat "$DIR/pairs")"
[ "$(awk '$1 == 0 && $2 == 5 && $5 == 0' "$DIR/want" | wc -l)" -gt 0 ] || fail "no touching pair (0, 5)"
[ "$(awk '$1 == 0 && $2 == 3 && $5 == 0' "$DIR/want" | wc -l)" -gt 0 ] || fail "no crossing pair (0, 3)"
[ "$(awk '{ s += $1 } END { print s + 0 }' "$DIR/corners")" -gt 0 ] || fail "manifold: no corner of flat contact among the points"
pass "contacts, collide, manifold (K 4, 2, all), --count at margins 0, 0.15, 0.35: equal to (manifold: drawn from) the world meshes' mesh contacts and their corners"

# distance: the smallest contact over all pairs (a margin holding every pair), ties to the
# smallest (i, j) then (ia, ib): the first such line in the sorted contacts.
ref_contacts $NB 20 > "$DIR/all"
[ "$(cut -d' ' -f1,2 "$DIR/all" | uniq | wc -l)" -eq 15 ] || fail "margin 20 does not hold every pair"
awk 'NR == 1 || $5 + 0 < m + 0 { m = $5; line = $0 } END { split(line, f, " ")
     print f[5], f[1], f[2], f[3], f[4], f[6], f[7], f[8], f[9], f[10], f[11] }' "$DIR/all" > "$DIR/want"
run 0 scene distance "$DIR/scene.txt"
same "$DIR/out" "$DIR/want" "distance against the smallest contact"
[ "$(cut -d' ' -f1 "$DIR/out")" = "$(ref_distance_d $NB)" ] || fail "distance: not the minimum of ttd mesh distance"
# Without the crossing and touching bodies: gaps, the wedge 0.1 from the cube (the tetrahedron 0.2).
BODIES2=$(echo "$BODIES" | sed -n '1,3p;5p')
write_scene "$DIR/scene2.txt" "$BODIES2"
world "$BODIES2"
ref_contacts 4 20 | awk 'NR == 1 || $5 + 0 < m + 0 { m = $5; line = $0 } END { split(line, f, " ")
     print f[5], f[1], f[2], f[3], f[4], f[6], f[7], f[8], f[9], f[10], f[11] }' > "$DIR/want"
run 0 scene distance "$DIR/scene2.txt"
same "$DIR/out" "$DIR/want" "distance of a scene with gaps"
awk '{ e = $1 - 0.1; if (e < 0) e = -e; exit !(e < 1e-15 && $2 == 0 && $3 == 2) }' "$DIR/out" || fail "distance: $(cat "$DIR/out"), want 0.1 between 0 and 2"
# --margin on distance is an upper bound: at or above the minimum the same line, below it none.
run 0 scene distance "$DIR/scene2.txt" --margin 0.15
same "$DIR/out" "$DIR/want" "distance --margin above the minimum"
run 0 scene distance "$DIR/scene2.txt" --margin "$(cut -d' ' -f1 "$DIR/want")"
same "$DIR/out" "$DIR/want" "distance --margin at the minimum"
run 0 scene distance "$DIR/scene2.txt" --margin 0.05
[ "$(cat "$DIR/out")" = "inf -1 -1 -1 -1 nan nan nan nan nan nan" ] || fail "distance beyond the bound: $(cat "$DIR/out")"
# --nearest: after that line, each body's nearest from the contact lines, as the body sees it
# (its own triangle and point first), ties to the smallest partner, then triangles; within the
# margin, 'inf' lines beyond it.
nearest_want() { # N [MARGIN] < contact lines (i j ia ib d p q)
    awk -v n="$1" -v m="${2:-inf}" 'function consider(s, o, ts, to, d, ps, po) {
        if (m != "inf" && d + 0 > m + 0) return
        if (!(s in bd) || d + 0 < bd[s] + 0 || (d + 0 == bd[s] + 0 && (o + 0 < bo[s] + 0 ||
            (o + 0 == bo[s] + 0 && (ts + 0 < bts[s] + 0 || (ts + 0 == bts[s] + 0 && to + 0 < bto[s] + 0)))))) {
            bd[s] = d; bo[s] = o; bts[s] = ts; bto[s] = to
            line[s] = d " " s " " o " " ts " " to " " ps " " po } }
      { consider($1, $2, $3, $4, $5, $6 " " $7 " " $8, $9 " " $10 " " $11)
        consider($2, $1, $4, $3, $5, $9 " " $10 " " $11, $6 " " $7 " " $8) }
      END { for (b = 0; b < n; ++b) print (b in line) ? line[b] : "inf " b " -1 -1 -1 nan nan nan nan nan nan" }'
}
write_scene "$DIR/scene.txt" "$BODIES"
world "$BODIES"
ref_contacts $NB 20 > "$DIR/all"
run 0 scene distance "$DIR/scene.txt" --nearest
head -n 1 "$DIR/out" > "$DIR/got1"
run 0 scene distance "$DIR/scene.txt"
same "$DIR/got1" "$DIR/out" "distance --nearest: its first line"
run 0 scene distance "$DIR/scene.txt" --nearest
tail -n +2 "$DIR/out" > "$DIR/got"
nearest_want $NB < "$DIR/all" > "$DIR/want"
same "$DIR/got" "$DIR/want" "distance --nearest against the contacts"
write_scene "$DIR/scene2.txt" "$BODIES2"
world "$BODIES2"
ref_contacts 4 20 > "$DIR/all"
for m in 20 0.15 0.1; do
    run 0 scene distance "$DIR/scene2.txt" --nearest --margin $m --threads 2
    tail -n +2 "$DIR/out" > "$DIR/got"
    nearest_want 4 $m < "$DIR/all" > "$DIR/want"
    same "$DIR/got" "$DIR/want" "distance --nearest --margin $m against the contacts (a scene with gaps)"
done
run 2 scene contacts "$DIR/scene.txt" --nearest
pass "distance: the smallest contact over every pair (also the ttd mesh distance minimum), ties by (i, j, ia, ib); --margin as an upper bound; --nearest: each body's nearest from the contacts"

# ---- filter and exclude statements, body names ------------------------------------------------
# The same six bodies, the cube 0 named floor and the wedge 2 named lid; the cube 0 and the
# crossing cube 3 in group 2 seeing group 1 only (so not each other, as a bin's walls), the
# touching wedge 5 in group 4 (which 0's mask leaves out), 0 and 2 excluded; rules referred to by
# name and by number. The same rules with numbers only, for the reference below.
NAMED=$(echo "$BODIES" | sed '1s/$/  name floor/; 3s/$/ name lid   # the wedge/')
{ echo "$SCENE_HEAD"; echo "$NAMED" | sed 's/^/body /'
  printf 'filter floor 2 0x1\nfilter 3 2 1   # the crossing cube\nfilter 5 4 0xFFFFFFFF\nexclude lid floor\n'; } > "$DIR/filtered.txt"
printf 'filter 0 2 1\nfilter 3 2 1\nfilter 5 4 4294967295\nexclude 0 2\n' > "$DIR/rules.txt"
# eligible COL < LINES: the lines whose bodies i = $COL, j = $(COL + 1) are a pair under rules.txt:
# (group_i & mask_j) != 0, (group_j & mask_i) != 0 (each body group 1, mask all ones unless a
# rule says otherwise), and not excluded.
eligible() {
    awk -v c="$1" -v rules="$DIR/rules.txt" '
    function band(a, b,    r, p) { r = 0; p = 1
        while (a > 0 && b > 0) { if (a % 2 == 1 && b % 2 == 1) r += p; a = int(a / 2); b = int(b / 2); p *= 2 }
        return r }
    function g(i) { return (i in G) ? G[i] : 1 }
    function m(i) { return (i in M) ? M[i] : 4294967295 }
    BEGIN { while ((getline l < rules) > 0) { split(l, f, " ")
        if (f[1] == "filter") { G[f[2]] = f[3]; M[f[2]] = f[4] } else { X[f[2] " " f[3]] = 1; X[f[3] " " f[2]] = 1 } } }
    { i = $c; j = $(c + 1) }
    band(g(i), m(j)) != 0 && band(g(j), m(i)) != 0 && !((i " " j) in X)'
}
for q in "contacts --margin 0.35" "collide --margin 0.35" "manifold --margin 0.35" "manifold --margin 0.15 --max-points 0" \
         "contacts --margin 0.35 --precision float"; do
    # shellcheck disable=SC2086
    "$TTD" scene $q "$DIR/scene.txt" | eligible 1 > "$DIR/want" || fail "$q on the unfiltered scene"
    # shellcheck disable=SC2086
    run 0 scene $q "$DIR/filtered.txt"
    same "$DIR/out" "$DIR/want" "$q with filters and an exclusion"
done
cut -d' ' -f1,2 "$DIR/out" | uniq | tr '\n' , > "$DIR/pairs"
[ "$(cat "$DIR/pairs")" = "0 1," ] || fail "filtered pairs at 0.35 (unfiltered: 0 1, 0 2, 0 3, 0 5): $(cat "$DIR/pairs")"
eligible 1 < "$DIR/all" | awk 'NR == 1 || $5 + 0 < m + 0 { m = $5; line = $0 } END { split(line, f, " ")
     print f[5], f[1], f[2], f[3], f[4], f[6], f[7], f[8], f[9], f[10], f[11] }' > "$DIR/want"
run 0 scene distance "$DIR/filtered.txt"
same "$DIR/out" "$DIR/want" "distance with filters and an exclusion"
[ "$(cut -d' ' -f2,3 "$DIR/out")" != "0 3" ] || fail "distance: the filtered pair (0, 3)"
# --names: the same lines with floor and lid for 0 and 2; unnamed bodies keep their numbers.
for q in "contacts --margin 20" "manifold --margin 0.35" "distance"; do
    col=1; case $q in distance) col=2 ;; esac
    # shellcheck disable=SC2086
    "$TTD" scene $q "$DIR/filtered.txt" | awk -v c=$col '{ for (k = c; k <= c + 1; k++) $k = $k == 0 ? "floor" : $k == 2 ? "lid" : $k } 1' > "$DIR/want"
    grep -q "floor" "$DIR/want" || fail "--names $q: the reference names nothing"
    # shellcheck disable=SC2086
    run 0 scene $q "$DIR/filtered.txt" --names
    same "$DIR/out" "$DIR/want" "$q --names"
done
# A bin as a user writes it: four static walls in group 2 with mask 1 (they never pair with each
# other), a ball in group 1 among them, touching each; the walls would otherwise pair with their
# neighbours where they touch.
{ echo "mesh cube cube.obj"
  echo "body cube 1 0 0 -1  0 1 0 0  0 0 1 0  name west";  echo "body cube 1 0 0 1  0 1 0 0  0 0 1 0  name east"
  echo "body cube 1 0 0 0  0 1 0 -1  0 0 1 0  name south"; echo "body cube 1 0 0 0  0 1 0 1  0 0 1 0  name north"
  echo "body cube 1 0 0 0  0 1 0 0  0 0 1 0  name ball"
  for w in west east south north; do echo "filter $w 2 1"; done; } > "$DIR/bin.txt"
sed '/^filter/d' "$DIR/bin.txt" > "$DIR/bin0.txt"
run 0 scene collide "$DIR/bin0.txt" --names
[ "$(cat "$DIR/out" | cut -d' ' -f1,2 | tr '\n' ,)" = "west south,west north,west ball,east south,east north,east ball,south ball,north ball," ] ||
    fail "the unfiltered bin: $(cat "$DIR/out" | tr '\n' ,)"
run 0 scene collide "$DIR/bin.txt" --names
[ "$(cat "$DIR/out" | cut -d' ' -f1,2 | tr '\n' ,)" = "west ball,east ball,south ball,north ball," ] ||
    fail "the filtered bin: $(cat "$DIR/out" | tr '\n' ,)"
pass "filter and exclude statements: every query equals the unfiltered scene's less the pairs the rules remove; names by reference and --names"

# ---- --motion: 3 steps, each equal to a scene file at those poses ----------------------------
STEP0=$BODIES
STEP1=$(echo "$BODIES" | sed '2s/.*/tet    0.6 0 0.8 1.05  0 1 0 0.25  -0.8 0 0.6 0.3/;5s/.*/tet    1 0 0 1.5  0 1 0 1.5  0 0 1 1/')
STEP2=$(echo "$BODIES" | sed '4s/.*/cube   1 0 0 3  0 1 0 0  0 0 1 0/;6s/.*/wedgeb 0 -1 0 0  1 0 0 0  0 0 1 -0.6/')
{ echo "# three steps of $NB poses"; for s in "$STEP0" "$STEP1" "$STEP2"; do echo "$s" | cut -c8-; echo; done
  echo "# end"; } > "$DIR/motion.txt"
for q in "collide --margin 0.1" "collide --margin 0.1 --count" "distance" "contacts --margin 0.05" "contacts --margin 0.05 --count" \
         "manifold --margin 0.05" "manifold --margin 0.05 --max-points 0 --count"; do
    : > "$DIR/want"
    k=0
    for s in "$STEP0" "$STEP1" "$STEP2"; do
        write_scene "$DIR/step.txt" "$s"
        # shellcheck disable=SC2086
        "$TTD" scene $q "$DIR/step.txt" | sed "s/^/$k /" >> "$DIR/want" || fail "$q on step $k"
        k=$((k + 1))
    done
    # shellcheck disable=SC2086
    run 0 scene $q "$DIR/scene.txt" --motion "$DIR/motion.txt"
    same "$DIR/out" "$DIR/want" "$q --motion"
done
[ "$(wc -l < "$DIR/want")" -eq 3 ] || fail "--count over 3 steps: $(cat "$DIR/want")"
# the steps differ (the motion is not a no-op)
[ "$("$TTD" scene contacts "$DIR/scene.txt" --margin 0.05 --motion "$DIR/motion.txt" --count | cut -d' ' -f2 | sort -u | wc -l)" -gt 1 ] ||
    fail "--motion: every step has the same count"
# from standard input; an empty motion gives no output
"$TTD" scene contacts "$DIR/scene.txt" --margin 0.05 --motion - < "$DIR/motion.txt" > "$DIR/out2" || fail "--motion -"
"$TTD" scene contacts "$DIR/scene.txt" --margin 0.05 --motion "$DIR/motion.txt" | cmp -s - "$DIR/out2" || fail "--motion - differs"
printf '# nothing\n\n' > "$DIR/nomotion.txt"
run 0 scene distance "$DIR/scene.txt" --motion "$DIR/nomotion.txt"; no_output "empty motion"
pass "--motion: 3 steps equal to a scene file per step (collide, distance, contacts, manifold, --count); from standard input"

# 'step' lines: the same motion opened step by step ('step' alone or with its index) reads the
# same; blanks beyond the 4096-byte line limit are no error, in the scene file or the motion.
blanks=$(awk 'BEGIN { s = ""; for (i = 0; i < 5000; i++) s = s " "; printf "%s\t", s }')
{ echo "# three steps of $NB poses"; k=0
  for s in "$STEP0" "$STEP1" "$STEP2"; do
      if [ $k = 1 ]; then echo "step 1   # the second"; else echo "  step$blanks"; fi
      echo "$s" | cut -c8- | sed "2s/\$/$blanks/"; k=$((k + 1)); done; } > "$DIR/motion_steps.txt"
{ echo "$SCENE_HEAD$blanks"; echo "$BODIES" | sed "s/^/body /; 1s/\$/$blanks/"; echo "$blanks"; } > "$DIR/scene_blanks.txt"
[ "$(head -n 1 "$DIR/motion_steps.txt" | wc -c)" -lt 4096 ] && [ "$(sed -n 2p "$DIR/motion_steps.txt" | wc -c)" -gt 5000 ] || fail "step lines: the test file"
for q in "contacts --margin 0.05" "manifold --margin 0.05 --count" "distance"; do
    # shellcheck disable=SC2086
    "$TTD" scene $q "$DIR/scene.txt" --motion "$DIR/motion.txt" > "$DIR/want" || fail "$q"
    # shellcheck disable=SC2086
    run 0 scene $q "$DIR/scene_blanks.txt" --motion "$DIR/motion_steps.txt"
    same "$DIR/out" "$DIR/want" "$q --motion with 'step' lines and trailing blanks"
done
"$TTD" scene contacts "$DIR/filtered.txt" --margin 0.35 --motion "$DIR/motion.txt" |
    awk '{ $2 = $2 == 0 ? "floor" : $2 == 2 ? "lid" : $2; $3 = $3 == 2 ? "lid" : $3 } 1' > "$DIR/want"
run 0 scene contacts "$DIR/filtered.txt" --margin 0.35 --motion "$DIR/motion.txt" --names
same "$DIR/out" "$DIR/want" "--names with --motion"
pass "--motion with 'step' lines ('step', 'step S'); blanks past the line limit in scene and motion files; --names"

# ---- threads, instruction sets, poses of 16 numbers, --orthonormalize, standard input --------
for q in "collide --margin 0.1" "distance" "contacts --margin 0.35" "manifold --margin 0.35 --max-points 3"; do
    # shellcheck disable=SC2086
    "$TTD" scene $q "$DIR/scene.txt" --motion "$DIR/motion.txt" --threads 1 > "$DIR/ref" || fail "$q --threads 1"
    for opt in "--threads 2" "--threads 0" "--threads 5"; do
        # shellcheck disable=SC2086
        "$TTD" scene $q "$DIR/scene.txt" --motion "$DIR/motion.txt" $opt | cmp -s - "$DIR/ref" || fail "$q $opt differs from --threads 1"
    done
    for isa in scalar sse2 avx2 avx512 neon portable; do
        # shellcheck disable=SC2086
        "$TTD" scene $q "$DIR/scene.txt" --motion "$DIR/motion.txt" --isa $isa > "$DIR/out" 2> "$DIR/err"
        rc=$?
        if [ $rc -eq 2 ]; then grep -q "not available" "$DIR/err" || fail "--isa $isa: $(cat "$DIR/err")"; continue; fi
        [ $rc -eq 0 ] || fail "$q --isa $isa: status $rc"
        cmp -s "$DIR/out" "$DIR/ref" || fail "$q --isa $isa differs"
    done
done
pass "threads 1, 2, 0, 5 and every available instruction set: identical output"

{ echo "$SCENE_HEAD"; echo "$BODIES" | sed 's/^/body /; s/$/  0 0 0 1   # 4x4/'; } > "$DIR/scene16.txt"
run 0 scene contacts "$DIR/scene16.txt" --margin 0.35
"$TTD" scene contacts "$DIR/scene.txt" --margin 0.35 | cmp -s - "$DIR/out" || fail "16-number body poses differ from their 12"
{ echo "$STEP0" | cut -c8- | sed 's/$/ 0 0 0 1/'; echo "$STEP1" | cut -c8-; } > "$DIR/motion16.txt"
run 0 scene distance "$DIR/scene.txt" --motion "$DIR/motion16.txt"
[ "$(wc -l < "$DIR/out")" -eq 2 ] || fail "16-number motion poses"
# A rotation printed with 5 digits: refused, repaired by --orthonormalize (the exact rotation's
# distance within 1e-12).
C5=0.70711; CX=0.70710678118654752
write_scene "$DIR/rot5.txt" "cube 1 0 0 0  0 1 0 0  0 0 1 0
tet $C5 -$C5 0 3  $C5 $C5 0 0  0 0 1 0"
write_scene "$DIR/rotx.txt" "cube 1 0 0 0  0 1 0 0  0 0 1 0
tet $CX -$CX 0 3  $CX $CX 0 0  0 0 1 0"
run 1 scene distance "$DIR/rot5.txt"; no_output "5-digit rotation"
err_has "rot5.txt:8: body 1: not a rotation: R is not orthonormal (an entry of R^T R - I is 9.1e-06" "5-digit rotation"
run 0 scene distance "$DIR/rot5.txt" --orthonormalize
awk -v want="$("$TTD" scene distance "$DIR/rotx.txt" | cut -d' ' -f1)" '{ e = $1 - want; if (e < 0) e = -e; exit !(e < 1e-12) }' "$DIR/out" ||
    fail "--orthonormalize: $(cat "$DIR/out")"
# The scene from standard input: mesh files relative to the working folder.
(cd "$DIR" && "$TTD" scene contacts - --margin 0.35 < scene.txt) > "$DIR/out2" || fail "scene from standard input"
"$TTD" scene contacts "$DIR/scene.txt" --margin 0.35 | cmp -s - "$DIR/out2" || fail "scene from standard input differs"
# Relative to the scene file's folder, from anywhere.
(cd "$DIR/sub" && "$TTD" scene collide ../scene.txt --margin 0.1) > "$DIR/out2" || fail "scene from another folder"
"$TTD" scene collide "$DIR/scene.txt" --margin 0.1 | cmp -s - "$DIR/out2" || fail "scene from another folder differs"
# No bodies, one body: nothing to report; distance says so.
{ echo "$SCENE_HEAD"; } > "$DIR/empty.txt"
run 0 scene contacts "$DIR/empty.txt" --margin 1; no_output "empty scene"
run 0 scene collide "$DIR/empty.txt" --count; [ "$(cat "$DIR/out")" = 0 ] || fail "empty scene --count"
write_scene "$DIR/one.txt" "cube 1 0 0 0  0 1 0 0  0 0 1 0"
run 0 scene distance "$DIR/one.txt"
[ "$(cat "$DIR/out")" = "inf -1 -1 -1 -1 nan nan nan nan nan nan" ] || fail "one body: $(cat "$DIR/out")"
pass "16-number poses (scene and motion), --orthonormalize, standard input, mesh paths from the scene's folder, empty scenes"

# ---- float: a scene whose world coordinates are exact in float -----------------------------
FBODIES='cube   1 0 0 0  0 1 0 0  0 0 1 0
tet    0 -1 0 1.25  1 0 0 0.25  0 0 1 0.5
wedge  1 0 0 0.25  0 0 -1 1.125  0 1 0 0.25
cube   0 0 1 -1  0 1 0 0.5  -1 0 0 1.75
wedgeb 0 1 0 0.5  0 0 1 0.25  1 0 0 -0.5'
write_scene "$DIR/fscene.txt" "$FBODIES"
world "$FBODIES"
for m in 0 0.25; do
    ref_contacts 5 $m float > "$DIR/want"
    [ -s "$DIR/want" ] || fail "float reference: no contacts at $m"
    run 0 scene contacts "$DIR/fscene.txt" --margin $m --precision float
    same "$DIR/out" "$DIR/want" "float contacts --margin $m against ttd mesh --precision float"
    run 0 scene collide "$DIR/fscene.txt" --margin $m --precision float
    cut -d' ' -f1,2 "$DIR/want" | uniq > "$DIR/wp"
    cut -d' ' -f1,2 "$DIR/out" | cmp -s - "$DIR/wp" || fail "float collide $m"
done
ref_contacts 5 20 float | awk 'NR == 1 || $5 + 0 < m + 0 { m = $5; line = $0 } END { split(line, f, " ")
     print f[5], f[1], f[2], f[3], f[4], f[6], f[7], f[8], f[9], f[10], f[11] }' > "$DIR/want"
run 0 scene distance "$DIR/fscene.txt" --precision float
same "$DIR/out" "$DIR/want" "float distance"
run 0 scene manifold "$DIR/fscene.txt" --margin 0.25 --precision float
[ -s "$DIR/out" ] && awk 'NF != 17 || length($17) != 16 || $17 !~ /^[0-9a-f]+$/ { exit 1 } { for (k = 3; k <= 16; k++) if ($k !~ /^-?[0-9.e+-]+$/) exit 1
     n = $6 * $6 + $7 * $7 + $8 * $8; if (n < 1 - 1e-6 || n > 1 + 1e-6) exit 1 }' "$DIR/out" ||
    fail "float manifold: $(head -3 "$DIR/out")"
# float prints 9 significant digits at most
awk '{ for (k = 1; k < NF; k++) { s = $k; sub(/e.*/, "", s); gsub(/[-.]/, "", s); sub(/^0+/, "", s); if (length(s) > 9) exit 1 } }' "$DIR/out" ||
    fail "float manifold: more than 9 digits"
pass "--precision float: contacts, collide, distance equal to ttd mesh --precision float on the world meshes; manifold well formed"

# ---- solids ------------------------------------------------------------------------------
# A unit cube sunk 0.1 into another (offset 0.1, 0.2), solid by --solid or by 'solid' lines: the
# same lines; the deepest point at depth M + 0.1 with normal +z, every point below 0 at d = -0.1
# (a corner of one cube inside the other) with depth M - d; as surfaces, no point below 0.
awk '/^v/ { print "v", $2 * 0.5, $3 * 0.5, $4 * 0.5; next } { print }' "$DIR/cube.obj" > "$DIR/half.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$DIR/open.obj"
SOLID_HEAD='mesh cube cube.obj
mesh half half.obj
mesh open open.obj'
printf '%s\nbody cube 1 0 0 0  0 1 0 0  0 0 1 0 name low\nbody cube 1 0 0 0.1  0 1 0 0.2  0 0 1 0.9\n' "$SOLID_HEAD" > "$DIR/sunk.txt"
run 0 scene manifold "$DIR/sunk.txt" --margin 0.01 --solid --max-points 0
cp "$DIR/out" "$DIR/sunk_solid"
awk 'BEGIN { deepest = -1 } { d = $9 + 0; depth = $10 + 0; if (depth > deepest) { deepest = depth; nz = $8 + 0 }
     e = depth - (0.01 - d); if (e < 0) e = -e; if (e > 1e-15) { print "depth " $0; exit 1 }
     if (d < 0 && (d + 0.1 > 1e-12 || d + 0.1 < -1e-12)) { print "d " $0; exit 1 } if (d < 0) below++ }
     END { e = deepest - 0.11; if (e < 0) e = -e; if (e > 1e-12 || nz != 1 || below < 2) { print "deepest " deepest " nz " nz " below " below; exit 1 } }' \
    "$DIR/sunk_solid" > "$DIR/diff" || fail "sunk cube, --solid: $(cat "$DIR/diff")"
{ cat "$DIR/sunk.txt"; echo "solid low"; echo "solid 1  # by number"; } > "$DIR/sunk2.txt"
run 0 scene manifold "$DIR/sunk2.txt" --margin 0.01 --max-points 0
same "$DIR/out" "$DIR/sunk_solid" "sunk cube: 'solid' lines against --solid"
run 0 scene manifold "$DIR/sunk.txt" --margin 0.01 --max-points 0
awk '$9 < 0 { exit 1 }' "$DIR/out" || fail "sunk cube as surfaces: a point below 0"
# A half cube inside the unit cube: as solids, collide at 0 finds the pair (the inner body's
# triangle 0, -1 for the outer), distance is 0 at the inner body's first vertex, the manifold's
# points lie below 0, the deepest at the penetration depth 0.75 along an axis; as surfaces,
# nothing collides.
printf '%s\nbody cube 1 0 0 0  0 1 0 0  0 0 1 0\nbody half 1 0 0 0.25  0 1 0 0.25  0 0 1 0.25\n' "$SOLID_HEAD" > "$DIR/nest.txt"
run 0 scene collide "$DIR/nest.txt" --solid
[ "$(cat "$DIR/out")" = "0 1 -1 0" ] || fail "nested solids, collide: $(cat "$DIR/out")"
run 0 scene distance "$DIR/nest.txt" --solid
[ "$(cat "$DIR/out")" = "0 0 1 -1 0 0.25 0.25 0.25 0.25 0.25 0.25" ] || fail "nested solids, distance: $(cat "$DIR/out")"
run 0 scene manifold "$DIR/nest.txt" --solid --max-points 0
# 8 vertices inside at -0.25 and the pair's penetration depth, 0.75 (the half cube leaves along an axis; docs/scenes.md 5b)
[ "$(wc -l < "$DIR/out" | tr -d ' ')" = 9 ] && awk '!($9 < 0) { exit 1 } $9 < -0.5 { deep++; if ($9 != -0.75 || $6 * $6 + $7 * $7 + $8 * $8 != 1 || $6 * $7 != 0 || $7 * $8 != 0 || $6 * $8 != 0) exit 1 }
    END { if (deep != 1) exit 1 }' "$DIR/out" || fail "nested solids, manifold: $(cat "$DIR/out")"
run 0 scene collide "$DIR/nest.txt"; no_output "nested surfaces collide"
# An open mesh cannot be a solid.
printf '%s\nbody open 1 0 0 0  0 1 0 0  0 0 1 0\n' "$SOLID_HEAD" > "$DIR/open.txt"
run 1 scene collide "$DIR/open.txt" --solid; no_output "--solid on an open mesh"
err_has "open.txt: --solid: body 0: a mesh is not closed" "--solid on an open mesh"
{ cat "$DIR/open.txt"; echo "solid 0"; } > "$DIR/open2.txt"
run 1 scene collide "$DIR/open2.txt"; no_output "solid on an open mesh"
err_has "open2.txt:5: solid: a mesh is not closed" "solid on an open mesh"
pass "solids: a cube sunk 0.1 (depth M + 0.1, +z; --solid and 'solid' lines alike), a cube inside a cube (collide, distance 0, points below 0), open meshes refused"

# ---- errors: the scene file ------------------------------------------------------------------
P0='1 0 0 0  0 1 0 0  0 0 1 0'
bad_scene() { # bad_scene WHAT PATTERN LINES...: a scene of the head and LINES, refused with PATTERN
    what=$1; pat=$2; shift 2
    { echo "$SCENE_HEAD"; for l in "$@"; do echo "$l"; done; } > "$DIR/bad.txt"
    run 1 scene contacts "$DIR/bad.txt" --margin 1; no_output "$what"; err_has "$pat" "$what"
    err_has "bad.txt: [0-9]* bad lines\{0,1\}; nothing computed" "$what (summary)"
}
bad_scene "unknown statement" "bad.txt:6: unknown statement 'bodies' (mesh, body, filter, exclude or solid)" "bodies cube $P0"
bad_scene "solid without BODY" "bad.txt:6: expected 'solid BODY', found no BODY" "solid"
bad_scene "solid with more" "bad.txt:7: expected 'solid BODY', found more words" "body cube $P0" "solid 0 1"
bad_scene "solid of no body" "bad.txt:7: solid: no body 3 (the body lines above this one are 0 to 0)" "body cube $P0" "solid 3"
bad_scene "unknown mesh" "bad.txt:7: body 1: unknown mesh 'cub' (a 'mesh NAME FILE' line must come first)" "body cube $P0" "body cub $P0"
bad_scene "duplicate mesh" "bad.txt:6: mesh 'tet' is already defined" "mesh tet cube.obj"
bad_scene "mesh without FILE" "bad.txt:6: expected 'mesh NAME FILE', found no FILE" "mesh foo  # a comment"
bad_scene "mesh without NAME" "bad.txt:6: expected 'mesh NAME FILE', found no NAME" "mesh"
bad_scene "mesh with more" "bad.txt:6: expected 'mesh NAME FILE', found more words" "mesh foo cube.obj extra"
bad_scene "body without MESH" "bad.txt:6: expected 'body MESH'" "body"
bad_scene "11 numbers" "bad.txt:6: body 0: expected 12 numbers (\[R | t\], 3x4) or 16 (a 4x4 matrix), found 11" "body cube 1 0 0 0 0 1 0 0 0 0 1"
bad_scene "no numbers" "bad.txt:6: body 0: expected 12 numbers (\[R | t\], 3x4) or 16 (a 4x4 matrix), found 0" "body cube # none"
bad_scene "17 numbers" "bad.txt:6: body 0: expected 12 or 16 numbers, found 17 or more" "body cube $P0 0 0 0 1 1"
bad_scene "bottom row" "bad.txt:6: body 0: the bottom row of a 4x4 pose must be 0 0 0 1, found 0 0 0 2" "body cube $P0 0 0 0 2"
bad_scene "bad number" "bad.txt:6: body 0: field 4 is not a number: 'x'" "body cube 1 0 0 x  0 1 0 0  0 0 1 0"
bad_scene "nan" "bad.txt:6: body 0: field 12 is not finite" "body cube 1 0 0 0  0 1 0 0  0 0 1 nan"
bad_scene "not orthonormal" "bad.txt:6: body 0: not a rotation: R is not orthonormal (an entry of R^T R - I is 3, at most 1e-6" "body cube 2 0 0 0  0 2 0 0  0 0 2 0"
bad_scene "reflection" "bad.txt:7: body 1: not a rotation: det R = -1 <= 0 (a reflection)" "body cube $P0" "body tet -1 0 0 0  0 1 0 0  0 0 1 0"
bad_scene "missing mesh file" "bad.txt:6: mesh 'x': .*nothere.obj: cannot open" "mesh x nothere.obj" "body x $P0"
printf 'v 0 0 0\nv 1 0 0\nf 1 2 9\n' > "$DIR/broken.obj"
bad_scene "malformed mesh file" "bad.txt:6: mesh 'x': .*broken.obj:3: " "mesh x broken.obj" "body x $P0"
bad_scene "beyond the range" "bad.txt:6: body 0: a mesh coordinate (or one moved by a pose) beyond" "body cube 1 0 0 1e300  0 1 0 0  0 0 1 0"
awk 'BEGIN { s = "body cube"; for (i = 0; i < 500; i++) s = s " 0.000000000"; print s }' > "$DIR/long.txt"
bad_scene "overlong line" "bad.txt:6: line longer than 4096 bytes" "$(cat "$DIR/long.txt")"
bad_scene "name without BODY" "bad.txt:6: body 0: expected 'name BODY' at the end of the line, found no BODY" "body cube $P0 name # none"
bad_scene "name and more" "bad.txt:6: body 0: expected 'name BODY' at the end of the line, found more words" "body cube $P0 name a b"
bad_scene "name with a digit" "bad.txt:6: body 0: the name '2a' starts with a digit" "body cube $P0 name 2a"
bad_scene "duplicate name" "bad.txt:7: body 1: the name 'a' is body 0's already" "body cube $P0 name a" "body tet $P0 name a"
bad_scene "name after 11 numbers" "bad.txt:6: body 0: expected 12 numbers .* found 11" "body cube 1 0 0 0 0 1 0 0 0 0 1 name a"
bad_scene "filter without BODY" "bad.txt:7: expected 'filter BODY GROUP MASK', found no BODY" "body cube $P0" "filter"
bad_scene "filter without MASK" "bad.txt:7: expected 'filter BODY GROUP MASK', found no MASK" "body cube $P0" "filter 0 1 # none"
bad_scene "filter with more" "bad.txt:7: expected 'filter BODY GROUP MASK', found more words" "body cube $P0" "filter 0 1 2 3"
bad_scene "filter before bodies" "bad.txt:6: filter: no body 0 (no body line comes before this one)" "filter 0 1 1" "body cube $P0"
bad_scene "filter of a later body" "bad.txt:7: filter: no body 1 (the body lines above this one are 0 to 0)" "body cube $P0" "filter 1 1 1" "body cube $P0"
bad_scene "filter of an unknown name" "bad.txt:7: filter: unknown body 'lid' (a body line naming it must come first)" "body cube $P0" "filter lid 1 1"
bad_scene "filter of a bad reference" "bad.txt:7: filter: '0x' is neither a body number nor a name" "body cube $P0" "filter 0x 1 1"
bad_scene "group beyond 32 bits" "bad.txt:7: filter: GROUP '0x100000000' is not a 32-bit number" "body cube $P0" "filter 0 0x100000000 1"
bad_scene "negative mask" "bad.txt:7: filter: MASK '-1' is not a 32-bit number" "body cube $P0" "filter 0 1 -1"
bad_scene "mask beyond 32 bits" "bad.txt:7: filter: MASK '4294967296' is not a 32-bit number" "body cube $P0" "filter 0 1 4294967296"
bad_scene "exclude one body" "bad.txt:7: expected 'exclude BODY BODY', found one BODY" "body cube $P0" "exclude 0"
bad_scene "exclude a body twice" "bad.txt:7: exclude: body 0 twice" "body cube $P0 name a" "exclude a 0"
bad_scene "exclude an unknown body" "bad.txt:8: exclude: unknown body 'b'" "body cube $P0 name a" "body cube $P0" "exclude a b"
# Every bad line is named, not only the first; a body of a mesh that failed is not named again.
bad_scene "several" "bad.txt:9: body 2: field 1 is not a number" "mesh x nothere.obj" "body x $P0" "body cube $P0" "body cube y 0 0 0  0 1 0 0  0 0 1 0" "what"
err_has "bad.txt:6: mesh 'x'" "several: the mesh"; err_has "bad.txt:10: unknown statement 'what'" "several: the last"
err_has "bad.txt: 3 bad lines; nothing computed" "several: 3 bad lines (the body of the failed mesh is not one)"
# float: a pose beyond float range, a mesh beyond float's coordinate range
{ echo "$SCENE_HEAD"; echo "body cube 1 0 0 1e39  0 1 0 0  0 0 1 0"; } > "$DIR/bad.txt"
run 1 scene collide "$DIR/bad.txt" --precision float; no_output "float pose"; err_has "bad.txt:6: body 0: field 4 is out of float range" "float pose"
printf 'v 2e18 0 0\nv 2e18 1 0\nv 2e18 0 1\nf 1 2 3\n' > "$DIR/big19.obj"
{ echo "mesh big big19.obj"; } > "$DIR/bad.txt"
run 1 scene collide "$DIR/bad.txt" --precision float; no_output "float mesh"; err_has "bad.txt:1: mesh 'big': .*big19.obj: cannot build the mesh: a mesh coordinate" "float mesh"
run 1 scene collide "$DIR/nothere.txt"; no_output "missing scene"; err_has "nothere.txt: cannot open" "missing scene"
run 1 scene collide "$DIR"; no_output "scene a directory"; err_has "read error" "scene a directory"
pass "errors: scene files (every bad line FILE:LINE, exit 1, nothing printed)"

# ---- errors: the motion file ---------------------------------------------------------------
bad_motion() { # bad_motion WHAT PATTERN: $DIR/badm.txt refused with PATTERN
    run 1 scene collide "$DIR/scene.txt" --motion "$DIR/badm.txt"; no_output "$1"; err_has "$2" "$1"
    err_has "badm.txt: [0-9]* bad lines\{0,1\}; nothing computed" "$1 (summary)"
}
{ echo "$STEP0" | cut -c8-; echo "$STEP1" | cut -c8- | sed '3s/ 0.2$//'; } > "$DIR/badm.txt"
bad_motion "11 numbers" "badm.txt:9: step 1, body 2: expected 12 numbers (\[R | t\], 3x4) or 16 (a 4x4 matrix), found 11"
{ echo "$STEP0" | cut -c8- | sed '4s/^.*$/0.36 0.48 -0.8 0.3  -0.8 0.6 0 0.4  -0.48 -0.64 -0.6 1.05/'; } > "$DIR/badm.txt"
bad_motion "reflection" "badm.txt:4: step 0, body 3: not a rotation: det R = -1"
{ echo "$STEP0" | cut -c8- | sed '2s/^.*$/1 0.01 0 0  0 1 0 0  0 0 1 0/'; } > "$DIR/badm.txt"
bad_motion "not orthonormal" "badm.txt:2: step 0, body 1: not a rotation: R is not orthonormal"
{ echo "$STEP0" | cut -c8- | sed '2s/^.*$/1 0 0 1e300  0 1 0 0  0 0 1 0/'; } > "$DIR/badm.txt"
bad_motion "beyond the range" "badm.txt:2: step 0, body 1: a mesh coordinate (or one moved by a pose) beyond"
{ echo "$STEP0" | cut -c8-; echo "# step 1, cut short"; echo "$STEP1" | cut -c8- | sed -n '1,2p'; } > "$DIR/badm.txt"
bad_motion "partial step" "badm.txt:8: step 1 is incomplete: 2 of 6 poses (one per body), to the end of the file"
{ echo "$STEP0" | cut -c8-; echo "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 7"; } > "$DIR/badm.txt"
bad_motion "17 numbers" "badm.txt:7: step 1, body 0: expected 12 or 16 numbers, found 17 or more"
run 1 scene collide "$DIR/scene.txt" --motion "$DIR/nothere.txt"; no_output "missing motion"; err_has "nothere.txt: cannot open" "missing motion"
# 'step' lines: a step of fewer or more poses than bodies (as a motion written for another scene
# whose line count happens to be a multiple of this one's bodies), a misnumbered or malformed
# 'step' line, one after poses without them.
{ echo "$STEP0" | sed -n '1,3p' | cut -c8- | sed '1s/^/step\n/'; echo step; echo "$STEP0" | sed -n '1,3p' | cut -c8-
  echo step; echo "$STEP0" | sed -n '1,3p' | cut -c8-; echo step; echo "$STEP0" | sed -n '1,3p' | cut -c8-; } > "$DIR/badm.txt"
[ "$(grep -c '^[0-9-]' "$DIR/badm.txt")" = 12 ] || fail "step lines: the test file"
bad_motion "a step of half the bodies" "badm.txt:1: step 0 has 3 poses where the scene has 6 bodies"
err_has "badm.txt:13: step 3 has 3 poses" "the last short step"
{ echo step; echo "$STEP0" | cut -c8-; echo "$STEP0" | sed -n 1p | cut -c8-; echo step; echo "$STEP1" | cut -c8-; } > "$DIR/badm.txt"
bad_motion "a step of too many poses" "badm.txt:8: step 0: more poses than the scene's 6 bodies"
{ echo step 0; echo "$STEP0" | cut -c8-; echo step 2; echo "$STEP1" | cut -c8-; } > "$DIR/badm.txt"
bad_motion "a misnumbered step" "badm.txt:8: 'step 2' where step 1 comes"
{ echo "step x"; echo "$STEP0" | cut -c8-; echo "step 1 2"; echo "$STEP1" | cut -c8-; } > "$DIR/badm.txt"
bad_motion "a malformed step" "badm.txt:1: expected 'step' or 'step S' (S the step's index, from 0), found an index that is not a whole number"
err_has "badm.txt:8: expected 'step' or 'step S' (S the step's index, from 0), found more words" "a step line with more words"
{ echo "$STEP0" | cut -c8-; echo step; echo "$STEP1" | cut -c8-; } > "$DIR/badm.txt"
bad_motion "a step line after unmarked poses" "badm.txt:7: a 'step' line, but the poses above it had none"
echo "$P0" > "$DIR/badm.txt"
run 1 scene collide "$DIR/empty.txt" --motion "$DIR/badm.txt"; no_output "motion of no bodies"
err_has "badm.txt:1: a pose, but the scene has no bodies" "motion of no bodies"
pass "errors: motion files (wrong count, not a rotation, beyond the range, a trailing partial step, 'step' lines; FILE:LINE, exit 1)"

# ---- errors: the command line (exit 2) ------------------------------------------------------
for m in -1 nan inf abc '' 1e999; do
    run 2 scene contacts "$DIR/scene.txt" --margin "$m"; no_output "margin '$m'"; err_has "bad value for --margin" "margin '$m'"
done
run 2 scene contacts "$DIR/scene.txt" --margin 1e39 --precision float; err_has "bad value for --margin" "float margin"
run 2 scene contacts "$DIR/scene.txt" --margin; err_has "--margin needs a value" "--margin without a value"
run 2 scene distance "$DIR/scene.txt" --count; err_has "--count is an option of scene collide, contacts and manifold" "--count on distance"
run 2 scene contacts "$DIR/scene.txt" --max-points 3; err_has "--max-points is an option of scene manifold only" "--max-points on contacts"
for k in -1 x 1.5 ''; do run 2 scene manifold "$DIR/scene.txt" --max-points "$k"; err_has "bad value for --max-points" "--max-points '$k'"; done
run 2 scene collide "$DIR/scene.txt" --precision half; err_has "bad value for --precision" "--precision"
run 2 scene collide "$DIR/scene.txt" --isa nosuch; err_has "bad value for --isa" "--isa"
run 2 scene collide "$DIR/scene.txt" --threads -1; err_has "bad value for --threads" "--threads"
run 2 scene collide "$DIR/scene.txt" --bogus; err_has "unknown option '--bogus'" "unknown option"
run 2 scene collide; err_has "the scene file is missing" "no operand"
run 2 scene collide "$DIR/scene.txt" "$DIR/scene.txt"; err_has "unexpected argument" "two operands"
run 2 scene collide - --motion -; err_has "standard input cannot hold both" "two stdin"
run 2 scene nearest "$DIR/scene.txt"; err_has "unknown command 'nearest'" "unknown command"
run 2 scene; err_has "usage: ttd scene" "no command"
run 2 scene collide "$DIR/nothere.txt" --bogus; err_has "unknown option" "usage errors before files"
if [ -w /dev/full ]; then
    "$TTD" scene contacts "$DIR/scene.txt" --margin 1 > /dev/full 2> "$DIR/err"
    [ $? -eq 1 ] || fail "output to /dev/full: status not 1"; err_has "error writing the output" "/dev/full"
fi
pass "errors: options and operands (exit 2)"

# ---- help ----------------------------------------------------------------------------------
run 0 scene --help
for key in "scene collide SCENE" "scene distance SCENE" "scene contacts SCENE" "scene manifold SCENE" "mesh NAME FILE" \
           "body MESH r00 r01 r02 t0" "name BODY" "filter BODY GROUP MASK" "exclude BODY BODY" "--names" "'step S'" "i j ia ib" "d i j ia ib px py pz qx qy qz" "i j ia ib d px py pz qx qy qz" \
           "i j px py pz nx ny nz d depth" "inf -1 -1 -1 -1 nan nan nan nan nan nan" "default 0" "--max-points K" \
           "default 4" "--motion FILE" "--count" "--precision" "--isa" "--threads" "--orthonormalize" "Exit status"; do
    grep -q -e "$key" "$DIR/out" || fail "scene --help lacks '$key'"
done
run 0 scene manifold -h; grep -q "depth" "$DIR/out" || fail "scene manifold -h"
run 0 --help; grep -q "scene collide SCENE" "$DIR/out" || fail "ttd --help lacks scene"
pass "help: ttd scene --help, ttd --help"
