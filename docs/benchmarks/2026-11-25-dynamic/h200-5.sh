# The fifth H200 run (issue 22): subtrees built as tasks from 4096 triangles (a) or from 1024 (b),
# three rounds at 4 and 16 threads. Variant binaries built from the commits before and after
# that change. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
for round in 1 2 3; do for t in 4 16; do for v in a b; do
  echo "round $round threads $t variant $v"; $B/rill-bench-dynamic-$v --sections build --repeats 15 --threads $t 2>&1 | tail -2
done; done; done
