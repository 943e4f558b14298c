#!/bin/bash
# Issue 51 item 4 on the GPU machine's host CPU (16 threads): `rill-trace render`'s Whitted
# frame on cpu and simd against the plain Embree renderer of bench/embree_whitted.h, thesis A,
# B, C, glass and the bunny at 1920x1080, full frames and camera-only frames (shadows off, max
# depth 0), three rounds of `rill-bench-trace --sections embree,whitted` (each figure the
# median of 3 interleaved repeats; the embree section gives hit finding on the same primary
# rays, Rill's intersector kernel against rtcIntersect1). Run from the repository root through
# the device tool. Needs .devcarry/bin/rill-bench-trace built from this change,
# .devcarry/lib/libembree3.so.3 (or .xz) beside the other carried libraries, and the bunny as
# .devcarry/stanford-bunny.obj (left out, with a note, where it is absent). Look for: rc=0 on
# every round (1: an image or the hits disagreed), "pixels agree" of 99% or more, Rill rays
# equal to Embree's total (the same ray trees), and the Rill/Embree column of the Whitted
# table (at least 0.8 is issue 51's goal).
source scripts/gpu-setup.sh
BUNNY=${BUNNY:-.devcarry/stanford-bunny.obj}
S=builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,builtin:glass
if [ -f "$BUNNY" ]; then S=$S,$BUNNY; else echo "note: no $BUNNY: the bunny is left out"; fi
lscpu | grep -E "Model name|^CPU\(s\)" | cut -c1-200
for round in 1 2 3; do
  timeout 190 "$B/rill-bench-trace" --sections embree,whitted --whitted-frames full,camera \
    --embree-modes 8 --size 1920x1080 --repeats 3 --scenes "$S" \
    --md "$OUT/whitted-$round.md" > "$OUT/whitted-$round.txt" 2>&1
  echo "round $round rc=$? load $(cut -d' ' -f1-3 /proc/loadavg)"
done
grep -h -A16 "Whitted frames" "$OUT"/whitted-*.md
