#!/bin/bash
# Issue 52 item 1: why OpenCL slows 3-5x when a GL backend shares its process. Run on the GPU
# machine from the repository root (scripts/gpu-setup.sh sets the drivers up). Two parts:
#  1. rill-bench-trace --sections shared: each GPU backend alone in a child process, then
#     together in one process (one after the other, then interleaved launch by launch), then
#     alone again while this process holds them all open: wall and device (kernel) times.
#  2. rows of the throughput section, one process each, with other backends beside OpenCL and
#     the NVIDIA driver's documented switches, while nvidia-smi samples clocks and use.
# Output: $OUT/shared.md, $OUT/rows/*.txt, $OUT/summary.txt, $OUT/smi.csv.
source scripts/gpu-setup.sh
mkdir -p $OUT/rows
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,compute_mode --format=csv | tee $OUT/summary.txt
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,utilization.gpu,pstate,power.draw --format=csv -lms 250 > $OUT/smi.csv &
smi=$!
mark() { echo "mark $(date +%T.%N) $*" >> $OUT/smi.csv; }
mark shared-section
timeout 200 $B/rill-bench-trace --sections shared --backends ${SHARED_BACKENDS:-opencl,glsl-compute,vulkan} \
  --size 1920x1080 --scenes builtin:thesis-c,builtin:thesis-a --repeats ${REPEATS:-9} --md $OUT/shared.md > $OUT/shared.txt 2>&1
echo "shared section rc=$?" | tee -a $OUT/summary.txt; cat $OUT/shared.md | tee -a $OUT/summary.txt
[ -n "${SHARED_ONLY:-}" ] && { kill $smi; exit 0; }
sc=builtin:thesis-c,builtin:thesis-a
row() { # name backends env...
  local name=$1 bes=$2; shift 2
  mark $name
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
kill $smi
