# Dynamic scenes on the H200 machine (issue 22): the bit-identity tests on the GPU backends,
# BVH rebuild and refit against Embree on its 16 cores, frame time with moving balls per
# backend at 1080p, and builtin:bounce's 97 frames per backend. Binaries and libraries are
# carried in .devcarry/ (bin/, lib/), the GL packages in .gl/.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
$B/rill-trace info 2>&1 | head -12 | tee $OUT/info.txt
$B/rill_raytracer_tests --gtest_filter='*DynamicRender*:DynamicFeatures*' > $OUT/tests.txt 2>&1; tail -4 $OUT/tests.txt
$B/rill-bench-dynamic --sections build --repeats 15 > $OUT/build.txt 2>&1; cat $OUT/build.txt
$B/rill-bench-dynamic --sections frames --backends cpu,simd,opencl,glsl-compute --size 1920x1080 --frames 15 > $OUT/frames.txt 2>&1; cat $OUT/frames.txt
for be in cpu opencl glsl-compute; do
  $B/rill-trace render builtin:bounce --frames 0:96 --size 1920x1080 --backend $be --out /tmp/b-$be-%03d.png --stats-json $OUT/bounce-$be.json 2>&1 | tail -2
done
cmp /tmp/b-cpu-050.png /tmp/b-opencl-050.png && cmp /tmp/b-cpu-050.png /tmp/b-glsl-compute-050.png && echo "frame 50: cpu, opencl and glsl-compute PNGs identical"
