#!/bin/bash
# Issue 52 item 1: why OpenCL slows 3-5x when a GL backend shares its process. Each row is one
# rill-bench-trace process, throughput section (primary and full-shading rays, strict), 1920x1080,
# on thesis C and the bunny-free built-ins; the backends listed run in that order in the one
# process. What differs between rows: which other backends the process also runs, their order,
# and the NVIDIA driver's documented switches. Output: $OUT/rows/*.txt, $OUT/summary.txt.
source scripts/gpu-setup.sh
mkdir -p $OUT/rows
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,compute_mode --format=csv | tee $OUT/summary.txt
which nsys ncu 2>&1 | tee -a $OUT/summary.txt
sc=builtin:thesis-c,builtin:thesis-a
row() { # name backends env...
  local name=$1 bes=$2; shift 2
  env "$@" timeout 120 $B/rill-bench-trace --sections throughput --backends $bes --size 1920x1080 \
    --scenes $sc --repeats 5 > $OUT/rows/$name.txt 2>&1
  echo "== $name ($bes; $*) rc=$?" | tee -a $OUT/summary.txt
  grep -E "^\| thesis" $OUT/rows/$name.txt | awk -F'|' '{print $2,$7,"primary",$9,"full",$12}' | tee -a $OUT/summary.txt
}
for k in 1 2; do
row opencl-alone$k opencl X=1
row opencl-glslc$k opencl,glsl-compute X=1
done
row opencl-cpu cpu,opencl X=1
row glslc-opencl glsl-compute,opencl X=1
row opencl-glsl opencl,glsl X=1
row opencl-vulkan opencl,vulkan X=1
row glslc-alone glsl-compute X=1
row opencl-glslc-nothreaded opencl,glsl-compute __GL_THREADED_OPTIMIZATIONS=0
row opencl-glslc-yield opencl,glsl-compute __GL_YIELD=USLEEP
row opencl-glslc-nosync opencl,glsl-compute __GL_SYNC_TO_VBLANK=0
row opencl-glslc-lazy opencl,glsl-compute CUDA_MODULE_LOADING=LAZY
