# The third H200 run (issue 22): the builder without its shared node counter (each subtree
# owns a region of the node array), thread by thread against Embree; frame time with moving
# balls (only the moving triangles' span uploaded now); and the dynamic-scene and
# partial-upload tests on NVIDIA OpenCL and GL. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
$B/rill_raytracer_tests --gtest_filter='*DynamicRender*:DynamicFeatures*:Animation*:Bvh*' > $OUT/tests.txt 2>&1; tail -3 $OUT/tests.txt
$B/rill_backend_tests --gtest_filter='*ArrayPartialUpload*:*ArrayResize*' > $OUT/backend-tests.txt 2>&1; tail -3 $OUT/backend-tests.txt
for t in 1 2 4 8 16; do
  echo "threads $t"; $B/rill-bench-dynamic --sections build --repeats 15 --threads $t 2>&1 | tail -2
done | tee $OUT/build.txt
for bvh in rebuild refit; do
  $B/rill-bench-dynamic --sections frames --backends opencl --size 1920x1080 --frames 15 --bvh $bvh > $OUT/frames-$bvh.txt 2>&1; tail -8 $OUT/frames-$bvh.txt
done
