# Issue 23, the fifth and sixth H200 runs: the tail of small tiles (--tail-tile) and render loops that wake
# when a tile is done, against the fourth run; and the data for the model of larger farms:
# every run's --stats-json (per_tile, gather) goes to $OUT. Thesis C at 1080p on `cpu`,
# ranks x threads = 16, three rounds beside the single process; then 24 frames of
# builtin:bounce at 1080p, and a GPU rank beside CPU ranks. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-distributed/setup.sh
RESULTS=${OUT:-/tmp/out}; OUT=/tmp/stats; mkdir -p $OUT $RESULTS
run() {  # run NAME RANKS THREADS OPTIONS...
  local name=$1 n=$2 t=$3; shift 3
  mpirun --oversubscribe --bind-to none -np $n $B/rill-trace render $S --threads $t \
    --out /tmp/$name.png --stats-json $OUT/$name.json "$@" 2>&1 | tail -1 | sed "s/^/$name: /"
  cmp -s /tmp/single.png /tmp/$name.png || echo "$name: IMAGE DIFFERS"
}
$B/rill-trace render $S --threads 16 --out /tmp/single.png --stats-json $OUT/single.json | tail -1
for rep in 1 2 3; do
  $B/rill-trace render $S --threads 16 --out /tmp/s.png --bench-frames 5 | grep "frames of" | sed "s/^/single-$rep: /"
  run r$rep-8x2-t128-tail0 8 2 --tile 128 --tail-tile 0
  run r$rep-8x2-t128 8 2 --tile 128
  run r$rep-8x2-t128-tail32 8 2 --tile 128 --tail-tile 32
  run r$rep-8x2-t64-tail0 8 2 --tile 64 --tail-tile 0
  run r$rep-8x2-t64 8 2 --tile 64
  run r$rep-4x4-t128 4 4 --tile 128
  run r$rep-2x8-t128 2 8 --tile 128
  run r$rep-16x1-t128 16 1 --tile 128
done
$B/rill-trace render $S --threads 16 --out /tmp/s.png --bench-frames 5 | grep "frames of" | sed "s/^/single-4: /"
# An animation: 24 frames of bounce at 1080p, one process against 8 ranks of 2 threads.
A="builtin:bounce --size 1920x1080 --frames 0:23"
mkdir -p /tmp/seq1 /tmp/seq8
/usr/bin/time -f "single sequence wall %e s" $B/rill-trace render $A --threads 16 --out /tmp/seq1/f-%04d.png --stats-json $OUT/seq-single.json --quiet 2>&1 | tail -2
/usr/bin/time -f "8x2 sequence wall %e s" mpirun --oversubscribe --bind-to none -np 8 $B/rill-trace render $A --threads 2 --tile 128 \
  --out /tmp/seq8/f-%04d.png --stats-json $OUT/seq-8x2.json --quiet 2>&1 | tail -2
for f in /tmp/seq1/*.png; do cmp -s $f /tmp/seq8/$(basename $f) || echo "sequence: $(basename $f) DIFFERS"; done
# A GPU rank beside CPU ranks (the OpenCL kernels compiled first, by one process).
$B/rill-trace render $S --backend opencl --out /tmp/gpu.png | tail -1
cmp -s /tmp/single.png /tmp/gpu.png || echo "opencl: IMAGE DIFFERS"
for tile in 128 256; do
  mpirun --oversubscribe --bind-to none -np 1 $B/rill-trace render $S --backend opencl --tile $tile \
    --out /tmp/mixed.png --stats-json $OUT/mixed-t$tile.json : -np 3 $B/rill-trace render $S --threads 5 \
    --tile $tile --out /tmp/mixed.png --stats-json $OUT/mixed-t$tile.json 2>&1 | tail -5
  cmp -s /tmp/single.png /tmp/mixed.png || echo "mixed: IMAGE DIFFERS"
done
tar -C $OUT -czf $RESULTS/stats.tar.gz .
