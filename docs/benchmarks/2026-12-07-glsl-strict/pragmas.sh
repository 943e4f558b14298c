#!/bin/bash
# The second GPU run of 2026-12-07-glsl-strict.md: do NVIDIA's GLSL pragmas
# optionNV(fastmath off) and optionNV(fastprecision off) make the driver's own / and sqrt
# correctly rounded (the strict conformance suite with RILL_GLSL_DIVSQRT=native), and what do
# they cost? Set-up as gpu.sh (same folder).
sed -n '/^for f in .gl/,/^export RILL_GL/p' docs/benchmarks/2026-12-07-glsl-strict/gpu.sh > /tmp/setup.sh; source /tmp/setup.sh
B=.devcarry/bin; here=docs/benchmarks/2026-12-07-glsl-strict
P="optionNV(fastmath off);optionNV(fastprecision off)"
nvidia-smi --query-gpu=name,driver_version --format=csv | tee $OUT/info-pragmas.txt
for be in glsl-compute glsl; do for prag in "" "optionNV(fastmath off)" "optionNV(fastprecision off)" "$P"; do
  f=$OUT/pragmas-$be-$(echo "$prag" | tr -c 'a-z' '_').txt
  RILL_GLSL_DIVSQRT=native RILL_GLSL_PRAGMAS="$prag" timeout 200 $B/rill-conformance --backend $be --accuracy strict > $f 2>&1
  echo "$be native [$prag]: $(grep -E '^glsl' $f | head -1) $(grep -oE 'FAIL [a-z_0-9]+' $f | tr '\n' ' ')" | tee -a $OUT/info-pragmas.txt
done; done
echo "| scene | backend | rule | frame ms (median of 20) | kernel ms |" | tee $OUT/table-pragmas.md
echo "| --- | --- | --- | --- | --- |" | tee -a $OUT/table-pragmas.md
row() {
  local scene=$1 args=$2 label=$3 be=$4; shift 4
  env RILL_X=1 "$@" timeout 120 $B/rill-trace render $scene $args --size 1920x1080 --backend $be \
    --bench-frames 20 --out /tmp/o.png --stats-json /tmp/s.json > /dev/null 2>&1 || { echo "| $scene | $be | $label | failed | |" | tee -a $OUT/table-pragmas.md; return; }
  python3 - /tmp/s.json "$(basename $scene .json)" "$be" "$label" <<'PY' | tee -a $OUT/table-pragmas.md
import json, sys
j = json.load(open(sys.argv[1])); b = j["bench_frames"]
k = b["median_split_ms"].get("kernel", -1)
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {b['median_ms']:.2f} | {k:.2f} |")
PY
}
for s in "builtin:cornell-path|--max-depth 8 --spp 1" "$here/../2026-12-07-path/thesis-c-area.json|--max-depth 8 --spp 1" "builtin:thesis-a|" "builtin:thesis-c|" "builtin:glass|"; do
  scene=${s%%|*}; args=${s#*|}
  row "$scene" "$args" strict opencl
  row "$scene" "$args" "driver / and sqrt, pragmas" glsl-compute RILL_GLSL_DIVSQRT=native "RILL_GLSL_PRAGMAS=$P"
  row "$scene" "$args" "driver / and sqrt" glsl-compute RILL_GLSL_DIVSQRT=native
  row "$scene" "$args" "strict, fused residual, pragmas" glsl-compute "RILL_GLSL_PRAGMAS=$P"
done
