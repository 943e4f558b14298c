# Issue 23, the third and fourth H200 runs: after the CPU backend's smaller ranges for small launches
# (third), and after workers post every tile in hand to their render thread at once (fourth):
# thesis C at 1080p, tiles of 128, 2-16 ranks with ranks x threads = 16, twice each, beside
# the single process. Set-up as in h200.sh.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
mkdir -p /tmp/mpi; for f in .mpi/*.deb; do dpkg -x $f /tmp/mpi; done
export RILL_CACHE_DIR=/tmp/rill-cache OPAL_PREFIX=/tmp/mpi/usr PATH=/tmp/mpi/usr/bin:$PATH
export LD_LIBRARY_PATH=$PWD/.devcarry/lib:/tmp/mpi/usr/lib/x86_64-linux-gnu:/tmp/mpi/usr/lib/x86_64-linux-gnu/openmpi/lib
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
B=$PWD/.devcarry/bin
S="builtin:thesis-c --size 1920x1080"
$B/rill-trace render $S --threads 16 --out /tmp/single.png --bench-frames 5 | grep "frames of"
for rep in 1 2; do
  for n in 2 4 8 16; do
    mpirun --oversubscribe --bind-to none -np $n $B/rill-trace render $S --threads $((16 / n)) --tile 128 \
      --out /tmp/d$n.png 2>&1 | tail -1
    cmp -s /tmp/single.png /tmp/d$n.png || echo "$n ranks: IMAGE DIFFERS"
  done
  for tile in 64 96; do
    mpirun --oversubscribe --bind-to none -np 8 $B/rill-trace render $S --threads 2 --tile $tile \
      --out /tmp/d.png 2>&1 | tail -1
  done
  $B/rill-trace render $S --threads 16 --out /tmp/single.png --bench-frames 5 | grep "frames of"
done
