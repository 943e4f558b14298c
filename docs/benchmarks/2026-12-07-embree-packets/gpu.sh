#!/bin/bash
# Issue 51 on the GPU machine's host CPU (16 threads): Embree 3.13's packet and stream modes
# beside its rtcIntersect1 and Rill's cpu and simd, on the same primary rays, thesis A, B, C
# and the bunny at 1920x1080, three rounds of `rill-bench-trace --sections embree` (each the
# median of 5 interleaved repeats). Run from the repository root through the device tool.
# Needs .devcarry/bin/rill-bench-trace built from this change, .devcarry/lib/libembree3.so.3
# (or .xz) beside the other carried libraries, and the bunny as .devcarry/stanford-bunny.obj
# (left out, with a note, where it is absent). Look for: "native yes" on the rtcIntersect8
# and rtcIntersect16 rows (else that width was emulated), "agree with Rill" of 99.9% or more
# on every row (the program exits 1 otherwise: rc=1), and the simd/Embree column.
source scripts/gpu-setup.sh
BUNNY=${BUNNY:-.devcarry/stanford-bunny.obj}
S=builtin:thesis-a,builtin:thesis-b,builtin:thesis-c
if [ -f "$BUNNY" ]; then S=$S,$BUNNY; else echo "note: no $BUNNY: the bunny is left out"; fi
lscpu | grep -E "Model name|^CPU\(s\)|Flags" | cut -c1-200
for round in 1 2 3; do
  timeout 170 "$B/rill-bench-trace" --sections embree --size 1920x1080 --repeats 5 --scenes "$S" \
    --md "$OUT/embree-modes-$round.md" > "$OUT/embree-modes-$round.txt" 2>&1
  echo "round $round rc=$?"
done
grep -h -A20 "ray modes" "$OUT"/embree-modes-*.md
