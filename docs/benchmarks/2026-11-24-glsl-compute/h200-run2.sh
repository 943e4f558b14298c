#!/bin/bash
# Issue 19, part 2: tracer throughput and the compute work-group size.
for f in .gl/libegl1*.deb .gl/libglvnd0*.deb .gl/libopengl0*.deb .gl/libgl1*.deb .gl/libglx0*.deb .gl/libgles2*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/x /tmp/icd; for f in .gl/ocl-icd*.deb .gl/libtbb*.deb .gl/libtinyobj*.deb .gl/libembree*.deb; do dpkg -x $f /tmp/x; done
export LD_LIBRARY_PATH=/tmp/x/usr/lib/x86_64-linux-gnu
echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
B=.devcarry/bin
timeout 330 $B/rill-bench-trace --sections throughput --size 1920x1080 --scenes builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,.devcarry/stanford-bunny.obj --backends opencl,glsl-compute,glsl --repeats 3 --md $OUT/trace.md > $OUT/trace.txt 2>&1; echo "trace rc=$?"; cat $OUT/trace.txt | tail -40
for ls in 32 128 256; do echo "local size $ls"; RILL_GLSL_LOCAL_SIZE=$ls timeout 60 $B/rill-bench-mandelbrot --repeats 5 2>&1 | grep -E "opencl|glsl-compute"; done
for ls in 128 256; do echo "local size $ls"; RILL_GLSL_LOCAL_SIZE=$ls timeout 90 $B/rill-bench-trace --sections throughput --size 1920x1080 --scenes builtin:thesis-c --backends opencl,glsl-compute --repeats 3 2>&1 | tail -8; done
