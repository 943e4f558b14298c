#!/bin/bash
# The GPU rows of 2026-12-07-divergent.md (issue 52, items 3-5), to run on the H200 machine
# (not run yet: no GPU machine came in the session that wrote it). Set-up as the dynamic-scene
# folder's (carried binaries in .devcarry/bin, libraries in .devcarry/lib); output to $OUT.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
nvidia-smi --query-gpu=name,clocks.sm,pstate --format=csv,noheader
echo "== item 3: builtin:glass 640x480, warm frames (median of 20), the 16-core cpu and simd beside the GPU"
for round in 1 2; do for be in opencl glsl-compute cpu simd; do
  echo "-- round $round $be $(timeout 120 $B/rill-trace render builtin:glass --size 640x480 --backend $be --bench-frames 20 --out /dev/null --quiet | grep -E 'frames of' | cut -d';' -f1)"
done; done
echo "== item 3: simd against cpu on the other built-in scenes, 1920x1080, median of 10"
for sc in thesis-a thesis-b thesis-c cornell cornell-path textured bounce; do for round in 1 2; do for be in simd cpu; do
  echo "-- $sc $be round $round $(timeout 120 $B/rill-trace render builtin:$sc --size 1920x1080 --backend $be --bench-frames 10 --out /dev/null --quiet | grep -E 'frames of' | cut -d';' -f1)"
done; done; done
echo "== item 4: one render's line (cold), then with --bench-frames 20 (warm Mrays/s)"
for be in opencl glsl-compute cpu; do
  timeout 120 $B/rill-trace render builtin:glass --size 640x480 --backend $be --out /dev/null --quiet
  timeout 120 $B/rill-trace render builtin:glass --size 640x480 --backend $be --out /dev/null --quiet --bench-frames 20
done
echo "== item 5: builtin:bounce, 97 frames at 1920x1080 with PNGs, --overlap on and off (wall time)"
d=$(mktemp -d)
for round in 1 2; do for be in opencl glsl-compute; do for ov in on off; do
  t0=$(date +%s.%N)
  timeout 300 $B/rill-trace render builtin:bounce --size 1920x1080 --backend $be --frames 0:96 --out $d/f-%02d.png --overlap $ov --quiet > /dev/null
  echo "-- round $round $be overlap $ov: wall $(python3 -c "print(round(($(date +%s.%N) - $t0) * 1000))") ms"
done; done; done
rm -rf "$d"
