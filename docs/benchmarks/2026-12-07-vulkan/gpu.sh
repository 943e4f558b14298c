#!/bin/bash
# The GPU run of the vulkan backend (issue 54 items 2 and 4): the strict
# conformance suite on vulkan through NVIDIA's Vulkan driver, then frames of the ray tracer on
# opencl, glsl-compute and vulkan side by side. Run on the GPU machine from the repository
# root, set up by scripts/gpu-setup.sh: rill-trace and rill-conformance with their shared
# libraries in .devcarry/ (bin/, lib/), and there too the Vulkan loader libvulkan.so.1
# (Debian's libvulkan1: the machine has NVIDIA's driver and ICD file,
# /usr/share/vulkan/icd.d/nvidia_icd.json, but no loader); the GL and OpenCL loaders' Debian
# packages in .gl/ (NVIDIA's Vulkan ICD is libGLX_nvidia.so.0, which needs libglvnd).
# ROUNDS (default 2) and SCENES (default: thesis A, thesis C, glass, cornell-path) shorten it;
# PART=conformance runs the conformance part only, PART=frames the frames only.
# Output: $OUT/info.txt (the GPU, the backends' lines, the Vulkan devices, the conformance
# verdicts), $OUT/conformance-*.txt, $OUT/table.md.
source scripts/gpu-setup.sh
ls -l $B/../lib/libvulkan.so.1* /usr/share/vulkan/icd.d/ 2>&1 | tee $OUT/info.txt
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee -a $OUT/info.txt
# The backends' lines (strict / and sqrt, the fma probe's verdict, float controls, subgroups)
# and the Vulkan devices the loader sees.
$B/rill-trace info 2>&1 | sed -n '/^backends:/,/^built-in/p' | grep -vE "^built-in" | tee -a $OUT/info.txt
# Bitwise: the strict conformance suite on vulkan with the corrections' residual as probed
# (auto), split (Dekker) and fused (one fma); then the denormal paths (VulkanBackend.cpp,
# choose_denormals: RILL_VULKAN_DENORMALS=auto as probed, flush, emulate = flushed in the
# kernels); glsl-compute's auto for comparison. Each file's first line says "flushes
# denormals" where the suite's own probe saw the backend flush.
if [ "${PART:-all}" != frames ]; then
for run in "vulkan fma-auto RILL_GLSL_FMA=auto" "vulkan fma-split RILL_GLSL_FMA=split" \
           "vulkan fma-fused RILL_GLSL_FMA=fused" "vulkan denormals-flush RILL_VULKAN_DENORMALS=flush" \
           "vulkan denormals-emulate RILL_VULKAN_DENORMALS=emulate" \
           "glsl-compute fma-auto RILL_GLSL_FMA=auto"; do
  read -r be label setting <<< "$run"
  env $setting timeout 300 $B/rill-conformance --backend $be --accuracy strict > $OUT/conformance-$be-$label.txt 2>&1
  rc=$?
  echo "conformance $be strict $setting: rc=$rc, $(head -1 $OUT/conformance-$be-$label.txt | cut -c1-120), $(tail -1 $OUT/conformance-$be-$label.txt)" | tee -a $OUT/info.txt
  env $setting $B/rill-trace info 2>&1 | sed -n "s/.* vulkan: .*; \(denormals: .*\); lane groups.*/  $setting: \1/p" | tee -a $OUT/info.txt
done
fi
[ "${PART:-all}" = conformance ] && exit 0
echo "| scene | backend | accuracy | frame ms (median of 20) | kernel ms | launch ms | read-back ms | compile ms |" | tee $OUT/table.md
echo "| --- | --- | --- | --- | --- | --- | --- | --- |" | tee -a $OUT/table.md
row() { # scene extra-args label backend env...
  local scene=$1 args=$2 label=$3 be=$4; shift 4
  local tag=$be; [ $# -gt 0 ] && tag="$be $*"
  env RILL_X=1 "$@" timeout 150 $B/rill-trace render $scene $args --size 1920x1080 --backend $be \
    --bench-frames 20 --out /tmp/o-$be.png --stats-json /tmp/s.json > /tmp/row.log 2>&1 || {
    echo "| $scene | $tag | $label | failed: $(tail -1 /tmp/row.log | tr '|' '/') | | | | |" | tee -a $OUT/table.md; return; }
  python3 - /tmp/s.json "$scene" "$tag" "$label" <<'PY' | tee -a $OUT/table.md
import json, sys
j = json.load(open(sys.argv[1])); b = j["bench_frames"]; m = b["median_split_ms"]
first = j["time_ms"]["compile"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {b['median_ms']:.2f} | {m.get('kernel', -1):.2f} "
      f"| {m.get('launch', -1):.2f} | {m.get('read_back', -1):.2f} | {first:.1f} |")
PY
}
# Twice over: the first round fills the kernel caches (the compile column then shows the disk
# cache's effect), the second is the one to quote.
default_scenes=("builtin:thesis-a|" "builtin:thesis-c|" "builtin:glass|" "builtin:cornell-path|--max-depth 8 --spp 1")
if [ -n "${SCENES:-}" ]; then IFS=";" read -r -a scenes <<< "$SCENES"; else scenes=("${default_scenes[@]}"); fi
for k in $(seq 1 "${ROUNDS:-2}"); do
for s in "${scenes[@]}"; do
  scene=${s%%|*}; args=${s#*|}
  for be in opencl glsl-compute vulkan; do
    row "$scene" "$args" strict $be
  done
  # Same bits on all three under strict: compare the last images.
  if cmp -s /tmp/o-opencl.png /tmp/o-vulkan.png && cmp -s /tmp/o-opencl.png /tmp/o-glsl-compute.png; then
    echo "$scene: images identical on opencl, glsl-compute, vulkan" | tee -a $OUT/info.txt
  else
    echo "$scene: IMAGES DIFFER" | tee -a $OUT/info.txt; cp /tmp/o-*.png $OUT/ 2>/dev/null
  fi
  cp /tmp/o-opencl.png /tmp/strict-opencl.png
  for be in opencl vulkan; do
    row "$scene" "$args --accuracy fast" fast $be
  done
  # vulkan's memory (RILL_VULKAN_MEMORY: auto above; mapped = every buffer in BAR memory read
  # through the mapping, as before the fix; staged = uploads through staging copies too) and
  # strict kernels that flush denormals themselves (RILL_VULKAN_DENORMALS=emulate), and the
  # launch parameters and strict constants in a uniform buffer (RILL_VULKAN_PARAMS=uniform:
  # GL's uniforms are in NVIDIA's constant bank; vulkan reads them from a storage buffer).
  for v in RILL_VULKAN_MEMORY=mapped RILL_VULKAN_MEMORY=staged RILL_VULKAN_DENORMALS=emulate \
           RILL_VULKAN_PARAMS=uniform; do
    row "$scene" "$args" strict vulkan $v
    cmp -s /tmp/strict-opencl.png /tmp/o-vulkan.png ||
      { echo "$scene: vulkan $v: IMAGE DIFFERS from opencl's" | tee -a $OUT/info.txt; cp /tmp/o-vulkan.png "$OUT/vulkan-${v#*=}.png"; }
  done
done; done
