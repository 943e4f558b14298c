#!/bin/bash
# The GPU check of glsl-compute's lane groups as GL_KHR_shader_subgroup operations (issue 51
# item 1; backends/glsl/Subgroups.h): this machine's llvmpipe (Mesa 22.3) has no such
# extension, so the subgroup path runs only on a GPU. Run on the GPU machine from the
# repository root, set up by scripts/gpu-setup.sh, with rill-info, rill-trace,
# rill-conformance, rill_backend_tests and rill_raytracer_tests in .devcarry/bin.
# Output in $OUT: info.txt (the verdicts, one line each), and a log per step. What to look for:
#   - info.txt's glsl-compute line says "lane groups: subgroups of 32" (NVIDIA), and
#     "one element (RILL_GLSL_SUBGROUPS=off)" under the switch;
#   - every "rc=" is 0: GroupTest with subgroups (checked against the host's recomputation
#     from the groups the elements report) and with a group of one, the conformance suite's
#     strict and fast runs (control.group_independent among them), and the packet traversal
#     against its brute-force closest-hit oracle on glsl_compute;
#   - "same bits" for rill-trace --packets on, glsl-compute (subgroups, and a group of one)
#     against cpu, and the subgroups' kernel using subgroupMin (the shared walk);
#   - table.md: frames with packets on and off, subgroups on and off (information, not a goal).
source scripts/gpu-setup.sh
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $OUT/info.txt
$B/rill-info 2>&1 | grep -E "^glsl-compute" | tee -a $OUT/info.txt
RILL_GLSL_SUBGROUPS=off $B/rill-info 2>&1 | grep -E "^glsl-compute" | sed 's/^/off: /' | tee -a $OUT/info.txt
for s in on off; do
  RILL_GLSL_SUBGROUPS=$s timeout 300 $B/rill_backend_tests --gtest_filter='Backends/GroupTest.*/glsl_compute' > $OUT/group-$s.txt 2>&1
  echo "GroupTest glsl_compute RILL_GLSL_SUBGROUPS=$s: rc=$? $(grep -E '^\[  (PASSED|FAILED)' $OUT/group-$s.txt | tr '\n' ' ')" | tee -a $OUT/info.txt
  for acc in strict fast; do
    RILL_GLSL_SUBGROUPS=$s timeout 300 $B/rill-conformance --backend glsl-compute --accuracy $acc > $OUT/conformance-$s-$acc.txt 2>&1
    echo "conformance glsl-compute $acc RILL_GLSL_SUBGROUPS=$s: rc=$? $(tail -1 $OUT/conformance-$s-$acc.txt)" | tee -a $OUT/info.txt
  done
done
timeout 600 $B/rill_raytracer_tests --gtest_filter='Backends/Packets.*/glsl_compute' > $OUT/packets-test.txt 2>&1
echo "Packets glsl_compute: rc=$? $(grep -E '^\[  (PASSED|FAILED)' $OUT/packets-test.txt | tr '\n' ' ')" | tee -a $OUT/info.txt
# The ray tracer's images with --packets on: the same PNG bytes on glsl-compute as on cpu.
for scene in builtin:thesis-a builtin:thesis-c builtin:cornell; do
  n=$(basename "$scene" | tr ':' '_')
  timeout 300 $B/rill-trace render $scene --backend cpu --packets on --size 640x480 --out /tmp/p-$n-cpu.png > $OUT/render-$n.txt 2>&1
  for s in on off; do
    RILL_GLSL_SUBGROUPS=$s timeout 300 $B/rill-trace render $scene --backend glsl-compute --packets on --size 640x480 --out /tmp/p-$n-$s.png --source /tmp/p-$n-$s.glsl >> $OUT/render-$n.txt 2>&1
    if cmp -s /tmp/p-$n-cpu.png /tmp/p-$n-$s.png; then v="same bits"; else v="DIFFERENT (see render-$n.txt)"; fi
    # With subgroups the kernel's walk uses them (subgroupMin: expect > 0 for on, 0 for off).
    echo "rill-trace $scene --packets on, glsl-compute RILL_GLSL_SUBGROUPS=$s vs cpu: $v; subgroupMin in the kernel: $(grep -c 'subgroupMin(' /tmp/p-$n-$s.glsl)" | tee -a $OUT/info.txt
  done
done
# Frames, side by side in one run (frame_row from gpu-setup.sh: medians of 20 frames at 1080p).
echo "| scene | backend | label | frame ms | kernel ms | read-back ms |" | tee $OUT/table.md
echo "| --- | --- | --- | --- | --- | --- |" | tee -a $OUT/table.md
for scene in builtin:thesis-a builtin:thesis-c; do
  for p in off on; do
    for s in on off; do
      frame_row $OUT/table.md $scene "--packets $p" "packets-$p-subgroups-$s" glsl-compute RILL_GLSL_SUBGROUPS=$s > /dev/null
    done
  done
done
cat $OUT/table.md
