# Plots the CSV of rill-bench-accuracy: one panel per kernel, each variant (backend x mode) a
# point at (time relative to strict on the same backend, error against the double reference).
# Error: RMS relative error of the float result (math, branchy: over the elements that took
# the reference's path), or the fraction of pixels whose iteration count differs (mandelbrot).
# Zero errors are drawn on the bottom edge. Strict gives the same bits on every backend, so
# its three points coincide at x = 1: point sizes differ per backend (cpu largest) to show
# them nested. Used for docs/accuracy-cost.svg:
#
#   build/bench/rill-bench-accuracy --csv accuracy-cost.csv
#   gnuplot -e "csv='accuracy-cost.csv'; out='docs/accuracy-cost.svg'" bench/plot_accuracy_cost.gp
if (!exists("csv")) csv = "accuracy-cost.csv"
if (!exists("out")) out = "accuracy-cost.svg"

set terminal svg size 1260,460 dynamic enhanced font "sans,11" background "white"
set output out
set datafile separator ","
set datafile missing "n/a"

backends = "cpu opencl glsl"
modes = "strict fast double"
kernels = "math branchy mandelbrot"
colour(i) = i == 1 ? 0x1f77b4 : i == 2 ? 0xd62728 : 0x2ca02c  # by backend
shape(j) = j == 1 ? 7 : j == 2 ? 5 : 9                        # by mode: circle, square, triangle
# Column 7: RMS relative error; 8 / 9: differing elements / elements.
error(k) = k eq "mandelbrot" ? column(8) / column(9) : column(7)
shown(v) = v > floor ? v : floor
size(i) = i == 1 ? 2.2 : i == 2 ? 1.6 : 1.0                   # nested points stay visible
pick(k, b, m) = strcol(1) eq k && strcol(2) eq b && strcol(3) eq m

set multiplot layout 1,3 title "Accuracy modes: time relative to strict against error vs. a double reference"
set logscale x 2
set logscale y 10
set xrange [0.125:4]
set format y "10^{%L}"
set grid
set xlabel "time / strict, same backend"
set key right center font ",9" spacing 0.9 box opaque

do for [n = 1:3] {
  k = word(kernels, n)
  set title k
  floor = k eq "mandelbrot" ? 1e-7 : 1e-8
  set yrange [floor:*]
  set ylabel (k eq "mandelbrot" ? "fraction of pixels whose iteration count differs (0 at the bottom)" \
                                 : "RMS relative error")
  if (n < 3) { unset key } else { set key }
  plot for [i = 1:3] for [j = 1:3] csv skip 1 \
      using (pick(k, word(backends, i), word(modes, j)) ? column(5) : NaN):(shown(error(k))) \
      with points pt shape(j) ps size(i) lc rgb colour(i) \
      title word(backends, i) . " " . word(modes, j)
}
unset multiplot
