#!/usr/bin/env bash
# Instruction mix of ttd's kernels per triangle pair, counted by valgrind's callgrind (there
# are no hardware counters on this machine). Runs `ttd dist` on PAIRS random pairs (the
# `random` family's distribution: vertices uniform in the unit cube, the second triangle
# shifted by a uniform offset in [-0.5,0.5]^3), counts only instructions executed inside the
# kernel functions (lane kernels `kernel_*`, scalar kernels `ttd_scalar_*`, and what they
# call), and classifies them from the disassembly. AVX-512 code cannot run under valgrind
# 3.19; use avx2, sse2 or scalar.
#
# Usage: bench/instr_mix.sh TTD ISA METHOD PRECISION [PAIRS [FAMILY]]
#   e.g. bench/instr_mix.sh build/cli/ttd avx2 exact double 4000
#   FAMILY is random (default) or paper (the paper's workload: gen/pairs.h's fixed pair,
#   S = (0,0,0) (1,0,0) (0,1,0), T = (0.3,0.3,0.5) (1,0.5,1.2) (0.4,1.1,0.9), replicated), or
#   file:PATH, pairs in `ttd dist --binary-in`'s format (float64, or float32 for float), such as
#   `ttd bench --save-pairs DIR` writes (DIR/mesh-near.f64 ...); its first PAIRS pairs are used.
# Also prints callgrind's simulated branch predictor: conditional and indirect branches per
# pair and how many it mispredicts (a model, not the CPU's predictor, but it separates
# data-dependent branching from predictable loops).
# Prints, per pair: instructions; floating-point operations (FMA = 2, counted over every lane
# of each vector instruction, active or not); the instruction classes; memory operations,
# with those on the stack (%rsp/%rbp: spills and reloads under register pressure) apart.
#
# bench/instr_mix.sh --fcl FCL_BENCH PRECISION PAIRS file:PATH
# FCL's triDistance (build/cli/ttd_fcl_bench) on the same pairs: instructions per pair.
#
# bench/instr_mix.sh --static TTD
# Prints, for every copy of every lane kernel in the binary (one per ISA and precision), its
# static instruction count and the share that touches the stack: a register-pressure measure
# that also covers AVX-512, which valgrind cannot run.
set -euo pipefail
if [ "${1:-}" = "--static" ] && [ $# -eq 2 ]; then
  objdump -d --no-show-raw-insn "$2" | awk '
    /^[0-9a-f]+ <(kernel_[a-z_]+|kx_run_[a-z]+|kw_load_group)>:$/ { name = $2; gsub(/[<>:]/, "", name); infn = 1; n = 0; st = 0; z = 0; y = 0; next }
    infn && /^$/ { isa = z ? "avx512" : (y ? "avx2" : "sse2 or other")
      printf "%-22s %-13s static instructions %5d, touching the stack %5d (%.0f%%)\n", name, isa, n, st, n ? 100 * st / n : 0
      infn = 0; next }
    infn && /^ *[0-9a-f]+:\t/ { n++; if ($0 ~ /\(%rsp|\(%rbp/ && $0 !~ /\tlea/) st++
      if ($0 ~ /%zmm|%k[0-7]/) z = 1; if ($0 ~ /%ymm/) y = 1 }'
  exit 0
fi
if [ "${1:-}" = "--fcl" ] && [ $# -eq 5 ]; then
  # FCL's triangle distance on the same pairs: instructions per call of triDistance (inclusive,
  # scalar code; no mix, its double instance lives in libfcl.so). ttd_fcl_bench makes three
  # passes over the pairs with MIN_SAMPLE_SECONDS 0 and 1 repeat (warm-up, calibration, sample).
  fcl=$2 prec=$3 n=$4 src=${5#file:}
  command -v valgrind >/dev/null || { echo "instr_mix.sh: valgrind is not installed" >&2; exit 1; }
  bytes=8; [ "$prec" = float ] && bytes=4
  have=$(( $(stat -c %s "$src") / (18 * bytes) )); [ "$n" -gt "$have" ] && n=$have
  tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
  # ttd_fcl_bench's input: "TTDW", version 1, bytes per real, pad, n; then every S, then every T
  python3 - "$src" "$tmp/in.bin" "$n" "$bytes" <<'PY'
import struct, sys
src, dst, n, b = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
raw = open(src, 'rb').read(n * 18 * b)
rec = [raw[18 * b * i:18 * b * (i + 1)] for i in range(n)]
with open(dst, 'wb') as f:
    f.write(b'TTDW' + struct.pack('<IIIQ', 1, b, 0, n))
    f.write(b''.join(r[:9 * b] for r in rec))
    f.write(b''.join(r[9 * b:] for r in rec))
PY
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$fcl" "$tmp/in.bin" "$tmp/out.bin" 0 1 \
    > /dev/null 2> "$tmp/vg.err" || { cat "$tmp/vg.err" >&2; exit 1; }
  callgrind_annotate --inclusive=yes "$tmp/cg.out" 2>/dev/null | grep -m1 'triDistance' |
    awk -v n="$n" -v prec="$prec" -v f="$(basename "$src")" '{ gsub(/,/, "", $1)
      printf "fcl %s, %d %s pairs: %.1f instructions per pair in triDistance (3 passes)\n", prec, n, f, $1 / (3 * n) }'
  exit 0
fi
[ $# -ge 4 ] || { sed -n '2,24p' "$0" >&2; exit 2; }
ttd=$1 isa=$2 method=$3 prec=$4 n=${5:-4000} family=${6:-random}
command -v valgrind >/dev/null || { echo "instr_mix.sh: valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

case $family in
  random) awk -v n="$n" 'BEGIN { srand(12345)
            for (i = 0; i < n; ++i) { l = ""
              for (k = 0; k < 9; ++k) l = l sprintf("%.17g ", rand())
              o[0] = rand() - 0.5; o[1] = rand() - 0.5; o[2] = rand() - 0.5
              for (k = 0; k < 9; ++k) l = l sprintf("%.17g ", rand() + o[k % 3])
              print l } }' > "$tmp/pairs.txt" ;;
  paper) awk -v n="$n" 'BEGIN { for (i = 0; i < n; ++i)
            print "0 0 0 1 0 0 0 1 0 0.3 0.3 0.5 1 0.5 1.2 0.4 1.1 0.9" }' > "$tmp/pairs.txt" ;;
  file:*) src=${family#file:}; bytes=8; [ "$prec" = float ] && bytes=4
          have=$(( $(stat -c %s "$src") / (18 * bytes) ))
          [ "$have" -ge 1 ] || { echo "instr_mix.sh: $src holds no whole pair" >&2; exit 2; }
          [ "$n" -gt "$have" ] && n=$have
          head -c $(( n * 18 * bytes )) "$src" > "$tmp/pairs.bin"
          family=$(basename "$src") ;;
  *) echo "instr_mix.sh: FAMILY is random, paper or file:PATH" >&2; exit 2 ;;
esac
input=("$tmp/pairs.txt")
[ -f "$tmp/pairs.bin" ] && input=(--binary-in "$tmp/pairs.bin")

case $isa in scalar) pattern='ttd_scalar_*' ;; *) pattern='kernel_*' ;; esac
valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" --dump-instr=yes --compress-pos=no --branch-sim=yes \
  --compress-strings=no --toggle-collect="$pattern" \
  "$ttd" dist --isa "$isa" --method "$method" --precision "$prec" --threads 1 "${input[@]}" \
  > /dev/null 2> "$tmp/vg.err" || { cat "$tmp/vg.err" >&2; exit 1; }

# Self cost per instruction address in the whole collected range (kernels and their callees);
# the line after calls= is the inclusive cost of a call, counted where it is spent instead.
# Columns after the address and line: Ir Bc Bcm Bi Bim (missing trailing ones are zero).
awk '/^calls=/ { skip = 1; next }
     /^0x/ { if (skip) { skip = 0; next } c[$1] += $3; bc += $4; bcm += $5; bi += $6; bim += $7 }
     END { for (a in c) if (c[a] > 0) print a, c[a]; print "branches", bc + 0, bcm + 0, bi + 0, bim + 0 }' \
  "$tmp/cg.out" > "$tmp/counts"
objdump -d --no-show-raw-insn "$ttd" > "$tmp/dis"
# Shared objects (libm's sqrt, memcpy) have no lines in the disassembly: counted as "other".

awk -v n="$n" -v isa="$isa" -v method="$method" -v prec="$prec" -v family="$family" '
  FNR == NR && $1 == "branches" { bc = $2; bcm = $3; bi = $4; bim = $5; next }
  FNR == NR { sub(/^0x0*/, "", $1); cnt[$1] = $2; total += $2; next }
  /^ *[0-9a-f]+:\t/ {
    addr = $1; sub(/:$/, "", addr); sub(/^0*/, "", addr)
    if (!(addr in cnt)) next
    c = cnt[addr]; seen += c
    line = $0; sub(/^[^\t]*\t/, "", line)
    m = line; sub(/[ \t].*$/, "", m)
    ops = line; sub(/^[^ \t]*[ \t]*/, "", ops)
    lanes = 1
    if (m ~ /p[sd]$/ || m ~ /^vp/) {
      bits = (ops ~ /%zmm/) ? 512 : (ops ~ /%ymm/) ? 256 : 128
      lanes = bits / ((m ~ /ps$/) ? 32 : 64)
    }
    cls = "other"
    if (m ~ /^v?f(n)?m(add|sub)/ || m ~ /^vfmaddsub|^vfmsubadd/) { cls = "fma"; fl += 2 * lanes * c }
    else if (m ~ /^v?(add|sub|mul)(p|s)(s|d)$/) { cls = "add/sub/mul"; fl += lanes * c }
    else if (m ~ /^v?(div|sqrt)(p|s)(s|d)$/) { cls = "div/sqrt"; fl += lanes * c }
    else if (m ~ /^v?(min|max)(p|s)(s|d)$/) cls = "min/max"
    else if (m ~ /^v?(u)?comis|^v?cmp.*(p|s)(s|d)$|^vpcmp|^vfpclass/) cls = "compare"
    else if (m ~ /^v?blendv?p|^vpblend|^v?(and|andn|or|xor)p|^vp(and|andn|or|xor|ternlog)|^k(and|andn|or|xor|not|mov|ortest|test|shift|unpck)/) cls = "blend/logic/mask"
    else if (m ~ /^v?(perm|shuf|unpck|insert|extract|broadcast|movddup|movs[hl]dup|movhlps|movlhps)|^vp(erm|shuf|unpck|broadcast|alignr)|^valign/) cls = "shuffle"
    else if (m ~ /^v?(cvt|round)/) cls = "convert/round"
    else if (m ~ /^v?mov/) cls = "move"
    else if (m ~ /^(j|call|ret|cmp|test|add|sub|inc|dec|lea|shl|shr|sar|and|or|xor|set|cmov|imul|nop|push|pop|xchg|endbr|cs|data)/) cls = "integer/control"
    k[cls] += c
    if (ops ~ /\(/ && m !~ /^(lea|nop|prefetch)/ && line !~ /^cs nop/) {
      n_ops = split(ops, parts, ",")
      store = (parts[n_ops] ~ /\(/)
      stack = (ops ~ /\(%rsp|\(%rbp/)
      if (stack) { if (store) ss += c; else sl += c } else { if (store) ms += c; else ml += c }
    }
  }
  END {
    printf "%s %s %s, %d %s pairs: %.1f instructions per pair in the kernels (%.0f%% of them mapped to the disassembly)\n", method, prec, isa, n, family, total / n, total ? 100 * seen / total : 0
    printf "  floating-point operations per pair (every lane counted): %.1f\n", fl / n
    for (x in k) printf "  %-18s %9.1f per pair  %5.1f%%\n", x, k[x] / n, 100 * k[x] / total
    printf "  branches per pair (callgrind model): conditional %.1f, mispredicted %.2f; indirect %.1f, mispredicted %.2f\n", bc / n, bcm / n, bi / n, bim / n
    printf "  memory: loads %.1f, stores %.1f per pair; on the stack (spills/reloads): loads %.1f, stores %.1f per pair (%.1f%% of instructions)\n", ml / n, ms / n, sl / n, ss / n, 100 * (sl + ss) / total
  }' "$tmp/counts" "$tmp/dis"
