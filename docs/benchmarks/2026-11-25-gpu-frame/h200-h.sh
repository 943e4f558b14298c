#!/bin/bash
# Issue 20 on the GPU machine, session 16: the OpenCL kernel-frame experiments side by side
# (RILL_OPENCL_EXPERIMENT, a switch of an uncommitted experiment build, removed after this
# run: restrict-qualified arrays, __constant shapes and uniforms, 32-bit clamped indices,
# persistent work-groups fetching batches), alternating in two rounds, one process per
# variant; the film's new sRGB encoding checked on NVIDIA's OpenCL and GL; the cpu frame of
# thesis A at 1024x1024 before and after the encoding change.
# Set-up: the dynamic-scene folder's setup.sh (carried libraries in .devcarry/lib).
source docs/benchmarks/2026-11-25-dynamic/setup.sh
[ -f .devcarry/lib/libembree3.so.3 ] || python3 -c "import lzma, shutil; shutil.copyfileobj(lzma.open('.devcarry/lib/libembree3.so.3.xz'), open('.devcarry/lib/libembree3.so.3', 'wb'))"
BUNNY=.devcarry/stanford-bunny.obj
nvidia-smi --query-gpu=name,clocks.sm,pstate --format=csv,noheader
echo "== tests on NVIDIA (film, render, dynamic)"
timeout 200 $B/rill_raytracer_tests --gtest_filter='*Film*:*Srgb8*:Backends/Render.*/opencl:Backends/Render.*/glsl_compute:Backends/Render.*/glsl:*DynamicRender*/opencl' > $OUT/rt-tests.txt 2>&1
echo "rc=$?"; grep -E "PASSED|FAILED|SKIPPED \]" $OUT/rt-tests.txt | sort | uniq -c | head -20
echo "== OpenCL variants: rill-bench-trace --sections throughput --size 1920x1080 --repeats 5"
S=builtin:thesis-a,builtin:thesis-c,$BUNNY
for round in 1 2; do
  for v in base restrict constant index32 restrict,constant,index32 persistent persistent-32 persistent,restrict,constant,index32; do
    x=$v; g=64; [ $v = base ] && x=; [ $v = persistent-32 ] && x=persistent && g=32
    echo "-- round $round variant $v"
    RILL_CACHE_DIR=/tmp/rc-$v RILL_OPENCL_GROUP=$g RILL_OPENCL_EXPERIMENT=$x timeout 120 \
      $B/rill-bench-trace --sections throughput --size 1920x1080 --repeats 5 --scenes $S --backends opencl 2>&1 | grep -E "\| opencl \|"
  done
done
echo "== frames: rill-trace render S --size 1920x1080 --backend opencl --bench-frames 20"
for round in 1 2; do for v in base restrict,constant,index32; do for sc in builtin:thesis-a builtin:thesis-c $BUNNY; do
  x=$v; [ $v = base ] && x=
  echo "-- round $round $v $sc $(RILL_CACHE_DIR=/tmp/rc-$v RILL_OPENCL_EXPERIMENT=$x timeout 60 $B/rill-trace render $sc --size 1920x1080 --backend opencl --bench-frames 20 --out /tmp/f.png | grep -E 'frames' | cut -d';' -f1)"
done; done; done
echo "== cpu, thesis A 1024x1024: frames before (old) and after the sRGB change"
for round in 1 2 3; do for v in rill-trace-old rill-trace; do
  echo "-- round $round $v $($B/$v render builtin:thesis-a --size 1024x1024 --backend cpu --bench-frames 9 --out /tmp/c.png | grep -E 'frames|median per step' | tr '\n' ' ')"
done; done
timeout 100 $B/rill-bench-trace --sections throughput --size 1024x1024 --repeats 5 --scenes builtin:thesis-a --backends cpu 2>&1 | grep -E "\| cpu \|"
