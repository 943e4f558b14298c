#!/bin/bash
# The GPU run of the lean correction (2026-12-07-glsl-strict.md, "What is left (2026-12-07,
# evening)"): strict glsl, glsl-compute and vulkan with the fused rule's lean correction
# against the fused residual and the split rule, bit for bit (the strict conformance suite),
# then frames of strict glsl-compute under each rule against OpenCL and the driver's own / and
# sqrt. Run on the GPU machine from the repository root, set up by scripts/gpu-setup.sh
# (rill-trace, rill-conformance with their shared libraries and the Vulkan loader in .devcarry/,
# the GL and OpenCL loaders' Debian packages in .gl/).
# PART=conformance|frames|all (default all), ROUNDS (default 2) and SCENES (";"-separated
# "scene|args" entries) shorten it. Output: $OUT/info.txt, $OUT/conformance-*.txt, $OUT/table.md.
source scripts/gpu-setup.sh
here=docs/benchmarks/2026-12-07-glsl-strict
part=${PART:-all}
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee -a $OUT/info.txt
# The backends' lines: "strict / and sqrt: corrected, fused lean" where the probe finds fma fused.
$B/rill-trace info 2>&1 | grep -E "^  (opencl|glsl|vulkan)" | tee -a $OUT/info.txt
if [ "$part" != frames ]; then
  # Bitwise: every row must pass on each stage under each rule (auto = fused lean on NVIDIA).
  for be in glsl-compute glsl vulkan; do
    for rule in "auto lean" "fused residual" "split lean"; do
      fma=${rule% *}; fused=${rule#* }
      f=$OUT/conformance-$be-$fma-$fused.txt
      RILL_GLSL_FMA=$fma RILL_GLSL_FUSED=$fused timeout 200 $B/rill-conformance --backend $be --accuracy strict > $f 2>&1
      echo "conformance $be strict RILL_GLSL_FMA=$fma RILL_GLSL_FUSED=$fused: rc=$?, $(grep -E '^(glsl|vulkan)' $f | head -1)" | tee -a $OUT/info.txt
    done
  done
fi
[ "$part" = conformance ] && exit 0
echo "| scene | backend | rule | frame ms (median of 20) | kernel ms | read-back ms |" | tee $OUT/table.md
echo "| --- | --- | --- | --- | --- | --- |" | tee -a $OUT/table.md
row() { frame_row $OUT/table.md "$@"; }
default_scenes=("builtin:cornell-path|--max-depth 8 --spp 1" "$here/../2026-12-07-path/thesis-c-area.json|--max-depth 8 --spp 1" "builtin:thesis-a|" "builtin:thesis-c|" "builtin:glass|")
if [ -n "${SCENES:-}" ]; then IFS=";" read -r -a scenes <<< "$SCENES"; else scenes=("${default_scenes[@]}"); fi
for k in $(seq 1 "${ROUNDS:-2}"); do
for s in "${scenes[@]}"; do
  scene=${s%%|*}; args=${s#*|}
  row "$scene" "$args" strict opencl
  row "$scene" "$args" "strict, split residual" glsl-compute RILL_GLSL_FMA=split
  row "$scene" "$args" "strict, fused residual" glsl-compute RILL_GLSL_FMA=fused RILL_GLSL_FUSED=residual
  row "$scene" "$args" "strict, fused lean" glsl-compute RILL_GLSL_FMA=fused RILL_GLSL_FUSED=lean
  row "$scene" "$args" "strict, fused lean" vulkan RILL_GLSL_FMA=fused RILL_GLSL_FUSED=lean
  row "$scene" "$args" "driver / and sqrt (not strict)" glsl-compute RILL_GLSL_DIVSQRT=native
  # Strict is the same image on every backend and rule: compare them with OpenCL's.
  for p in /tmp/o-glsl-compute-strict*.png /tmp/o-vulkan-strict*.png; do
    cmp -s /tmp/o-opencl-strict.png "$p" || { echo "$scene: $(basename $p) DIFFERS from opencl's" | tee -a $OUT/info.txt; cp "$p" $OUT/; }
  done
  echo "$scene: strict images compared with opencl's (differences listed above)" | tee -a $OUT/info.txt
  rm -f /tmp/o-*.png
done; done
