#!/bin/bash
# The seventh H200 run (issue 22): the BVH builder before (old) and after (new) the partition
# reads each triangle's bin from the binning instead of binning it again; three rounds at 4,
# 8 and 16 threads, old and new alternating. Set-up in setup.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh
[ -f .devcarry/lib/libembree3.so.3 ] || python3 -c "import lzma, shutil; shutil.copyfileobj(lzma.open('.devcarry/lib/libembree3.so.3.xz'), open('.devcarry/lib/libembree3.so.3', 'wb'))"
for round in 1 2 3; do for t in 4 8 16; do for v in old new; do
  echo "round $round threads $t variant $v"; $B/rill-bench-dynamic-$v --sections build --repeats 15 --threads $t 2>&1 | tail -2
done; done; done
