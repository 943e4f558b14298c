#!/bin/bash
# The 2-core measurement of 2026-12-08-embree-whitted.md: rounds of the embree and whitted
# sections at 1024x1024 (each figure the median of 3 interleaved repeats), thesis A, B, C,
# glass and, where ../shared/meshes has it, the bunny; full and camera-only Whitted frames.
# Run from the repository root after a RelWithDebInfo build; OUT names the folder for the
# tables (default /tmp/embree-whitted), ROUNDS how many (default 3).
OUT=${OUT:-/tmp/embree-whitted}
mkdir -p "$OUT"
S=builtin:thesis-a,builtin:thesis-b,builtin:thesis-c,builtin:glass
[ -f ../shared/meshes/stanford-bunny.obj ] && S=$S,../shared/meshes/stanford-bunny.obj
for round in $(seq 1 "${ROUNDS:-3}"); do
  build/bench/rill-bench-trace --sections embree,whitted --whitted-frames full,camera \
    --embree-modes 8 --size 1024x1024 --repeats 3 --scenes "$S" \
    --md "$OUT/round-$round.md" > "$OUT/round-$round.txt" 2>&1
  echo "round $round rc=$? load $(cut -d' ' -f1-3 /proc/loadavg)"
done
# Per scene, frame and backend: Rill/Embree of the Whitted frames, the median of the rounds
# (each round in parentheses).
python3 - "$OUT"/round-*.md <<'PY'
import statistics, sys
rows = {}
for path in sys.argv[1:]:
    table = False
    for line in open(path):
        if line.startswith("###"):
            table = "Whitted frames" in line
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if table and len(cells) == 14 and cells[4] in ("cpu", "simd"):
            rows.setdefault((cells[0], cells[2], cells[4]), []).append(float(cells[11]))
print("| scene | frame | backend | Rill/Embree |\n| --- | --- | --- | ---: |")
for (scene, frame, be), v in rows.items():
    print(f"| {scene} | {frame} | {be} | %.3f (%s) |" % (statistics.median(v), ", ".join("%.3f" % x for x in v)))
PY
