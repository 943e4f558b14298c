#!/bin/bash
# Session 17: the shadow rays' light buffer (accel/LightBuffer.h) on the H200: its image
# tests on NVIDIA's OpenCL and GL, then whole frames with it off and on, side by side, two
# rounds, on each GPU backend and on the host's 16 cores; and issue 20's cpu ratio.
# SKIP_CPU16=1 leaves out the 16-core frames (the re-run after the review's fix, h200-o.txt).
# Set-up: the dynamic-scene folder's setup.sh (carried libraries in .devcarry/lib).
source docs/benchmarks/2026-11-25-dynamic/setup.sh
echo "== tests"
timeout 240 $B/rill_raytracer_tests --gtest_filter='LightBuffer*:*LightBufferRender*/opencl:*LightBufferRender*/glsl_compute:*LightBufferRender*/glsl' > $OUT/lb-tests.txt 2>&1; echo "rc=$?"; grep -E "OK \]|PASSED|FAILED" $OUT/lb-tests.txt
echo "== frames: rill-trace render S --size 1920x1080 --backend B --bench-frames 20 --light-buffer off|auto"
for round in 1 2; do
for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c builtin:cornell builtin:glass; do for be in opencl glsl-compute; do for lb in off auto; do
  echo "-- round $round $sc $be light-buffer $lb"
  timeout 60 $B/rill-trace render $sc --size 1920x1080 --backend $be --bench-frames 20 --light-buffer $lb --pfm /tmp/$be-$lb.pfm | grep -E 'frames of|median per step'
done; cmp /tmp/$be-off.pfm /tmp/$be-auto.pfm && echo "identical images"; done; done
done
[ -z "$SKIP_CPU16" ] && echo "== cpu, 16 threads: rill-trace render S --size 1920x1080 --backend cpu --bench-frames 5"
[ -z "$SKIP_CPU16" ] && for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c builtin:cornell; do for lb in off auto off auto; do
  echo "-- $sc cpu light-buffer $lb"
  timeout 60 $B/rill-trace render $sc --size 1920x1080 --backend cpu --bench-frames 5 --light-buffer $lb --out /tmp/c.png | grep -E 'frames of|median per step'
done; done
echo "== issue 20's cpu ratio: rill-bench-trace --sections throughput --size 1024x1024 --scenes builtin:thesis-a --backends cpu,simd --repeats 9"
for r in 1 2; do timeout 100 $B/rill-bench-trace --sections throughput --size 1024x1024 --scenes builtin:thesis-a --backends cpu,simd --repeats 9 | grep -E '^\| thesis'; done
