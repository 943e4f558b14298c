#!/bin/bash
# Session 25 (2026-11-28) on the H200 machine: the build with skipped pixels (the scene's box
# on screen), AOV-less and self-encoding megakernel variants (rill-trace) against the build
# before the session (rill-trace-base, 294bb3f): the new tests on NVIDIA's OpenCL and GL, then
# frame times at 1920x1080, each scene and backend with both builds in both orders, and the
# PNGs compared. Set-up: the dynamic-scene folder's setup.sh (carried libraries in
# .devcarry/lib); the bunny is ../shared/meshes/stanford-bunny.obj, carried.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
BUNNY=.devcarry/stanford-bunny.obj
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
echo "== tests"
timeout 240 $B/rill_raytracer_tests --gtest_filter='*SkippedPixels*:*Window.Tiles*:*MegakernelLoop*:*Film*:Camera.*' > $OUT/rt-tests.txt 2>&1; echo "raytracer rc=$?"; grep -E "PASSED|FAILED|OK \].*(opencl|glsl)" $OUT/rt-tests.txt | tail -30
echo "== rill-trace render S --size 1920x1080 --backend B --bench-frames N: frame, launch, kernel, reduce, read-back (ms)"
for order in "rill-trace rill-trace-base" "rill-trace-base rill-trace"; do
for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c $BUNNY; do for be in opencl glsl-compute cpu simd; do
  N=20; [ $be = cpu -o $be = simd ] && [ $sc = builtin:thesis-b -o $sc = builtin:thesis-c ] && N=7
  for bin in $order; do
    r=$(timeout 100 $B/$bin render $sc --size 1920x1080 --backend $be --bench-frames $N --out /tmp/$bin.png)
    echo "-- $(basename $sc) $be $bin frame $(echo "$r" | grep 'frames of' | sed -E 's/.*first: median ([0-9.]+) ms.*/\1/') $(echo "$r" | grep 'median per step' | sed -E 's/.*launch ([0-9.]+) ms \(kernel ([0-9.]+) ms\).*reduce ([0-9.]+) ms, read-back ([0-9.]+) ms.*/launch \1 kernel \2 reduce \3 read-back \4/')"
  done
  cmp -s /tmp/rill-trace-base.png /tmp/rill-trace.png && echo "identical PNGs" || echo "PNGS DIFFER"
done; done; done
echo "== glsl (fragment stage), new build"
for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c $BUNNY; do
  echo "-- $(basename $sc) glsl $(timeout 100 $B/rill-trace render $sc --size 1920x1080 --backend glsl --bench-frames 5 --out /tmp/g.png | grep 'frames of' | sed -E 's/.*first: median ([0-9.]+) ms.*/frame \1/')"
done
