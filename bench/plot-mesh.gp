# SPDX-License-Identifier: MIT
# The mesh section of `ttd bench` (issue 9) as a figure: time per query of ttd and of FCL 0.7 on
# the same meshes and poses, one thread, log scale. Three panels: minimum distance per mesh and
# placement (and per pose of the random poses); collision with margin 0; contacts within a margin
# (double and float), the per-triangle reduction (FCL: its pair traversal) and the tree builds.
#
# Usage: gnuplot -e "csv='results/bench-mesh.csv'; out='results/figure-mesh'" bench/plot-mesh.gp
# Writes out.svg and out.png. Needs awk (to pick rows out of the CSV).

if (!exists("csv")) csv = 'results/bench-mesh.csv'
if (!exists("out")) out = 'results/figure-mesh'

# One panel's rows: "label" ttd_ms fcl_ms ("-" where FCL has none), one thread. With R=1 instead
# the panel's y range as two powers of ten: the decades strictly below its smallest time / 1.5
# and above its largest x 1.5, so that every bar (they grow from the bottom of a logarithmic
# axis) has a height.
awk_rows = 'NR==1{for(i=1;i<=NF;i++)c[$i]=i;next} \
$c["threads"]==1 { q=$c["query"]; w=$c["workload"]; p=$c["pose"]; l=""; \
  if (P=="distance" && q=="distance") l=w" "p; \
  else if (P=="collide" && q=="collide") l=w" "p; \
  else if (P=="other" && q=="contacts") l=w" contacts "$c["precision"]; \
  else if (P=="other" && q=="closest") l=w" closest"; \
  else if (P=="other" && q=="build") l=w" build"; \
  if (l=="" || $c["ms"]=="") next; \
  if (!R) { printf "\"%s\" %s %s\n", l, $c["ms"], ($c["fcl_ms"]=="" ? "-" : $c["fcl_ms"]); next } \
  for (k = 0; k < 2; ++k) { x = $c[k ? "fcl_ms" : "ms"] + 0; if (x > 0) { if (!n++ || x < lo) lo = x; if (x > hi) hi = x } } } \
END { if (!R) exit; if (!n) { print "none"; exit } a = log(lo / 1.5) / log(10); b = log(hi * 1.5) / log(10); \
  ka = int(a); if (ka > a) ka--; kb = int(b); if (kb < b) kb++; printf "%d %d", ka, kb }'

rows(p) = sprintf("< awk -F, -v P=%s -v R=0 '%s' '%s'", p, awk_rows, csv)
range_of(p) = system(sprintf("awk -F, -v P=%s -v R=1 '%s' '%s'", p, awk_rows, csv))
count(p) = int(system(sprintf("awk -F, -v P=%s -v R=0 '%s' '%s' | wc -l", p, awk_rows, csv)))
titles = "distance collide other"
title_of(p) = (p eq "distance") ? "minimum distance (double), ms per query" : \
              (p eq "collide") ? "collision, margin 0 (double), ms per query" : \
              "contacts within a margin, per-triangle closest, tree build: ms"

set datafile missing "-"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.85 border -1
set boxwidth 0.9
set logscale y
set format y "10^{%L}"
set grid ytics
set xtics rotate by -35 nomirror font ",9"
set key top left
set linetype 1 lc rgb "#2b8cbe"
set linetype 2 lc rgb "#e6550d"

do for [fmt in "svg png"] {
  if (fmt eq "svg") { set terminal svg size 1300,1500 dynamic font "sans,11" } \
  else { set terminal pngcairo size 1300,1500 font "sans,10" }
  set output sprintf("%s.%s", out, fmt)
  set multiplot layout 3,1 title "ttd's mesh queries against FCL 0.7 (BVHModel<OBBRSS>), same meshes and poses, one thread"
  do for [p in titles] {
    if (count(p) >= 1) {
      set title title_of(p)
      set ylabel "ms"
      r = range_of(p)
      if (words(r) == 2) { set yrange [10.0 ** int(word(r, 1)):10.0 ** int(word(r, 2))] } else { set autoscale y }
      plot rows(p) using 2:xtic(1) title "ttd" lt 1, '' using 3 title "FCL" lt 2
    }
  }
  unset multiplot
  unset output
}
