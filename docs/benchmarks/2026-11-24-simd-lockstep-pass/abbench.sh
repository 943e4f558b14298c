#!/bin/bash
# Side by side: the baseline (before the lockstep pass) and the new simd, alternating A B A B.
OLD=/work/baseline NEW=/work/main/build/bench
export RILL_CACHE_DIR=/tmp/abcache
for round in 1 2 3; do
  for v in old new; do
    d=$OLD; [ $v = new ] && d=$NEW
    echo "== round $round $v trace"
    $d/rill-bench-trace --sections throughput --backends simd --size 1024x1024 --repeats 3 2>&1 | grep -E "\| simd \|"
    echo "== round $round $v mandelbrot"
    $d/rill-bench-mandelbrot 2>&1 | grep -E "^  simd"
  done
done
