# The second H200 run (issue 22): the builder with parallel partitions, frame time with the
# BVH rebuilt and refitted, and the dynamic-scene tests (deforming meshes included) on the
# GPU backends. Set-up as in h200.sh.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/icd; echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export LD_LIBRARY_PATH=$PWD/.devcarry/lib
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
B=.devcarry/bin
$B/rill_raytracer_tests --gtest_filter='*DynamicRender*:DynamicFeatures*:Animation*:Bvh*' > $OUT/tests.txt 2>&1; tail -4 $OUT/tests.txt
$B/rill-bench-dynamic --sections build --repeats 15 > $OUT/build.txt 2>&1; cat $OUT/build.txt
for bvh in rebuild refit; do
  $B/rill-bench-dynamic --sections frames --backends simd,opencl,glsl-compute --size 1920x1080 --frames 15 --bvh $bvh > $OUT/frames-$bvh.txt 2>&1; cat $OUT/frames-$bvh.txt
done
