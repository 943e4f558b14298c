#!/bin/bash
# Issue 20: glsl-compute one scene per process, and the scene-order effect in one process.
source "$(dirname "$0")/setup.sh"
BUNNY=.devcarry/stanford-bunny.obj
T="$B/rill-bench-trace --size 1920x1080 --repeats 5 --sections throughput"
echo "== glsl-compute, one scene per process"
for round in 1 2; do for sc in builtin:thesis-a builtin:thesis-b builtin:thesis-c $BUNNY; do
  timeout 100 $T --scenes $sc --backends glsl-compute 2>&1 | grep -E "\| glsl-compute \|"; done; done
echo "== scene order in one process"
for order in builtin:thesis-a,builtin:thesis-c builtin:thesis-c,builtin:thesis-a builtin:thesis-b,builtin:thesis-c; do
  for be in glsl-compute opencl; do echo "-- $order $be"; timeout 100 $T --scenes $order --backends $be 2>&1 | grep -E "\| $be \|"; done; done
