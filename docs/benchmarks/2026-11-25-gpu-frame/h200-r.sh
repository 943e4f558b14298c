#!/bin/bash
# Session 18 (2026-11-27), after h200-q.sh: the final build (the highlight's zero told by the
# bits) against the build before this session, now with the new build first in each pair and
# then in the other order, to tell the order from the change in h200-q's OpenCL read-back;
# and the tests of the final build on NVIDIA's OpenCL and GL. Set-up as h200-q.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
echo "== tests"
timeout 150 $B/rill_backend_tests --gtest_filter='*PowOfZero*:*MaskTest*' > $OUT/backend-tests.txt 2>&1; echo "rc=$?"; grep -E "PASSED|FAILED" $OUT/backend-tests.txt
timeout 200 $B/rill_raytracer_tests --gtest_filter='*Film*:*Srgb8*:*Render.*/opencl:*Render.*/glsl_compute:*Render.*/glsl' > $OUT/raytracer-tests.txt 2>&1; echo "rc=$?"; grep -E "PASSED|FAILED" $OUT/raytracer-tests.txt
echo "== rill-trace render S --size 1920x1080 --backend B --bench-frames 20"
for order in "rill-trace rill-trace-base" "rill-trace-base rill-trace" "rill-trace rill-trace-base" "rill-trace-base rill-trace"; do
for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c; do for be in opencl glsl-compute; do
  for bin in $order; do
    r=$(timeout 100 $B/$bin render $sc --size 1920x1080 --backend $be --bench-frames 20 --out /tmp/$bin.png)
    echo "-- $sc $be $bin frame $(echo "$r" | grep 'frames of' | sed -E 's/.*first: median ([0-9.]+) ms.*/\1/') $(echo "$r" | grep 'median per step' | sed -E 's/.*launch ([0-9.]+) ms \(kernel ([0-9.]+) ms\).*reduce ([0-9.]+) ms, read-back ([0-9.]+) ms.*/launch \1 kernel \2 reduce \3 read-back \4/')"
  done
  cmp /tmp/rill-trace-base.png /tmp/rill-trace.png && echo "identical PNGs"
done; done; done
