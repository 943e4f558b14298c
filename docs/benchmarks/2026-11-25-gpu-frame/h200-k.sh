#!/bin/bash
# Issue 20 on the GPU machine, session 16: the H200 table (docs/gpu.md's then; now docs/benchmarks/2026-12-07-gpu-history.md) again, with this session's
# build (32-bit gather indices, the three-gather sRGB encoding, the kernel time in the frame
# split): every backend's primary and full throughput (one process per GPU backend, Embree
# on the 16 host cores beside cpu and simd) and frame time. PART=1: the throughput; PART=2:
# the frames. Set-up: the dynamic-scene folder's setup.sh (carried libraries in .devcarry/lib).
source docs/benchmarks/2026-11-25-dynamic/setup.sh
[ -f .devcarry/lib/libembree3.so.3 ] || python3 -c "import lzma, shutil; shutil.copyfileobj(lzma.open('.devcarry/lib/libembree3.so.3.xz'), open('.devcarry/lib/libembree3.so.3', 'wb'))"
BUNNY=.devcarry/stanford-bunny.obj
S=builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,$BUNNY
T="$B/rill-bench-trace --size 1920x1080 --repeats 5 --sections throughput"
if [ "${PART:-1}" = 1 ]; then
  timeout 250 $T,embree --scenes $S --backends cpu,simd --md $OUT/table-cpu.md > $OUT/table-cpu.txt 2>&1; echo "cpu,simd rc=$?"
  for be in opencl glsl-compute; do timeout 100 $T --scenes $S --backends $be --md $OUT/table-$be.md > $OUT/table-$be.txt 2>&1; echo "$be rc=$?"; done
  timeout 200 $B/rill-bench-trace --size 1920x1080 --repeats 3 --sections throughput --scenes $S --backends glsl --md $OUT/table-glsl.md > $OUT/table-glsl.txt 2>&1; echo "glsl rc=$?"
  grep -hE "^\| (thesis|stanford)" $OUT/table-*.txt
  grep -hiE "embree" $OUT/table-cpu.txt | head -20
else
  for sc in thesis-a thesis-b thesis-c bunny; do for be in cpu simd opencl glsl-compute glsl; do
    S1=builtin:$sc; [ $sc = bunny ] && S1=$BUNNY; N=20; [ $be = glsl ] && N=5; [ $be = cpu -o $be = simd ] && [ $sc = thesis-b -o $sc = thesis-c ] && N=7
    echo "-- $sc $be $(timeout 100 $B/rill-trace render $S1 --size 1920x1080 --backend $be --bench-frames $N --out /tmp/f.png --stats-json $OUT/frames-$sc-$be.json | grep -E 'frames of|median per step' | tr '\n' ' ' | sed 's/; [a-z-]*: .*  median/; median/')"
  done; done
fi
