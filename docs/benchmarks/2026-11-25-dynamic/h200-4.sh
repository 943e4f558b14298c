# The fourth H200 run (issue 22): the builder after this session's work (no shared node
# counter, SSE bins, 32-byte triangles, memory kept between builds), thread by thread against
# Embree, twice; and frame time with moving balls on NVIDIA OpenCL. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
for round in 1 2; do for t in 1 2 4 8 16; do
  echo "round $round threads $t"; $B/rill-bench-dynamic --sections build --repeats 15 --threads $t 2>&1 | tail -2
done; done | tee $OUT/build.txt
for bvh in rebuild refit; do
  $B/rill-bench-dynamic --sections frames --backends opencl --size 1920x1080 --frames 15 --bvh $bvh > $OUT/frames-$bvh.txt 2>&1; tail -6 $OUT/frames-$bvh.txt
done
