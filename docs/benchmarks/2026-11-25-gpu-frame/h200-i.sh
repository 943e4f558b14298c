#!/bin/bash
# Issue 20 on the GPU machine, session 16, after the changes: the committed build (32-bit
# clamped indices in every C-family kernel, the film's three-gather encoding) on NVIDIA's
# OpenCL and GL: backend and ray tracer tests, primary and full throughput in three
# processes, frame times, and the cpu frame of thesis A at 1024x1024 on the 16 host cores.
# Set-up: the dynamic-scene folder's setup.sh (carried libraries in .devcarry/lib).
source docs/benchmarks/2026-11-25-dynamic/setup.sh
[ -f .devcarry/lib/libembree3.so.3 ] || python3 -c "import lzma, shutil; shutil.copyfileobj(lzma.open('.devcarry/lib/libembree3.so.3.xz'), open('.devcarry/lib/libembree3.so.3', 'wb'))"
BUNNY=.devcarry/stanford-bunny.obj
nvidia-smi --query-gpu=name,clocks.sm,pstate --format=csv,noheader
echo "== tests on NVIDIA"
timeout 150 $B/rill_backend_tests --gtest_filter='*/opencl:*/glsl_compute' > $OUT/backend-tests.txt 2>&1; echo "backend rc=$?"; tail -1 $OUT/backend-tests.txt
timeout 200 $B/rill_raytracer_tests --gtest_filter='*/opencl:*/glsl_compute:*Film*:*Srgb8*' > $OUT/rt-tests.txt 2>&1; echo "raytracer rc=$?"; tail -1 $OUT/rt-tests.txt
echo "== rill-bench-trace --sections throughput --size 1920x1080 --repeats 5 --backends opencl, three processes"
for round in 1 2 3; do
  timeout 120 $B/rill-bench-trace --sections throughput --size 1920x1080 --repeats 5 --scenes builtin:thesis-a,builtin:thesis-c,$BUNNY --backends opencl 2>&1 | grep -E "\| opencl \|"
done
echo "== frames: rill-trace render S --size 1920x1080 --backend opencl --bench-frames 20"
for round in 1 2; do for sc in builtin:thesis-a builtin:thesis-c $BUNNY; do
  echo "-- round $round $sc $(timeout 60 $B/rill-trace render $sc --size 1920x1080 --backend opencl --bench-frames 20 --out /tmp/f.png | grep -E 'frames' | cut -d';' -f1)"
done; done
echo "== cpu, thesis A 1024x1024"
timeout 100 $B/rill-bench-trace --sections throughput --size 1024x1024 --repeats 5 --scenes builtin:thesis-a --backends cpu 2>&1 | grep -E "\| cpu \|"
