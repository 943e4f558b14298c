#!/bin/bash
# Issue 20: OpenCL read-backs through pinned memory, on and off, side by side.
source "$(dirname "$0")/setup.sh"
BUNNY=.devcarry/stanford-bunny.obj
timeout 100 $B/rill_backend_tests --gtest_filter='*/opencl' > $OUT/be.txt 2>&1; echo "opencl backend tests rc=$?"; tail -1 $OUT/be.txt
for round in 1 2 3; do for p in on off; do for sc in builtin:thesis-a $BUNNY; do
  echo "$round pinned=$p $(basename $sc): $(RILL_OPENCL_PINNED=$p timeout 60 $B/rill-trace render $sc --size 1920x1080 --backend opencl --bench-frames 30 --out /tmp/f-$p.png | grep -E 'frames|median per' | sed 's/; opencl.*//' | tr '\n' ' ')"
done; done; cmp /tmp/f-on.png /tmp/f-off.png && echo "same png"; done
