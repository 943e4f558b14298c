#!/bin/bash
# The wavefront strategy on simd with compaction of its masked launches on and off
# (RILL_SIMD_COMPACT), against cpu and the megakernel, interleaved; cornell-path, 4 spp,
# 320x240. Run from the repository root after a build.
B=build/apps/rill-trace/rill-trace
for round in 1 2 3; do
  for cfg in "wavefront simd on" "wavefront simd off" "wavefront cpu on" "megakernel simd on"; do
    set -- $cfg
    echo "cornell-path spp4 $1 $2 compact=$3 round $round: $(RILL_SIMD_COMPACT=$3 $B render builtin:cornell-path --size 320x240 --spp 4 --strategy $1 --backend $2 --bench-frames 3 --out /dev/null --quiet | grep -o 'after the first: median [0-9.]* ms')"
  done
done
