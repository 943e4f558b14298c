#!/bin/bash
# The H200 run of bench.sh (2026-12-07): rill-trace and its shared libraries carried in
# .devcarry/ (bin/, lib/), the GL and OpenCL loaders in .gl/ (Debian packages), as
# docs/benchmarks/2026-11-25-gpu-frame/setup.sh does.
for f in .gl/libegl1*.deb .gl/libglvnd0*.deb .gl/libopengl0*.deb .gl/libgl1*.deb .gl/libglx0*.deb .gl/libgles2*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/x /tmp/icd; for f in .gl/ocl-icd*.deb; do dpkg -x $f /tmp/x; done
export LD_LIBRARY_PATH=/tmp/x/usr/lib/x86_64-linux-gnu:$PWD/.devcarry/lib
echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
B=.devcarry/bin
$B/rill-trace info 2>&1 | head -20 | tee $OUT/info.txt
nvidia-smi --query-gpu=name,clocks.sm,clocks.max.sm --format=csv | tee -a $OUT/info.txt
echo "| scene | backend | accuracy | frame ms | Mpaths/s | Mrays/s |" | tee $OUT/table.md
echo "| --- | --- | --- | --- | --- | --- |" | tee -a $OUT/table.md
bash docs/benchmarks/2026-12-07-path/bench.sh $B/rill-trace ${BACKENDS:-opencl,glsl-compute,cpu,simd,glsl} ${FRAMES:-10} /tmp/bench-out | tee -a $OUT/table.md
