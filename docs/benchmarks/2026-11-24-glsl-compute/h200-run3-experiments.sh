#!/bin/bash
# Issue 19, part 3: where glsl-compute's time goes (experiment binaries in .devcarry/exp:
# RILL_TMP_NATIVE_COMPARE=1 compares floats natively, RILL_TMP_NOWAIT=1 skips reading counts).
for f in .gl/libegl1*.deb .gl/libglvnd0*.deb .gl/libopengl0*.deb .gl/libgl1*.deb .gl/libglx0*.deb .gl/libgles2*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/x /tmp/icd; for f in .gl/ocl-icd*.deb .gl/libtbb*.deb .gl/libtinyobj*.deb .gl/libembree*.deb; do dpkg -x $f /tmp/x; done
export LD_LIBRARY_PATH=/tmp/x/usr/lib/x86_64-linux-gnu
echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
E=.devcarry/exp
which nsys ncu nvidia-smi; ls /usr/local/cuda*/bin 2>/dev/null | head
RILL_TMP_NATIVE_COMPARE=1 timeout 120 $E/rill-conformance --backend glsl-compute --accuracy strict > $OUT/conf-native.txt 2>&1; echo "conformance native compare rc=$?"; grep -E "FAIL|pass," $OUT/conf-native.txt | head -8
for v in base native nowait; do
  env_=""; [ $v = native ] && export RILL_TMP_NATIVE_COMPARE=1; [ $v = nowait ] && { unset RILL_TMP_NATIVE_COMPARE; export RILL_TMP_NOWAIT=1; }
  echo "== $v"; timeout 60 $E/rill-bench-mandelbrot --repeats 5 2>&1 | grep -E "^  (opencl|glsl-compute) "
  timeout 150 $E/rill-bench-trace --sections throughput --size 1920x1080 --scenes builtin:thesis-b,builtin:thesis-c --backends opencl,glsl-compute --repeats 3 2>&1 | grep -E "\| (opencl|glsl-compute) \|"
done
