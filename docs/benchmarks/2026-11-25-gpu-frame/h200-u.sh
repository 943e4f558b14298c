#!/bin/bash
# Session 25 (2026-11-28), after h200-t.sh: OpenCL frames of thesis A and the bunny, both builds
# alternating in four rounds of 30 frames, because h200-s.sh's two rounds left thesis A's
# OpenCL frame within the noise. Set-up as h200-s.sh.
source docs/benchmarks/2026-11-25-dynamic/setup.sh; BUNNY=.devcarry/stanford-bunny.obj
for r in 1 2 3 4; do for sc in builtin:thesis-a $BUNNY; do for bin in rill-trace rill-trace-base; do
  x=$(timeout 60 $B/$bin render $sc --size 1920x1080 --backend opencl --bench-frames 30 --out /tmp/$bin.png)
  echo "-- $r $(basename $sc) $bin frame $(echo "$x" | grep 'frames of' | sed -E 's/.*first: median ([0-9.]+) ms.*/\1/') $(echo "$x" | grep 'median per step' | sed -E 's/.*launch ([0-9.]+) ms \(kernel ([0-9.]+) ms\).*reduce ([0-9.]+) ms, read-back ([0-9.]+) ms.*/launch \1 kernel \2 reduce \3 read-back \4/')"
done; done; done
