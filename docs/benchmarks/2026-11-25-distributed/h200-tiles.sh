# Issue 23, the second H200 run: tile sizes 64, 96 and 128 at 4 and 8 ranks (ranks x threads
# = 16), beside the single process, each twice. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-distributed/setup.sh
$B/rill-trace render $S --threads 16 --out /tmp/single.png --bench-frames 5 | grep "frames of"
for rep in 1 2; do
  for n in 4 8; do
    for tile in 64 96 128; do
      mpirun --oversubscribe --bind-to none -np $n $B/rill-trace render $S --threads $((16 / n)) --tile $tile \
        --out /tmp/d.png 2>&1 | tail -1
    done
  done
  $B/rill-trace render $S --threads 16 --out /tmp/single.png | tail -1
done
