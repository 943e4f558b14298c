#!/bin/bash
# The evening's one GPU run (2026-12-07), every part short enough to fit one call of the GPU
# machine: (1) the strict conformance suite on glsl-compute, glsl and vulkan with their
# defaults (the fused lean division and square root where the fma is fused; Vulkan's denormal
# probe and memory placement); (2) frames at 1920x1080 of OpenCL against glsl-compute (lean,
# the old fused residual, the staging read-back) and vulkan, with the strict images compared;
# (3) rill-bench-trace --sections shared; (4) path regeneration on and off. The longer
# scripts of each part: 2026-12-07-glsl-strict/gpu-lean.sh, 2026-12-07-vulkan/gpu.sh,
# 2026-12-07-shared-process/gpu.sh, 2026-12-07-readback/gpu.sh, 2026-12-07-divergent/regen-gpu.sh.
# Run from the repository root on the GPU machine. Output: $OUT/info.txt, $OUT/frames.md,
# $OUT/shared.md, $OUT/regen.md, $OUT/conformance.txt.
# SHORT=1: what fits a call of about 200 s (the conformance suite for at most 90 s; OpenCL,
# lean glsl-compute, its staging read-back and vulkan on cornell-path, thesis C and thesis A;
# the shared section on thesis C, 3 repeats; no regeneration rows).
source scripts/gpu-setup.sh
short=${SHORT:-0}
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee $OUT/info.txt
$B/rill-trace info 2>&1 | grep -E "^  (opencl|glsl|vulkan)" | tee -a $OUT/info.txt
# (1)
timeout $([ $short = 1 ] && echo 90 || echo 200) $B/rill-conformance --backend glsl-compute,glsl,vulkan --accuracy strict > $OUT/conformance.txt 2>&1
echo "conformance strict glsl-compute,glsl,vulkan: rc=$?" | tee -a $OUT/info.txt
grep -E "^(glsl|glsl-compute|vulkan) strict|FAIL" $OUT/conformance.txt | head -30 | tee -a $OUT/info.txt
# (2)
echo "| scene | backend | setting | frame ms (median of 20) | kernel ms | read-back ms |" | tee $OUT/frames.md
echo "| --- | --- | --- | --- | --- | --- |" | tee -a $OUT/frames.md
row() { frame_row $OUT/frames.md "$@"; }
area=docs/benchmarks/2026-12-07-path/thesis-c-area.json
scenes=("builtin:cornell-path|--max-depth 8 --spp 1" "$area|--max-depth 8 --spp 1" "builtin:thesis-a|" "builtin:thesis-c|")
[ $short = 1 ] && scenes=("builtin:cornell-path|--max-depth 8 --spp 1" "builtin:thesis-c|" "builtin:thesis-a|")
for s in "${scenes[@]}"; do
  scene=${s%%|*}; args=${s#*|}
  row "$scene" "$args" strict opencl
  row "$scene" "$args" "strict lean" glsl-compute
  [ $short = 1 ] || row "$scene" "$args" "strict residual" glsl-compute RILL_GLSL_FUSED=residual
  row "$scene" "$args" "strict lean staging" glsl-compute RILL_GLSL_READBACK=staging
  row "$scene" "$args" "strict" vulkan
  [ $short = 1 ] || row "$scene" "$args" "native div-sqrt" glsl-compute RILL_GLSL_DIVSQRT=native
  for p in /tmp/o-glsl-compute-strict*.png /tmp/o-vulkan-strict*.png; do
    cmp -s /tmp/o-opencl-strict.png "$p" || echo "$scene: $(basename $p) DIFFERS from opencl's" | tee -a $OUT/info.txt
  done
  echo "$scene: strict images compared" | tee -a $OUT/info.txt; rm -f /tmp/o-*.png
done
# (3)
shared_scenes=builtin:thesis-c,builtin:thesis-a; repeats=5
[ $short = 1 ] && shared_scenes=builtin:thesis-c && repeats=3
timeout 150 $B/rill-bench-trace --sections shared --backends opencl,glsl-compute,vulkan --size 1920x1080 \
  --scenes $shared_scenes --repeats $repeats --md $OUT/shared.md > $OUT/shared.txt 2>&1
echo "shared section rc=$?" | tee -a $OUT/info.txt
# (4)
[ $short = 1 ] && exit 0
echo "| scene | backend | regenerate | frame ms | kernel ms |" > $OUT/regen.md
for be in opencl glsl-compute; do for r in off on; do
  RILL_PATH_REGENERATE=$r timeout 60 $B/rill-trace render builtin:cornell-path --size 1920x1080 --spp 16 --backend $be \
    --bench-frames 5 --out /tmp/r-$be-$r.png --stats-json /tmp/s.json > /dev/null 2>&1 || { echo "| cornell-path 16spp | $be | $r | failed | |" >> $OUT/regen.md; continue; }
  python3 -c "
import json; b=json.load(open('/tmp/s.json'))['bench_frames']; print(f\"| cornell-path 16 spp | $be | $r | {b['median_ms']:.2f} | {b['median_split_ms'].get('kernel',-1):.2f} |\")" >> $OUT/regen.md
done; cmp -s /tmp/r-$be-on.png /tmp/r-$be-off.png && echo "regen $be: same PNG on and off" | tee -a $OUT/info.txt; done
cat $OUT/regen.md
