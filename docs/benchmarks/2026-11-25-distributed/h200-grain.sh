# Issue 23, the third and fourth H200 runs: after the CPU backend's smaller ranges for small launches
# (third), and after workers post every tile in hand to their render thread at once (fourth):
# thesis C at 1080p, tiles of 128, 2-16 ranks with ranks x threads = 16, twice each, beside
# the single process. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-distributed/setup.sh
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
