#!/bin/bash
# Issue 19, part 4: native strict comparisons on NVIDIA (RILL_GLSL_COMPARE=auto), both stages.
for f in .gl/libegl1*.deb .gl/libglvnd0*.deb .gl/libopengl0*.deb .gl/libgl1*.deb .gl/libglx0*.deb .gl/libgles2*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/x /tmp/icd; for f in .gl/ocl-icd*.deb .gl/libtbb*.deb .gl/libtinyobj*.deb .gl/libembree*.deb; do dpkg -x $f /tmp/x; done
export LD_LIBRARY_PATH=/tmp/x/usr/lib/x86_64-linux-gnu
echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
B=.devcarry/bin
$B/rill-info | tee $OUT/info.txt
for be in glsl-compute glsl; do for acc in strict fast; do timeout 120 $B/rill-conformance --backend $be --accuracy $acc > $OUT/conf-$be-$acc.txt 2>&1; echo "conformance $be $acc rc=$?: $(grep -E 'pass,' $OUT/conf-$be-$acc.txt)"; grep FAIL $OUT/conf-$be-$acc.txt | head -3; done; done
timeout 150 $B/rill_backend_tests --gtest_filter='*/glsl_compute:*/glsl' > $OUT/backend-tests.txt 2>&1; echo "backend tests rc=$?"; tail -4 $OUT/backend-tests.txt
for sc in thesis-b glass cornell; do for st in megakernel multipass; do
  [ $sc = glass ] && [ $st = multipass ] && continue
  for be in cpu opencl glsl glsl-compute; do timeout 60 $B/rill-trace render builtin:$sc --backend $be --strategy $st --size 160x120 --pfm /tmp/$sc-$st-$be.pfm > /dev/null 2>>$OUT/render-err.txt || echo "render $sc $st $be failed"; done
  for be in opencl glsl glsl-compute; do cmp -s /tmp/$sc-$st-cpu.pfm /tmp/$sc-$st-$be.pfm && echo "same bits $sc $st $be" || echo "DIFFERENT $sc $st $be"; done
done; done
timeout 100 $B/rill-bench-mandelbrot --repeats 5 > $OUT/mandelbrot.txt 2>&1; tail -6 $OUT/mandelbrot.txt
timeout 330 $B/rill-bench-trace --sections throughput --size 1920x1080 --scenes builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,.devcarry/stanford-bunny.obj --backends opencl,glsl-compute,glsl --repeats 3 --md $OUT/trace.md > $OUT/trace.txt 2>&1; echo "trace rc=$?"; grep -E "^\|" $OUT/trace.txt
