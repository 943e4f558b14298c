# The sixth H200 run (issue 22): variants of the parallel thresholds, three rounds at 8 and 16
# threads: b as committed (subtree tasks from 1024 triangles, parallel partitions from 32768,
# parallel binning from 16384), c (512, 16384, 16384), d (1024, 16384, 8192). Variant binaries
# built from local edits of Bvh.cpp. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
for round in 1 2 3; do for t in 8 16; do for v in b c d; do
  echo "round $round threads $t variant $v"; $B/rill-bench-dynamic-$v --sections build --repeats 15 --threads $t 2>&1 | tail -2
done; done; done
