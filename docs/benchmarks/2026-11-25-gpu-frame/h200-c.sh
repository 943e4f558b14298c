#!/bin/bash
# Issue 20 on the GPU machine: read-back straight into reused memory; OpenCL tiles and group
# sizes side by side; frames; identity.
source "$(dirname "$0")/setup.sh"
BUNNY=.devcarry/stanford-bunny.obj
timeout 100 $B/rill_backend_tests --gtest_filter='*/opencl:*/glsl_compute' > $OUT/be-tests.txt 2>&1; echo "backend tests rc=$?"; tail -1 $OUT/be-tests.txt
echo "== tiles and group sizes (rill-bench-trace --sections throughput --size 1920x1080 --backends opencl --repeats 5)"
for round in 1 2; do for cfg in "on 64" "off 64" "on 128" "on 32" "on 256"; do set -- $cfg
  echo "-- round $round tiles $1 group $2"
  RILL_OPENCL_TILES=$1 RILL_OPENCL_GROUP=$2 timeout 100 $B/rill-bench-trace --sections throughput --size 1920x1080 --scenes builtin:thesis-a,builtin:thesis-c,$BUNNY --backends opencl --repeats 5 2>&1 | grep -E "\| opencl \|"
done; done
echo "== frames (rill-trace render --size 1920x1080 --bench-frames 20)"
for sc in thesis-a thesis-b thesis-c bunny; do for be in opencl glsl-compute; do
  S=builtin:$sc; [ $sc = bunny ] && S=$BUNNY
  echo "-- $sc $be"; timeout 120 $B/rill-trace render $S --size 1920x1080 --backend $be --bench-frames 20 --out /tmp/f.png --stats-json $OUT/frames-$sc-$be.json | grep -E "frames|median per step"
done; done
for sc in thesis-b glass cornell; do
  for be in cpu opencl glsl glsl-compute; do timeout 60 $B/rill-trace render builtin:$sc --backend $be --size 160x120 --spp 3 --pfm /tmp/$sc-$be.pfm --out /tmp/$sc-$be.png > /dev/null 2>>$OUT/render-err.txt || echo "render $sc $be failed"; done
  for be in opencl glsl glsl-compute; do cmp -s /tmp/$sc-cpu.pfm /tmp/$sc-$be.pfm && cmp -s /tmp/$sc-cpu.png /tmp/$sc-$be.png && echo "same bits $sc $be" || echo "DIFFERENT $sc $be"; done
done
