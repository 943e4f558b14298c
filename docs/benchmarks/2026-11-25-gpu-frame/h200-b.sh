#!/bin/bash
# Issue 20 on the GPU machine: the film (device accumulation, 8-bit encode, read-back of what
# is asked, buffers reused per backend) and per-device grid defaults; tests, identity, frames.
source "$(dirname "$0")/setup.sh"
BUNNY=.devcarry/stanford-bunny.obj
nproc; $B/rill-info > $OUT/info.txt 2>&1
timeout 200 $B/rill_raytracer_tests --gtest_filter='*FilmTest*:*Frames*:*OptionsKeep*:Grid.Subgrids*:*KnobsOnBackend*' > $OUT/rt-tests.txt 2>&1; echo "raytracer tests rc=$?"; grep -E "FAILED|PASSED|SKIPPED \]" $OUT/rt-tests.txt | head -12
timeout 60 $B/rill_backend_tests --gtest_filter='*RunsOnGpu*' > $OUT/be-tests.txt 2>&1; echo "backend tests rc=$?"; tail -2 $OUT/be-tests.txt
for sc in thesis-b glass cornell; do
  for be in cpu opencl glsl glsl-compute; do timeout 60 $B/rill-trace render builtin:$sc --backend $be --size 160x120 --spp 3 --pfm /tmp/$sc-$be.pfm --out /tmp/$sc-$be.png > /dev/null 2>>$OUT/render-err.txt || echo "render $sc $be failed"; done
  for be in opencl glsl glsl-compute; do cmp -s /tmp/$sc-cpu.pfm /tmp/$sc-$be.pfm && cmp -s /tmp/$sc-cpu.png /tmp/$sc-$be.png && echo "same bits $sc $be" || echo "DIFFERENT $sc $be"; done
done
echo "== frames (rill-trace render --size 1920x1080 --bench-frames 20)"
for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c $BUNNY; do for be in opencl glsl-compute simd cpu; do
  echo "-- $sc $be"; timeout 120 $B/rill-trace render $sc --size 1920x1080 --backend $be --bench-frames 20 --out /tmp/f.png --stats-json $OUT/frames-$(basename $sc)-$be.json | grep -E "frames|median per step|Mrays"
done; done
echo "== old and new rill-bench-trace side by side (full: old reads back colour and AOVs, new what a PNG needs)"
for pair in 1 2; do for bin in rill-bench-trace-old rill-bench-trace; do
  echo "== pair $pair $bin"
  timeout 150 $B/$bin --sections throughput --size 1920x1080 --scenes builtin:thesis-a,builtin:thesis-c,$BUNNY --backends opencl,glsl-compute --repeats 5 2>&1 | grep -E "\| (opencl|glsl-compute|cpu) \|"
done; done
