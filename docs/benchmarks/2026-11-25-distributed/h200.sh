# Issue 23 on the H200 host: Debian 12's Open MPI unpacked from its packages (.mpi/, carried)
# into /tmp/mpi and relocated with OPAL_PREFIX; rill-trace carried in .devcarry/bin with its
# libraries. thesis C at 1080p on the 16 cores: one process, then 2, 4, 8 and 16 ranks with
# ranks x threads = 16, twice each (the second with warm kernel caches), and one OpenCL rank
# beside three CPU ranks. Every image is compared with the single-process one.
source docs/benchmarks/2026-11-25-distributed/setup.sh
$B/rill-trace render $S --threads 16 --out /tmp/single.png --bench-frames 5 | tail -3 | tee $OUT/single.txt
for n in 2 4 8 16; do
  for rep in 1 2; do
    mpirun --oversubscribe --bind-to none -np $n $B/rill-trace render $S --threads $((16 / n)) --tile 128 \
      --out /tmp/d$n.png --stats-json $OUT/mpi-$n-$rep.json 2>&1 | tail -1
  done
  cmp /tmp/single.png /tmp/d$n.png && echo "$n ranks: image identical to the single process"
done
mpirun --oversubscribe --bind-to none -np 1 $B/rill-trace render $S --backend opencl --tile 128 --out /tmp/g.png \
  --stats-json $OUT/mpi-gpu-cpu.json : -np 3 $B/rill-trace render $S --threads 5 --tile 128 --out /tmp/g.png 2>&1 | tail -5
cmp /tmp/single.png /tmp/g.png && echo "opencl + 3 cpu ranks: image identical to the single process"
