#!/bin/bash
# Issue 52 item 5: frame n's device read-back overlapping frame n + 1's trace (--overlap on)
# against read-back before the next frame (--overlap off), at 1920x1080, in interleaved rounds:
#  - rill-trace render S --bench-frames 20 on thesis A and thesis C, opencl and glsl-compute,
#    the median frame and its split (with overlap on, a frame's read-back step is starting it
#    plus waiting for it after the next frame traced); the PNGs of on and off compared;
#  - rill-trace render builtin:bounce --frames 0:20 on opencl and glsl-compute, the wall time
#    of the command (kernels from the disk cache after the first round), the frames compared.
# Run on the GPU machine from the repository root; ROUNDS (default 2: one call of the GPU machine) sets the rounds.
# Output: $OUT/overlap.md.
source scripts/gpu-setup.sh
T=$OUT/overlap.md
echo "| scene | backend | overlap | frame ms | kernel ms | read-back ms |" | tee "$T"
echo "| --- | --- | --- | --- | --- | --- |" | tee -a "$T"
for k in $(seq 1 "${ROUNDS:-2}"); do
  for scene in builtin:thesis-a builtin:thesis-c; do
    for be in opencl glsl-compute; do
      for ov in on off; do frame_row "$T" "$scene" "--overlap $ov" "$ov" "$be"; done
      cmp -s "/tmp/o-$be-on.png" "/tmp/o-$be-off.png" && echo "$scene $be: the same PNG on and off" | tee -a "$T"
    done
  done
  for be in opencl glsl-compute; do
    for ov in on off; do
      rm -rf "/tmp/seq-$ov" && mkdir -p "/tmp/seq-$ov"
      t0=$(date +%s%N)
      timeout 300 "$B/rill-trace" render builtin:bounce --size 1920x1080 --backend $be --frames 0:20 \
        --overlap "$ov" --quiet --out "/tmp/seq-$ov/f-%03d.png" > /tmp/seq.log 2>&1 || { echo "bounce $be --frames 0:20 --overlap $ov: failed: $(tail -1 /tmp/seq.log)" | tee -a "$T"; continue; }
      echo "bounce $be --frames 0:20 --overlap $ov: $(( ($(date +%s%N) - t0) / 1000000 )) ms (the whole command)" | tee -a "$T"
    done
    diff -rq /tmp/seq-on /tmp/seq-off > /dev/null && echo "bounce $be: the same 21 PNGs on and off" | tee -a "$T"
  done
done
