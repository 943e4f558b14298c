# Sourced by the GPU machine's scripts (scripts/gpu-run, docs/benchmarks/*/gpu.sh): makes NVIDIA's
# OpenGL (EGL), OpenCL and Vulkan drivers reachable from Rill's binaries carried in .devcarry/.
# The GPU machine has NVIDIA's drivers but no package registry, so the loaders come as Debian
# packages in .gl/ (libglvnd's EGL/GL, ocl-icd) and .devcarry/lib/ (the Vulkan loader and the
# binaries' other shared libraries); large files travel xz-compressed (*.xz, unpacked here).
# Run from the repository root. Sets B (the binaries' folder) and the drivers' variables.
for f in .gl/libegl1*.deb .gl/libglvnd0*.deb .gl/libopengl0*.deb .gl/libgl1*.deb .gl/libglx0*.deb .gl/libgles2*.deb; do dpkg -x "$f" /; done
ldconfig
mkdir -p /tmp/x /tmp/icd /tmp/rill-gpu/bin /tmp/rill-gpu/lib
for f in .gl/ocl-icd*.deb .gl/libtbb*.deb .gl/libtinyobj*.deb; do [ -e "$f" ] && dpkg -x "$f" /tmp/x; done
if [ -d .devcarry ]; then
  cp -a .devcarry/bin/. /tmp/rill-gpu/bin/
  cp -a .devcarry/lib/. /tmp/rill-gpu/lib/
  for f in /tmp/rill-gpu/bin/*.xz /tmp/rill-gpu/lib/*.xz; do [ -e "$f" ] && xz -d -f "$f"; done
  chmod +x /tmp/rill-gpu/bin/*
fi
export LD_LIBRARY_PATH=/tmp/x/usr/lib/x86_64-linux-gnu:/tmp/rill-gpu/lib
echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd
export OCL_ICD_VENDORS=/tmp/icd
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
# Older Vulkan loaders read VK_ICD_FILENAMES, newer VK_DRIVER_FILES.
export VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/nvidia_icd.json VK_DRIVER_FILES=/usr/share/vulkan/icd.d/nvidia_icd.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia RILL_VULKAN_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
# RILL_GPU_BIN: binaries carried elsewhere (their libraries on LD_LIBRARY_PATH).
B=${RILL_GPU_BIN:-/tmp/rill-gpu/bin}

# One row of a frames table: `rill-trace render SCENE ARGS --size 1920x1080 --backend BACKEND
# --bench-frames 20` under the environment ENV..., appended to TABLE as "| scene | backend |
# label | frame ms | kernel ms | read-back ms |" (medians); the image is left at
# /tmp/o-BACKEND-LABEL.png (characters other than a-z0-9- as _) for comparisons.
frame_row() { # table scene args label backend env...
  local table=$1 scene=$2 args=$3 label=$4 be=$5; shift 5
  local png=/tmp/o-$(printf %s "$be-$label" | tr -c 'a-z0-9-' '_').png
  # shellcheck disable=SC2086 # args: several options
  env RILL_X=1 "$@" timeout 120 "$B/rill-trace" render "$scene" $args --size 1920x1080 --backend "$be" \
    --bench-frames 20 --out "$png" --stats-json /tmp/s.json > /tmp/row.log 2>&1 || {
    echo "| $scene | $be | $label | failed: $(tail -1 /tmp/row.log | tr '|' '/') | | |" | tee -a "$table"; return; }
  python3 - /tmp/s.json "$(basename "$scene" .json)" "$be" "$label" <<'PY' | tee -a "$table"
import json, sys
b = json.load(open(sys.argv[1]))["bench_frames"]; s = b["median_split_ms"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {b['median_ms']:.2f} | {s.get('kernel', -1):.2f} | {s.get('read_back', -1):.2f} |")
PY
}
