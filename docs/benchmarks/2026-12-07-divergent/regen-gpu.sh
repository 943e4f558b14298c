#!/bin/bash
# The GPU rows of path regeneration (2026-12-07-divergent.md, "path regeneration"): the path
# megakernel with RILL_PATH_REGENERATE=on (up to 16 samples per launch, a work-item whose path
# ended starting its next sample at once) and off (one sample per launch, as before), on
# opencl and glsl-compute, cornell-path and thesis C with an area light, 1920x1080, 4 and 16
# spp, the two settings interleaved per round; the 16-core cpu and simd backends at 4 spp for
# the ratio. First a bitwise check: on and off give the same PFM on each GPU backend.
# Run on the GPU machine from the repository root, set up by scripts/gpu-setup.sh (rill-trace
# and its shared libraries in .devcarry/, the loaders' packages in .gl/). ROUNDS (default 2)
# shortens it. Output: $OUT/info.txt, $OUT/table.md.
source scripts/gpu-setup.sh
here=docs/benchmarks/2026-12-07-divergent
area=docs/benchmarks/2026-12-07-path/thesis-c-area.json
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee $OUT/info.txt
nproc | sed 's/^/host cores: /' | tee -a $OUT/info.txt
# Bitwise: regeneration changes no bit (colour and depth) on the GPU backends.
for be in opencl glsl-compute; do for scene in builtin:cornell-path $area; do
  for r in on off; do
    RILL_PATH_REGENERATE=$r timeout 150 $B/rill-trace render $scene --size 640x480 --spp 8 --backend $be \
      --out /tmp/r-$r.png --pfm /tmp/r-$r.pfm --depth /tmp/r-$r.depth.pfm --quiet > /dev/null 2>&1
  done
  if cmp -s /tmp/r-on.pfm /tmp/r-off.pfm && cmp -s /tmp/r-on.depth.pfm /tmp/r-off.depth.pfm; then v=same; else v=DIFFERENT; fi
  echo "bitwise $be $(basename $scene) 640x480 8 spp, regenerate on vs off: $v" | tee -a $OUT/info.txt
done; done
echo "| scene | spp | backend | regenerate | frame ms (median) | kernel ms | launches |" | tee $OUT/table.md
echo "| --- | --- | --- | --- | --- | --- | --- |" | tee -a $OUT/table.md
row() { # scene spp backend regenerate frames
  local scene=$1 spp=$2 be=$3 r=$4 frames=$5
  RILL_PATH_REGENERATE=$r timeout 300 $B/rill-trace render $scene --size 1920x1080 --spp $spp --backend $be \
    --bench-frames $frames --out /tmp/o.png --stats-json /tmp/s.json > /tmp/row.log 2>&1 || {
    echo "| $scene | $spp | $be | $r | failed: $(tail -1 /tmp/row.log | tr '|' '/') | | |" | tee -a $OUT/table.md; return; }
  python3 - /tmp/s.json "$(basename $scene)" "$spp" "$be" "$r" <<'PY' | tee -a $OUT/table.md
import json, sys
j = json.load(open(sys.argv[1])); b = j["bench_frames"]
k = b["median_split_ms"].get("kernel", -1)
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {sys.argv[5]} | {b['median_ms']:.2f} | {k:.2f} | {j.get('launches', '')} |")
PY
}
for round in $(seq ${ROUNDS:-2}); do
  for scene in builtin:cornell-path $area; do
    for spp in 4 16; do for be in opencl glsl-compute; do for r in on off; do
      row $scene $spp $be $r 10
    done; done; done
    for be in cpu simd; do for r in on off; do row $scene 4 $be $r 3; done; done
  done
done
