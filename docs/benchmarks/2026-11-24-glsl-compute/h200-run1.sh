#!/bin/bash
# Issue 19 on the GPU machine: glsl-compute beside glsl and NVIDIA OpenCL.
for f in .gl/libegl1*.deb .gl/libglvnd0*.deb .gl/libopengl0*.deb .gl/libgl1*.deb .gl/libglx0*.deb .gl/libgles2*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/x /tmp/icd; for f in .gl/ocl-icd*.deb .gl/libtbb*.deb .gl/libtinyobj*.deb .gl/libembree*.deb; do dpkg -x $f /tmp/x; done
export LD_LIBRARY_PATH=/tmp/x/usr/lib/x86_64-linux-gnu
echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
B=.devcarry/bin
$B/rill-info | tee $OUT/info.txt
timeout 120 $B/rill_backend_tests --gtest_filter='*/glsl_compute' > $OUT/backend-tests.txt 2>&1; echo "backend tests rc=$?"; tail -8 $OUT/backend-tests.txt
for acc in strict fast; do timeout 120 $B/rill-conformance --backend glsl-compute --accuracy $acc > $OUT/conf-$acc.txt 2>&1; echo "conformance glsl-compute $acc rc=$?"; tail -3 $OUT/conf-$acc.txt; done
# Same bits: every backend's image of thesis-b and glass, both strategies, against cpu.
for sc in thesis-b glass cornell; do for st in megakernel multipass; do
  [ $sc = glass ] && [ $st = multipass ] && continue
  for be in cpu opencl glsl glsl-compute; do timeout 60 $B/rill-trace render builtin:$sc --backend $be --strategy $st --size 160x120 --pfm /tmp/$sc-$st-$be.pfm > /dev/null 2>>$OUT/render-err.txt || echo "render $sc $st $be failed"; done
  for be in opencl glsl glsl-compute; do cmp -s /tmp/$sc-$st-cpu.pfm /tmp/$sc-$st-$be.pfm && echo "same bits $sc $st $be" || echo "DIFFERENT $sc $st $be"; done
done; done
timeout 200 $B/rill-bench-mandelbrot --repeats 5 > $OUT/mandelbrot.txt 2>&1; tail -12 $OUT/mandelbrot.txt
timeout 300 $B/rill-bench-trace --sections throughput --size 1920x1080 --scenes builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,.devcarry/stanford-bunny.obj --backends opencl,glsl-compute,glsl --repeats 3 --md $OUT/trace.md > $OUT/trace.txt 2>&1; echo "trace rc=$?"; cat $OUT/trace.txt | tail -30
