#!/bin/bash
# The GPU run of 2026-12-07-glsl-strict.md: strict glsl-compute against OpenCL, with the
# division and square-root corrections' residual split (Dekker) or fused (one fma), and with
# the driver's own / and sqrt (not strict: shows what the corrections cost). Run on the GPU
# machine from the repository root, rill-trace and rill-conformance with their shared libraries
# in .devcarry/ (bin/, lib/), the GL and OpenCL loaders' Debian packages in .gl/, as
# docs/benchmarks/2026-12-07-path/h200.sh does. Output: $OUT/conformance-*.txt, $OUT/table.md.
source scripts/gpu-setup.sh  # the drivers, the carried binaries: B
here=docs/benchmarks/2026-12-07-glsl-strict
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee $OUT/info.txt
$B/rill-trace info 2>&1 | grep -E "^  (opencl|glsl)" | tee -a $OUT/info.txt
# Bitwise: the strict conformance suite with the rule's default (auto: fused on NVIDIA) and split.
for be in glsl-compute glsl; do for fma in auto split fused; do
  RILL_GLSL_FMA=$fma timeout 200 $B/rill-conformance --backend $be --accuracy strict > $OUT/conformance-$be-$fma.txt 2>&1
  echo "conformance $be strict RILL_GLSL_FMA=$fma: $(grep -E '^(glsl|opencl)' $OUT/conformance-$be-$fma.txt | head -1) rc=$?" | tee -a $OUT/info.txt
done; done
echo "| scene | backend | rule | frame ms (median of 20) | kernel ms |" | tee $OUT/table.md
echo "| --- | --- | --- | --- | --- |" | tee -a $OUT/table.md
row() { # scene extra-args label backend env...
  local scene=$1 args=$2 label=$3 be=$4; shift 4
  env RILL_X=1 "$@" timeout 120 $B/rill-trace render $scene $args --size 1920x1080 --backend $be \
    --bench-frames 20 --out /tmp/o.png --stats-json /tmp/s.json > /dev/null 2>&1 || { echo "| $scene | $be | $label | failed | |" | tee -a $OUT/table.md; return; }
  python3 - /tmp/s.json "$(basename $scene .json)" "$be" "$label" <<'PY' | tee -a $OUT/table.md
import json, sys
j = json.load(open(sys.argv[1])); b = j["bench_frames"]
k = b["median_split_ms"].get("kernel", -1)
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {b['median_ms']:.2f} | {k:.2f} |")
PY
}
for k in 1 2; do
for s in "builtin:cornell-path|--max-depth 8 --spp 1" "$here/../2026-12-07-path/thesis-c-area.json|--max-depth 8 --spp 1" "builtin:thesis-a|" "builtin:thesis-c|" "builtin:glass|"; do
  scene=${s%%|*}; args=${s#*|}
  row "$scene" "$args" strict opencl
  row "$scene" "$args" "strict, split residual" glsl-compute RILL_GLSL_FMA=split
  row "$scene" "$args" "strict, fused residual" glsl-compute RILL_GLSL_FMA=fused
  row "$scene" "$args" "driver / and sqrt (not strict)" glsl-compute RILL_GLSL_DIVSQRT=native
  row "$scene" "$args --accuracy fast" fast opencl
  row "$scene" "$args --accuracy fast" fast glsl-compute
done; done
