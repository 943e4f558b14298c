#!/bin/bash
# simd against cpu on the path tracer (cornell-path, 4 spp) and thesis A, then the megakernel
# against the wavefront on both; run from the repository root after a build.
B=build/apps/rill-trace/rill-trace
for round in 1 2 3 4; do for be in simd cpu; do
echo "cornell-path spp4 $be round $round: $($B render builtin:cornell-path --size 320x240 --spp 4 --backend $be --bench-frames 3 --out /dev/null --quiet | grep -o 'after the first: median [0-9.]* ms')"
done; done
for round in 1 2 3; do for be in simd cpu; do
echo "thesis-a $be round $round: $($B render builtin:thesis-a --size 320x240 --backend $be --bench-frames 9 --out /dev/null --quiet | grep -o 'after the first: median [0-9.]* ms')"
done; done
B=build/apps/rill-trace/rill-trace
for round in 1 2 3; do for st in megakernel wavefront; do for be in simd cpu; do
echo "cornell-path spp4 $st $be round $round: $($B render builtin:cornell-path --size 320x240 --spp 4 --strategy $st --backend $be --bench-frames 3 --out /dev/null --quiet | grep -o 'after the first: median [0-9.]* ms')"
done; done; done
# simd against cpu on cornell-path by the paths' length: no bounce, two (before Russian
# roulette, which starts at depth 3), eight (the scene's).
for round in 1 2; do for d in 0 2 8; do for be in simd cpu; do
echo "cornell-path max-depth $d $be round $round: $($B render builtin:cornell-path --size 320x240 --spp 4 --max-depth $d --backend $be --bench-frames 3 --out /dev/null --quiet | grep -o 'after the first: median [0-9.]* ms')"
done; done; done
