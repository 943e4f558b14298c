for f in .gl/libegl1*.deb .gl/libglvnd0*.deb .gl/libopengl0*.deb .gl/libgl1*.deb .gl/libglx0*.deb .gl/libgles2*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/x /tmp/icd; for f in .gl/ocl-icd*.deb .gl/libtbb*.deb .gl/libtinyobj*.deb; do dpkg -x $f /tmp/x; done
export LD_LIBRARY_PATH=/tmp/x/usr/lib/x86_64-linux-gnu
echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia
B=.devcarry/bin
S=docs/benchmarks/2026-11-24-modular-renderer
python3 $S/speed_kept.py $B/rill-trace-before $B/rill-trace --backends simd,cpu --workloads primary --size 1920x1080 --reps 15 --json $OUT/h200-simd-primary-after-fix.json 2>&1 | tail -7
