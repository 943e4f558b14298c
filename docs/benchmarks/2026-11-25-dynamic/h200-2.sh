# The second H200 run (issue 22): the builder with parallel partitions, frame time with the
# BVH rebuilt and refitted, and the dynamic-scene tests (deforming meshes included) on the
# GPU backends. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
$B/rill_raytracer_tests --gtest_filter='*DynamicRender*:DynamicFeatures*:Animation*:Bvh*' > $OUT/tests.txt 2>&1; tail -4 $OUT/tests.txt
$B/rill-bench-dynamic --sections build --repeats 15 > $OUT/build.txt 2>&1; cat $OUT/build.txt
for bvh in rebuild refit; do
  $B/rill-bench-dynamic --sections frames --backends simd,opencl,glsl-compute --size 1920x1080 --frames 15 --bvh $bvh > $OUT/frames-$bvh.txt 2>&1; cat $OUT/frames-$bvh.txt
done
