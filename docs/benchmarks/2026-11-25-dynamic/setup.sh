# The H200 set-up both scripts here source: the GL packages from .gl/ unpacked, NVIDIA's
# OpenCL ICD and EGL vendor files, and the carried binaries (.devcarry/bin) and libraries
# (.devcarry/lib) in B and LD_LIBRARY_PATH.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/icd; echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export LD_LIBRARY_PATH=$PWD/.devcarry/lib
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export RILL_GL=egl RILL_OPENCL_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
B=.devcarry/bin
