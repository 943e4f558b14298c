# Plots the CSV of rill-bench-accuracy: one panel per kernel, each variant (backend x mode) a
# point at (time relative to strict on the same backend, error against the double reference).
# Error: RMS relative error of the float result (math, branchy: over the elements that took
# the reference's path), or the fraction of pixels whose iteration count differs (mandelbrot).
# Zero errors are drawn on the bottom edge. Used for docs/accuracy-cost.svg:
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
floor = 1e-9
colour(i) = i == 1 ? 0x1f77b4 : i == 2 ? 0xd62728 : 0x2ca02c  # by backend
shape(j) = j == 1 ? 7 : j == 2 ? 5 : 9                        # by mode: circle, square, triangle
# Column 7: RMS relative error; 8 / 9: differing elements / elements.
error(k) = k eq "mandelbrot" ? column(8) / column(9) : column(7)
shown(v) = v > floor ? v : floor
pick(k, b, m) = strcol(1) eq k && strcol(2) eq b && strcol(3) eq m

set multiplot layout 1,3 title "Accuracy modes: time relative to strict against error vs. a double reference"
set logscale x 2
set logscale y 10
set xrange [0.125:4]
set format y "10^{%L}"
set grid
set xlabel "time / strict, same backend"
set key bottom left font ",9" spacing 0.9

do for [n = 1:3] {
  k = word(kernels, n)
  set title k
  set ylabel (k eq "mandelbrot" ? "pixels whose iteration count differs" : "RMS relative error")
  if (n > 1) { unset key }
  plot for [i = 1:3] for [j = 1:3] csv skip 1 \
      using (pick(k, word(backends, i), word(modes, j)) ? column(5) : NaN):(shown(error(k))) \
      with points pt shape(j) ps 1.4 lc rgb colour(i) \
      title word(backends, i) . " " . word(modes, j)
}
unset multiplot
