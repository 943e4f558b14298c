#!/bin/bash
# Issue 52 item 1: why OpenCL slows 3x when a GL context shares its process (and GL compute
# runs the ray tracer 2-3x slower than OpenCL). rill-bench-sm-probe (bench/gpu_sm_probe.cpp)
# runs one spinning kernel through OpenCL and GL compute, step by step, and prints each step's
# median time and how many multiprocessors (SMs) its work-groups ran on. Run from the
# repository root on the GPU machine (sources scripts/gpu-setup.sh; needs
# $B/rill-bench-sm-probe). Output: $OUT/probe.txt.
source scripts/gpu-setup.sh
P=$B/rill-bench-sm-probe
T=$OUT/probe.txt
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,compute_mode --format=csv | tee "$T"
for spin in 20000 200000; do
  echo "== spin $spin: OpenCL alone, then beside a GL context, GL compute, the context dropped" | tee -a "$T"
  timeout 60 "$P" --spin $spin cl cl glctx cl gl cl gldrop cl 2>&1 | tee -a "$T"
  echo "== spin $spin: GL compute first, then OpenCL beside it" | tee -a "$T"
  timeout 60 "$P" --spin $spin gl gl cl gl 2>&1 | tee -a "$T"
  echo "== spin $spin: two OpenCL contexts in one process" | tee -a "$T"
  timeout 60 "$P" --spin $spin cl cl2 cl 2>&1 | tee -a "$T"
done
echo "== OpenCL in one process while another process holds a GL context (and has launched on it)" | tee -a "$T"
timeout 60 "$P" gl sleep 12 > /tmp/holder.txt 2>&1 &
sleep 4
timeout 40 "$P" cl cl 2>&1 | tee -a "$T"
wait
sed 's/^/holder: /' /tmp/holder.txt | tee -a "$T"
