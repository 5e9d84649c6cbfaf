# SPDX-License-Identifier: MIT
# Figure 3 of the paper, redrawn from `ttd bench` results: time per pair of each method in
# double and float, scalar and on each SIMD instruction set (one thread), FCL beside; one
# panel for the paper's workload (one pair x1000) and one for random pairs. A second figure
# shows time per pair against the number of pairs (the working-set sweep), where memory
# bandwidth would show as a rise once the data leave the caches.
#
# Usage: gnuplot -e "csv='results/bench.csv'; out='results/figure'" bench/plot.gp
# Writes out.svg and out.png, and out-sizes.svg/.png when the CSV has the sweep rows.
# Needs awk (to pick rows out of the CSV).

if (!exists("csv")) csv = 'results/bench.csv'
if (!exists("out")) out = 'results/figure'

# Pivot of one workload's 1-thread rows: a header "label isa1 isa2 ...", then one line per
# method and precision (FCL last) with ns per pair under each instruction set ("-" if none).
awk_pivot = 'NR==1{for(i=1;i<=NF;i++)c[$i]=i;next} \
$c["workload"]==W && $c["threads"]==1 { \
  m=$c["method"]; p=$c["precision"]; a=(m=="fcl" ? "FCL" : $c["isa"]); \
  if(m!="fcl" && !(m in sm)){sm[m]=1; mo[++nm]=m} \
  sa[a]=1; v[m" "p,a]=$c["ns_per_pair"]; have[m" "p]=1 } \
END{ split("scalar sse2 avx2 avx512 neon FCL",I," "); ni=0; \
  for(i=1;i<=6;i++) if(I[i] in sa) J[++ni]=I[i]; \
  if(ni==0) exit; \
  printf "label"; for(i=1;i<=ni;i++) printf " %s",J[i]; printf "\n"; \
  mo[++nm]="fcl"; \
  for(j=1;j<=nm;j++) for(q=1;q<=2;q++){ p=(q==1?"double":"float"); k=mo[j]" "p; if(!(k in have)) continue; \
    printf "\"%s\"",(mo[j]=="fcl"?"FCL":mo[j])" "p; \
    for(i=1;i<=ni;i++){x=v[k,J[i]]; printf " %s",(x==""?"-":x)} \
    printf "\n"} }'

pivot(w) = sprintf("< awk -F, -v W=%s '%s' '%s'", w, awk_pivot, csv)
header(w) = system(sprintf("awk -F, -v W=%s '%s' '%s' | head -1", w, awk_pivot, csv))
ncols(w) = words(header(w))
nlines(w) = int(system(sprintf("awk -F, -v W=%s '%s' '%s' | wc -l", w, awk_pivot, csv)))

set datafile missing "-"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.85 border -1
set boxwidth 0.9
set logscale y
set grid ytics mytics
set ylabel "time per pair (ns), one thread"
set xtics rotate by -35 nomirror
set key top left
set linetype 1 lc rgb "#4d4d4d"
set linetype 2 lc rgb "#74a9cf"
set linetype 3 lc rgb "#2b8cbe"
set linetype 4 lc rgb "#045a8d"
set linetype 5 lc rgb "#a6bddb"
set linetype 6 lc rgb "#e6550d"

# The y range of a panel: its smallest and largest 1-thread time padded by a factor 1.5, and
# widened to the decades around them so that the axis has labelled tics. Autoscaling stops at
# the tic next to the data, and on a logarithmic axis the bars grow from the bottom of the
# range, so a bar exactly on a decade (exact float AVX2 at 100 ns, seen in --quick) had no
# height at all.
awk_range = 'function dec(x, up) { l = log(x) / log(10); k = int(l + (l < 0 ? -0.5 : 0.5)); \
    if (l - k > 1e-9 || k - l > 1e-9) k = (up ? (l > 0 ? int(l) + 1 : -int(-l)) : (l >= 0 ? int(l) : -int(-l) - 1)); \
    return 10 ^ k } \
NR==1{for(i=1;i<=NF;i++)c[$i]=i;next} \
$c["workload"]==W && $c["threads"]==1 && $c["ns_per_pair"]+0 > 0 { \
  x=$c["ns_per_pair"]+0; if(!n++ || x<lo) lo=x; if(x>hi) hi=x } \
END{ if(!n) { printf "0 0"; exit } a = lo / 1.5; b = hi * 1.5; \
  if (dec(lo, 0) < a) a = dec(lo, 0); if (dec(hi, 1) > b) b = dec(hi, 1); printf "%.9g %.9g", a, b }'
range_of(w) = system(sprintf("awk -F, -v W=%s '%s' '%s'", w, awk_range, csv))

pairs_of(w) = system(sprintf("awk -F, -v W=%s 'NR==1{for(i=1;i<=NF;i++)c[$i]=i;next} $c[\"workload\"]==W{print $c[\"pairs\"]; exit}' '%s'", w, csv))
panel_title(w) = (w eq "paper") ? "the paper's workload: one pair x1000" : sprintf("%s pairs (%s)", w, pairs_of(w))

do for [fmt in "svg png"] {
  if (fmt eq "svg") { set terminal svg size 1200,520 dynamic font "sans,11" } \
  else { set terminal pngcairo size 1200,520 font "sans,10" }
  set output sprintf("%s.%s", out, fmt)
  set multiplot layout 1,2 title "ttd: time per triangle pair by method, precision and instruction set (FCL beside)"
  do for [w in "paper random"] {
    n = ncols(w)
    if (n >= 2 && nlines(w) >= 2) {
      set title panel_title(w)
      r = range_of(w)
      if (real(word(r, 1)) > 0) { set yrange [real(word(r, 1)):real(word(r, 2))] } else { set autoscale y }
      h = header(w)
      plot for [i=2:n] pivot(w) using i:xtic(1) title columnhead(i) lt (word(h, i) eq "FCL" ? 6 : i - 1)
    }
  }
  unset multiplot
  unset output
}

# Working-set sweep: ns per pair of the exact and penalty methods against pairs, per ISA and
# thread count, from the random-* workloads and "random".
awk_sweep = 'NR==1{for(i=1;i<=NF;i++)c[$i]=i;next} \
($c["workload"]=="random" || $c["workload"] ~ /^random-/) && $c["method"]==M && $c["precision"]==P && $c["isa"]==A && $c["threads"]==T \
  { print $c["pairs"], $c["ns_per_pair"] }'
sweep(m, p, a, t) = sprintf("< awk -F, -v M=%s -v P=%s -v A=%s -v T=%d '%s' '%s' | sort -n", m, p, a, t, awk_sweep, csv)
sweep_n(m, p, a, t) = int(system(sprintf("awk -F, -v M=%s -v P=%s -v A=%s -v T=%d '%s' '%s' | wc -l", m, p, a, t, awk_sweep, csv)))
best_isa = system(sprintf("awk -F, 'NR==1{for(i=1;i<=NF;i++)c[$i]=i;next} $c[\"workload\"]==\"random-1k\" && $c[\"isa\"]!=\"scalar\"{print $c[\"isa\"]; exit}' '%s'", csv))
max_threads = int(system(sprintf("awk -F, 'NR==1{for(i=1;i<=NF;i++)c[$i]=i;next} $c[\"workload\"] ~ /^random-/ && $c[\"threads\"]>t{t=$c[\"threads\"]} END{print t+0}' '%s'", csv)))

if (strlen(best_isa) > 0 && sweep_n("exact", "double", best_isa, 1) >= 2) {
  set style data linespoints
  set autoscale y
  set logscale xy
  set xtics norotate
  set format x "10^{%L}"
  set format y "%g"
  set xlabel "pairs in the batch (input: 144 bytes per pair in double, 72 in float)"
  set ylabel "time per pair (ns)"
  set key top left
  # blue double, orange float; solid exact, dashed penalty; filled points 1 thread, open all
  set style line 1 lc rgb "#2b8cbe" lw 2 dt 1 pt 7
  set style line 2 lc rgb "#2b8cbe" lw 2 dt 1 pt 6
  set style line 3 lc rgb "#e6550d" lw 2 dt 1 pt 7
  set style line 4 lc rgb "#e6550d" lw 2 dt 1 pt 6
  set style line 5 lc rgb "#2b8cbe" lw 2 dt 2 pt 5
  set style line 6 lc rgb "#2b8cbe" lw 2 dt 2 pt 4
  set style line 7 lc rgb "#e6550d" lw 2 dt 2 pt 5
  set style line 8 lc rgb "#e6550d" lw 2 dt 2 pt 4
  do for [fmt in "svg png"] {
    if (fmt eq "svg") { set terminal svg size 900,520 dynamic font "sans,11" } \
    else { set terminal pngcairo size 900,520 font "sans,10" }
    set output sprintf("%s-sizes.%s", out, fmt)
    set title sprintf("ttd: time per pair against working-set size (random pairs, %s)", best_isa)
    plot for [m in "exact penalty"] for [p in "double float"] for [t in sprintf("1 %d", max_threads)] \
         sweep(m, p, best_isa, int(t)) using 1:2 title sprintf("%s %s, %s thread%s", m, p, t, (t eq "1") ? "" : "s") \
         ls 1 + 4 * (m eq "penalty") + 2 * (p eq "float") + (t ne "1")
    unset output
  }
}
