#!/bin/bash
# Issue 20 on the GPU machine: GL and OpenCL in one process; glsl-compute tiles; the table of
# every backend (one process per GPU backend), with Embree; frame times.
source "$(dirname "$0")/setup.sh"
BUNNY=.devcarry/stanford-bunny.obj
T="$B/rill-bench-trace --size 1920x1080 --repeats 5"
timeout 100 $B/rill_raytracer_tests --gtest_filter='*/opencl:*/glsl_compute' > $OUT/rt-tests.txt 2>&1; echo "raytracer tests rc=$?"; tail -1 $OUT/rt-tests.txt
echo "== one API or two in one process"
for round in 1 2; do for bes in opencl opencl,glsl-compute glsl-compute; do echo "-- round $round --backends $bes"
  timeout 100 $T --sections throughput --scenes builtin:thesis-c,$BUNNY --backends $bes 2>&1 | grep -E "\| (opencl|glsl-compute) \|"; done; done
echo "== glsl-compute tiles"
for round in 1 2; do for t in on off; do echo "-- round $round RILL_GLSL_TILES=$t"
  RILL_GLSL_TILES=$t timeout 100 $T --sections throughput --scenes builtin:thesis-c,$BUNNY --backends glsl-compute 2>&1 | grep -E "\| glsl-compute \|"; done; done
echo "== table: rill-bench-trace --sections throughput[,embree] --size 1920x1080 --repeats 5, one process per line"
S=builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,$BUNNY
timeout 200 $T --sections throughput,embree --scenes $S --backends cpu,simd --md $OUT/table-cpu.md > $OUT/table-cpu.txt 2>&1; echo "cpu,simd rc=$?"
for be in opencl glsl-compute; do timeout 100 $T --sections throughput --scenes $S --backends $be --md $OUT/table-$be.md > $OUT/table-$be.txt 2>&1; echo "$be rc=$?"; done
timeout 200 $B/rill-bench-trace --size 1920x1080 --repeats 3 --sections throughput --scenes $S --backends glsl --md $OUT/table-glsl.md > $OUT/table-glsl.txt 2>&1; echo "glsl rc=$?"
grep -hE "^\| (thesis|stanford)" $OUT/table-*.txt
echo "== frames: rill-trace render S --size 1920x1080 --backend BE --bench-frames 20"
for sc in thesis-a thesis-b thesis-c bunny; do for be in cpu simd opencl glsl-compute glsl; do
  S1=builtin:$sc; [ $sc = bunny ] && S1=$BUNNY; N=20; [ $be = glsl ] && N=5
  echo "-- $sc $be $(timeout 120 $B/rill-trace render $S1 --size 1920x1080 --backend $be --bench-frames $N --out /tmp/f.png --stats-json $OUT/frames-$sc-$be.json | grep -E 'frames' | cut -d';' -f1)"
done; done
