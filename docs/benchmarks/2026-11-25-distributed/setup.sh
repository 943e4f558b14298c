# The H200 set-up the scripts here source: the GL packages from .gl/ unpacked, Debian 12's
# Open MPI unpacked from .mpi/ into /tmp/mpi and relocated with OPAL_PREFIX, NVIDIA's OpenCL
# ICD, the carried rill-trace (.devcarry/bin, in B) with its libraries, and thesis C at 1080p
# in S.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/mpi; for f in .mpi/*.deb; do dpkg -x $f /tmp/mpi; done
mkdir -p /tmp/icd; echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd; export OCL_ICD_VENDORS=/tmp/icd
export RILL_OPENCL_DEVICE=nvidia RILL_CACHE_DIR=/tmp/rill-cache
export OPAL_PREFIX=/tmp/mpi/usr PATH=/tmp/mpi/usr/bin:$PATH
export LD_LIBRARY_PATH=$PWD/.devcarry/lib:/tmp/mpi/usr/lib/x86_64-linux-gnu:/tmp/mpi/usr/lib/x86_64-linux-gnu/openmpi/lib
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
B=$PWD/.devcarry/bin
S="builtin:thesis-c --size 1920x1080"
