#!/bin/bash
# Session 18 (2026-11-27): the 8-bit encoder's table of one entry per bucket (one gather a
# channel instead of three) and the highlight's pow skipped where its base is 0, against the
# build before them (rill-trace-base), alternating, two rounds; and the tests they touch on
# NVIDIA's OpenCL and GL. Set-up: the dynamic-scene folder's setup.sh (carried libraries in
# .devcarry/lib, GL packages in .gl).
source docs/benchmarks/2026-11-25-dynamic/setup.sh
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
echo "== tests"
timeout 150 $B/rill_backend_tests --gtest_filter='*PowOfZero*:*MaskTest*:*StrictRoutines*' > $OUT/backend-tests.txt 2>&1; echo "rc=$?"; grep -E "PASSED|FAILED" $OUT/backend-tests.txt
timeout 240 $B/rill_raytracer_tests --gtest_filter='*Film*:*Srgb8*:*Render.*/opencl:*Render.*/glsl_compute' > $OUT/raytracer-tests.txt 2>&1; echo "rc=$?"; grep -E "PASSED|FAILED" $OUT/raytracer-tests.txt
echo "== rill-trace render S --size 1920x1080 --backend B --bench-frames N, before (base) and after"
for round in 1 2; do
for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c; do for be in opencl glsl-compute cpu; do
  N=20; [ $be = cpu ] && N=7
  [ $be = cpu ] && [ $sc != builtin:thesis-a ] && continue
  for bin in rill-trace-base rill-trace; do
    echo "-- round $round $sc $be $bin $(timeout 100 $B/$bin render $sc --size 1920x1080 --backend $be --bench-frames $N --out /tmp/$bin.png | grep -E 'frames of|median per step' | tr '\n' ' ' | sed 's/; [a-z-]*: .*  median/; median/')"
  done
  cmp /tmp/rill-trace-base.png /tmp/rill-trace.png && echo "identical PNGs"
done; done; done
