#!/bin/bash
# The CPU figures of 2026-12-07-divergent.md (issue 52, items 3-5), on the machine at hand.
# Run from the repository root after a build; writes its output to stdout.
# Every process renders once (cold, compiling from the disk cache) and then --bench-frames N
# more; the figure is the median of those, alternating the backends (or settings) per round.
B=${RILL_TRACE:-build/apps/rill-trace/rill-trace}
median() { grep -o "median [0-9.]* ms" | grep -o "[0-9.]*"; }
echo "== simd against cpu, builtin:glass 640x480 (glass and mirrors), 3 frames per process"
for round in 1 2 3; do
  for be in simd cpu; do
    echo "glass $be round $round: $($B render builtin:glass --size 640x480 --backend $be --bench-frames 3 --out /dev/null --quiet | median) ms"
  done
done
echo "== the same, one thread (--threads 1)"
for round in 1 2; do
  for be in simd cpu; do
    echo "glass $be threads 1 round $round: $($B render builtin:glass --size 640x480 --backend $be --threads 1 --bench-frames 3 --out /dev/null --quiet | median) ms"
  done
done
echo "== simd against cpu, the other built-in scenes at 320x240, 5 frames per process"
for s in thesis-a thesis-b thesis-c cornell cornell-path textured bounce; do
  for round in 1 2; do
    for be in simd cpu; do
      echo "$s $be round $round: $($B render builtin:$s --size 320x240 --backend $be --bench-frames 5 --out /dev/null --quiet | median) ms"
    done
  done
done
echo "== first use: one render's line, then the warm frames (glass 640x480)"
for be in cpu simd opencl; do
  $B render builtin:glass --size 640x480 --backend $be --out /dev/null --quiet
  $B render builtin:glass --size 640x480 --backend $be --out /dev/null --quiet --bench-frames 3
done
echo "== overlap: builtin:bounce, 24 frames at 640x480 with PNGs, wall time"
d=$(mktemp -d)
for round in 1 2; do
  for ov in on off; do
    t0=$(date +%s.%N)
    $B render builtin:bounce --size 640x480 --backend simd --frames 0:23 --out $d/f-%02d.png --overlap $ov --quiet --stats-json $d/s.json > /dev/null
    t1=$(date +%s.%N)
    tr=$(python3 -c "import json; print(round(json.load(open('$d/s.json'))['time_ms']['trace'], 1))")
    echo "bounce overlap $ov round $round: wall $(python3 -c "print(round(($t1 - $t0) * 1000, 1))") ms, trace of the 24 frames $tr ms"
  done
done
rm -rf "$d"
