#!/bin/bash
# The H200 run of bench.sh (2026-12-07): rill-trace and its shared libraries carried in
# .devcarry/ (bin/, lib/), the GL and OpenCL loaders in .gl/ (Debian packages), as
# docs/benchmarks/2026-11-25-gpu-frame/setup.sh does.
source scripts/gpu-setup.sh  # the drivers, the carried binaries: B
$B/rill-trace info 2>&1 | head -20 | tee $OUT/info.txt
nvidia-smi --query-gpu=name,clocks.sm,clocks.max.sm --format=csv | tee -a $OUT/info.txt
echo "| scene | backend | accuracy | frame ms | Mpaths/s | Mrays/s |" | tee $OUT/table.md
echo "| --- | --- | --- | --- | --- | --- |" | tee -a $OUT/table.md
bash docs/benchmarks/2026-12-07-path/bench.sh $B/rill-trace ${BACKENDS:-opencl,glsl-compute,cpu,simd,glsl} ${FRAMES:-10} /tmp/bench-out | tee -a $OUT/table.md
