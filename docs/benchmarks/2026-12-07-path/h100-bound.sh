#!/bin/bash
# What bounds the first version (2026-12-07, H100): cornell-path at 1920x1080, strict, spp 1,
# median of 20 frames, OpenCL and glsl-compute: the megakernel against the wavefront strategy
# (the same image: if the wavefront's stage-by-stage launches were faster, divergence between
# paths of different depth would be the bound), and max_depth 1, 2, 4, 8 (the cost per bounce).
# glsl-compute strict three times (the first run's two processes gave 52.8 and 12.8 ms).
source <(sed -n '/^for f in .gl/,/^B=/p' docs/benchmarks/2026-12-07-path/h200.sh)
frame() { timeout 120 $B/rill-trace render builtin:cornell-path --size 1920x1080 --spp 1 --bench-frames 20 --out /tmp/f.png "$@" | grep 'frames of' | sed -E 's/.*first: median ([0-9.]+) ms.*/\1/'; }
for be in opencl glsl-compute; do
  for st in megakernel wavefront; do for d in 1 2 4 8; do
    echo "| $be | $st | $d | $(frame --backend $be --strategy $st --max-depth $d) |"
  done; done
done | tee $OUT/bound.md
for k in 1 2 3; do echo "glsl-compute strict depth 8 run $k: $(frame --backend glsl-compute --max-depth 8) ms"; done | tee -a $OUT/bound.md
