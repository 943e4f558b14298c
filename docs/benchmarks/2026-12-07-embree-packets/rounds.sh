#!/bin/bash
# The 2-core measurement of 2026-12-07-embree-packets.md: three rounds of the embree section at
# 1024x1024 (each the median of 3 interleaved repeats), thesis A, B, C and, where
# ../shared/meshes has it, the bunny. Run from the repository root after a RelWithDebInfo build;
# OUT names the folder for the tables (default /tmp/embree-packets).
OUT=${OUT:-/tmp/embree-packets}
mkdir -p "$OUT"
S=builtin:thesis-a,builtin:thesis-b,builtin:thesis-c
[ -f ../shared/meshes/stanford-bunny.obj ] && S=$S,../shared/meshes/stanford-bunny.obj
for round in 1 2 3; do
  build/bench/rill-bench-trace --sections embree --size 1024x1024 --repeats 3 --scenes "$S" \
    --md "$OUT/round-$round.md" > "$OUT/round-$round.txt" 2>&1
  echo "round $round rc=$? load $(cut -d' ' -f1-3 /proc/loadavg)"
done
# Per scene and Embree mode: cpu/Embree and simd/Embree, the median of the rounds (each round
# in parentheses).
python3 - "$OUT"/round-*.md <<'PY'
import statistics, sys
rows = {}
for path in sys.argv[1:]:
    table = False
    for line in open(path):
        table = table or "ray modes" in line
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if table and len(cells) >= 10 and cells[2].startswith("rtcIntersect"):
            rows.setdefault((cells[0], cells[2]), []).append((float(cells[-2]), float(cells[-1])))
print("| scene | Embree mode | cpu/Embree | simd/Embree |\n| --- | --- | ---: | ---: |")
for (scene, mode), v in rows.items():
    col = lambda k: "%.3f (%s)" % (statistics.median(x[k] for x in v), ", ".join("%.3f" % x[k] for x in v))
    print(f"| {scene} | {mode} | {col(0)} | {col(1)} |")
PY
