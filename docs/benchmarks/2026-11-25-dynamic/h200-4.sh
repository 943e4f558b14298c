source docs/benchmarks/2026-11-25-dynamic/setup.sh
for t in 1 2 4 8 16; do for v in a b; do
  echo "threads $t variant $v"; $B/rill-bench-dynamic-$v --sections build --repeats 15 --threads $t 2>&1 | tail -2
done; done | tee $OUT/build.txt
