#!/bin/bash
# Session 17: the 8-bit image encoded into RenderResult::rgb8's own bytes (3 a pixel, no
# unpacking) against the build before it (rill-trace-prefilm: 4 bytes a pixel, unpacked on
# the host), alternating, two rounds; and the film's tests on NVIDIA's OpenCL and GL.
# Set-up: the dynamic-scene folder's setup.sh (carried libraries in .devcarry/lib).
source docs/benchmarks/2026-11-25-dynamic/setup.sh
BUNNY=.devcarry/stanford-bunny.obj
echo "== tests"
timeout 200 $B/rill_raytracer_tests --gtest_filter='*Film*:*Srgb8*:*LightBufferRender*/opencl' > $OUT/film-tests.txt 2>&1; echo "rc=$?"; grep -E "OK \]|PASSED|FAILED" $OUT/film-tests.txt
echo "== rill-trace render S --size 1920x1080 --backend B --bench-frames N, before (prefilm) and after"
for round in 1 2; do
for sc in builtin:thesis-a builtin:thesis-c $BUNNY; do for be in opencl glsl-compute cpu; do
  N=20; [ $be = cpu ] && N=7
  for bin in rill-trace-prefilm rill-trace; do
    echo "-- round $round $sc $be $bin $(timeout 100 $B/$bin render $sc --size 1920x1080 --backend $be --bench-frames $N --out /tmp/$bin.png | grep -E 'frames of|median per step' | tr '\n' ' ' | sed 's/; [a-z-]*: .*  median/; median/')"
  done
  cmp /tmp/rill-trace-prefilm.png /tmp/rill-trace.png && echo "identical PNGs"
done; done; done
