#!/bin/bash
# Issue 20 on the GPU machine, session 16: glsl-compute's slow mode against the GPU's clocks.
# rill-bench-trace on glsl-compute with RILL_THREADS=16 and 1 (the cpu reference between the
# GPU launches takes longer with 1), two rounds, while nvidia-smi samples the SM clock and
# the performance state every 20 ms; each process's samples are summarized.
# Set-up: the dynamic-scene folder's setup.sh (carried libraries in .devcarry/lib).
source docs/benchmarks/2026-11-25-dynamic/setup.sh
[ -f .devcarry/lib/libembree3.so.3 ] || python3 -c "import lzma, shutil; shutil.copyfileobj(lzma.open('.devcarry/lib/libembree3.so.3.xz'), open('.devcarry/lib/libembree3.so.3', 'wb'))"
for round in 1 2; do for t in 16 1; do
  nvidia-smi --query-gpu=clocks.sm,pstate,utilization.gpu --format=csv,noheader,nounits -lms 20 > /tmp/clk.txt &
  smi=$!
  echo "-- round $round RILL_THREADS=$t"
  RILL_THREADS=$t timeout 100 $B/rill-bench-trace --size 1920x1080 --repeats 5 --sections throughput --scenes builtin:thesis-c --backends glsl-compute 2>&1 | grep -E "glsl-compute \|"
  kill $smi; wait $smi 2>/dev/null
  python3 - <<'PY'
import collections
rows=[l.strip().split(', ') for l in open('/tmp/clk.txt') if l.count(',')==2]
clk=[int(r[0]) for r in rows if r[0].isdigit()]
busy=[(int(r[0]),int(r[2])) for r in rows if r[0].isdigit() and r[2].isdigit() and int(r[2])>0]
print("samples", len(rows), "pstates", dict(collections.Counter(r[1] for r in rows)))
print("SM MHz over the run: min", min(clk), "median", sorted(clk)[len(clk)//2], "max", max(clk))
if busy:
    b=sorted(c for c,u in busy)
    print("SM MHz while the GPU was busy:", len(b), "samples, min", b[0], "median", b[len(b)//2], "max", b[-1])
PY
done; done
