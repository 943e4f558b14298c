#!/bin/bash
# Issue 52 item 2's read-back: glsl-compute's frame read-back with glGetBufferSubData (get)
# against a device copy into a GL_STREAM_READ buffer that is then mapped (staging), OpenCL's
# beside them; rill-trace render --bench-frames 20 at 1920x1080, the median frame's split.
# Run on the GPU machine from the repository root; ROUNDS (default 2) shortens it.
# Output: $OUT/readback.md.
source scripts/gpu-setup.sh
echo "| scene | backend | read-back | frame ms | kernel ms | read-back ms |" | tee $OUT/readback.md
echo "| --- | --- | --- | --- | --- | --- |" | tee -a $OUT/readback.md
for k in $(seq 1 "${ROUNDS:-2}"); do for scene in builtin:thesis-a builtin:thesis-c; do
  for run in "opencl -" "glsl-compute get" "glsl-compute staging"; do
    be=${run% *}; rb=${run#* }
    RILL_GLSL_READBACK=${rb/-/get} timeout 120 $B/rill-trace render $scene --size 1920x1080 --backend $be \
      --bench-frames 20 --out /tmp/rb-$be-$rb.png --stats-json /tmp/rb.json > /dev/null 2>&1 || { echo "| $scene | $be | $rb | failed | | |" | tee -a $OUT/readback.md; continue; }
    python3 - /tmp/rb.json "$scene" "$be" "$rb" <<'PY' | tee -a $OUT/readback.md
import json, sys
b = json.load(open(sys.argv[1]))["bench_frames"]; s = b["median_split_ms"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {b['median_ms']:.2f} | {s.get('kernel', -1):.2f} | {s.get('read_back', -1):.2f} |")
PY
  done
  cmp -s /tmp/rb-glsl-compute-get.png /tmp/rb-glsl-compute-staging.png && echo "$scene: same PNG both ways" | tee -a $OUT/readback.md
done; done
