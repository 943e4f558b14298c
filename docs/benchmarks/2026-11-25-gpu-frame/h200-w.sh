#!/bin/bash
# Session 26 (2026-11-29), after h200-v.sh: the H200 table (docs/gpu.md's then; now docs/benchmarks/2026-12-07-gpu-history.md) with this session's build
# (84e9679), in two machine calls. PART=1: primary and full throughput as h200-t.sh (one
# process per GPU backend, Embree on the 16 host cores beside cpu and simd). PART=2: the
# frame times, rill-trace render S --size 1920x1080 --backend B --bench-frames N, two
# processes each (the table takes the lower). Set-up as h200-s.sh, with Embree unpacked.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
[ -f .devcarry/lib/libembree3.so.3 ] || python3 -c "import lzma, shutil; shutil.copyfileobj(lzma.open('.devcarry/lib/libembree3.so.3.xz'), open('.devcarry/lib/libembree3.so.3', 'wb'))"
BUNNY=.devcarry/stanford-bunny.obj
S=builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,$BUNNY
if [ "$PART" = 1 ]; then
  T="$B/rill-bench-trace --size 1920x1080 --repeats 5 --sections throughput"
  timeout 230 $T,embree --scenes $S --backends cpu,simd --md $OUT/table-cpu.md > $OUT/table-cpu.txt 2>&1; echo "cpu,simd rc=$?"
  for be in opencl glsl-compute; do timeout 90 $T --scenes $S --backends $be --md $OUT/table-$be.md > $OUT/table-$be.txt 2>&1; echo "$be rc=$?"; done
  timeout 170 $B/rill-bench-trace --size 1920x1080 --repeats 3 --sections throughput --scenes $S --backends glsl --md $OUT/table-glsl.md > $OUT/table-glsl.txt 2>&1; echo "glsl rc=$?"
  grep -hE "^\| (thesis|stanford)" $OUT/table-*.txt
else
  for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c $BUNNY; do for be in opencl glsl-compute cpu simd glsl; do
    N=20; [ $be = glsl ] && N=5; [ $be = cpu -o $be = simd ] && [ $sc = builtin:thesis-b -o $sc = builtin:thesis-c ] && N=7
    for k in 1 2; do
      echo "-- $(basename $sc) $be $(timeout 60 $B/rill-trace render $sc --size 1920x1080 --backend $be --bench-frames $N --out /tmp/f.png | grep 'frames of' | sed -E 's/.*first: median ([0-9.]+) ms.*/frame \1/')"
    done
  done; done
fi
