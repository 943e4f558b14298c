#!/bin/bash
# Session 26 (2026-11-29) on the H200 machine: the build with the tile mask of occupied boxes,
# light-buffer entries tightened to their cells and Phong's pow test (rill-trace,
# rill-bench-trace) against the build before the session (rill-trace-base,
# rill-bench-trace-base, 82a2085): the new and touched tests on NVIDIA's OpenCL and GL, issue
# 20's cpu ratio on the host's cores, then 1080p frames per scene and backend with both
# builds alternating, the PNGs compared. Set-up as h200-s.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
xz -dk .devcarry/lib/libembree3.so.3.xz 2>/dev/null
BUNNY=.devcarry/stanford-bunny.obj
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc
echo "== tests"
timeout 200 $B/rill_raytracer_tests --gtest_filter='*SkippedPixels*:*Window.Tiles*:*LightBuffer*:*DynamicRender*:Camera.*:OccupiedBoxes.*:*ShaderRender*:*CameraRays*' > $OUT/rt-tests.txt 2>&1; echo "raytracer rc=$?"; grep -E "PASSED|FAILED" $OUT/rt-tests.txt | tail -8
timeout 100 $B/rill_backend_tests --gtest_filter='*PowTerm*:*PowOfZero*' > $OUT/backend-tests.txt 2>&1; echo "backend rc=$?"; grep -E "OK|FAILED|PASSED" $OUT/backend-tests.txt | tail -12
echo "== issue 20's cpu target: rill-bench-trace --sections throughput --scenes builtin:thesis-a --backends cpu,simd --repeats 11"
for r in 1 2; do for bin in rill-bench-trace-base rill-bench-trace; do
  echo "-- $r $bin $(timeout 60 $B/$bin --sections throughput --scenes builtin:thesis-a --backends cpu,simd --repeats 11 2>&1 | grep '^| thesis' | awk -F'|' '{printf "%s primary %s full %s ratio %.2f; ",$7,$8,$10,$10/$8}')"
done; done
echo "== rill-trace render S --size 1920x1080 --backend B --bench-frames N: frame, launch, kernel, reduce, read-back (ms)"
for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c $BUNNY; do for be in opencl glsl-compute cpu; do
  N=20; [ $be = cpu ] && [ $sc != builtin:thesis-a ] && continue
  for bin in rill-trace-base rill-trace rill-trace-base rill-trace; do
    x=$(timeout 60 $B/$bin render $sc --size 1920x1080 --backend $be --bench-frames $N --out /tmp/$bin.png)
    echo "-- $(basename $sc) $be $bin frame $(echo "$x" | grep 'frames of' | sed -E 's/.*first: median ([0-9.]+) ms.*/\1/') $(echo "$x" | grep 'median per step' | sed -E 's/.*launch ([0-9.]+) ms \(kernel ([0-9.]+) ms\).*reduce ([0-9.]+) ms, read-back ([0-9.]+) ms.*/launch \1 kernel \2 reduce \3 read-back \4/')"
  done
  cmp -s /tmp/rill-trace-base.png /tmp/rill-trace.png && echo "identical PNGs" || echo "PNGS DIFFER"
done; done
echo "== primary rays, NVIDIA OpenCL: rill-bench-trace --sections throughput --scenes thesis-c,bunny --backends cpu,opencl --size 1920x1080"
timeout 150 $B/rill-bench-trace --sections throughput --scenes builtin:thesis-c,$BUNNY --backends cpu,opencl --size 1920x1080 --repeats 11 2>&1 | grep -E "^\|" | tail -6
