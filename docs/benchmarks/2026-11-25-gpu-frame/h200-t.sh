#!/bin/bash
# Session 25 (2026-11-28), after h200-s.sh in the same machine session: the H200 table (docs/gpu.md's then; now docs/benchmarks/2026-12-07-gpu-history.md)
# with this session's build, as h200-k.sh PART=1 (primary and full throughput, one process per
# GPU backend, Embree on the 16 host cores beside cpu and simd); the frame times are
# h200-s.sh's new-build rows. Set-up as h200-s.sh, with Embree unpacked.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
[ -f .devcarry/lib/libembree3.so.3 ] || python3 -c "import lzma, shutil; shutil.copyfileobj(lzma.open('.devcarry/lib/libembree3.so.3.xz'), open('.devcarry/lib/libembree3.so.3', 'wb'))"
BUNNY=.devcarry/stanford-bunny.obj
S=builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,$BUNNY
T="$B/rill-bench-trace --size 1920x1080 --repeats 5 --sections throughput"
timeout 230 $T,embree --scenes $S --backends cpu,simd --md $OUT/table-cpu.md > $OUT/table-cpu.txt 2>&1; echo "cpu,simd rc=$?"
for be in opencl glsl-compute; do timeout 90 $T --scenes $S --backends $be --md $OUT/table-$be.md > $OUT/table-$be.txt 2>&1; echo "$be rc=$?"; done
timeout 170 $B/rill-bench-trace --size 1920x1080 --repeats 3 --sections throughput --scenes $S --backends glsl --md $OUT/table-glsl.md > $OUT/table-glsl.txt 2>&1; echo "glsl rc=$?"
grep -hE "^\| (thesis|stanford)" $OUT/table-*.txt
