#!/bin/bash
# Issue 20: glsl-compute runs that are 5x slower: the GPU's clocks and power state alongside.
source "$(dirname "$0")/setup.sh"
T="$B/rill-bench-trace --size 1920x1080 --repeats 5 --sections throughput --scenes builtin:thesis-c"
for i in 1 2 3 4; do for be in glsl-compute opencl; do
  nvidia-smi --query-gpu=clocks.sm,clocks.mem,pstate,utilization.gpu --format=csv,noheader -lms 100 > /tmp/smi.txt 2>&1 & P=$!
  r=$(timeout 100 $T --backends $be 2>&1 | grep -E "\| $be \|" | cut -d'|' -f7-10)
  kill $P; echo "$i $be: $r; SM clocks seen (MHz, count): $(cut -d, -f1 /tmp/smi.txt | sort | uniq -c | sort -rn | head -4 | tr -s ' ' | tr '\n' ';') pstates: $(cut -d, -f3 /tmp/smi.txt | sort | uniq -c | tr -s ' ' | tr '\n' ';')"
done; done
