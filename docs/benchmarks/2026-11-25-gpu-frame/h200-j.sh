#!/bin/bash
# Issue 20 on the GPU machine, session 16: the kernel's own time within a launch
# (LaunchStats::device_ms, FrameTimes::kernel) on NVIDIA's OpenCL and GL: the tests that
# check it, and the frame split of rill-trace --bench-frames on each GPU backend.
# Set-up: the dynamic-scene folder's setup.sh (carried libraries in .devcarry/lib).
source docs/benchmarks/2026-11-25-dynamic/setup.sh
BUNNY=.devcarry/stanford-bunny.obj
echo "== tests"
timeout 120 $B/rill_backend_tests --gtest_filter='*DeviceTimeIsWithinTheLaunch*:*LaunchTest*/opencl:*LaunchTest*/glsl_compute' > $OUT/backend-tests.txt 2>&1; echo "backend rc=$?"; grep -E "OK \].*DeviceTime|PASSED|FAILED" $OUT/backend-tests.txt
timeout 120 $B/rill_raytracer_tests --gtest_filter='*KernelTimeIsPartOfTheLaunch*' > $OUT/rt-tests.txt 2>&1; echo "raytracer rc=$?"; grep -E "OK \]|PASSED|FAILED" $OUT/rt-tests.txt
echo "== frames: rill-trace render S --size 1920x1080 --backend B --bench-frames 20 (glsl: 5)"
for sc in builtin:thesis-a builtin:thesis-c $BUNNY; do for be in opencl glsl-compute glsl; do
  n=20; [ $be = glsl ] && n=5
  echo "-- $sc $be"; timeout 100 $B/rill-trace render $sc --size 1920x1080 --backend $be --bench-frames $n --out /tmp/f.png | grep -E 'frames of|median per step'
done; done
