#!/bin/bash
# Path tracing throughput (issue 48's benchmark): rill-trace render S --size 1920x1080
# --max-depth 8 --spp 1 --bench-frames N: each frame is one camera path per pixel (Russian
# roulette from bounce 3), so camera paths per second = 1920 * 1080 / the median frame, and
# rays per second = the frame's rays (camera, bounce and shadow rays) / the median frame.
#   bench.sh RILL_TRACE BACKENDS FRAMES OUT_DIR
# Scenes: builtin:cornell-path (its area light) and thesis C with a 4 x 4 area light
# (thesis-c-area.json). Strict and fast. Two processes per figure; the table takes the lower.
exe=$1; backends=$2; frames=$3; out=$4; here=$(dirname "$0")
mkdir -p "$out"
for scene in builtin:cornell-path "$here/thesis-c-area.json"; do
  name=$(basename "$scene" .json); name=${name#builtin:}
  for be in ${backends//,/ }; do for acc in strict fast; do for k in 1 2; do
    j="$out/$name-$be-$acc-$k.json"
    timeout 300 "$exe" render "$scene" --size 1920x1080 --max-depth 8 --spp 1 --backend "$be" \
      --accuracy "$acc" --bench-frames "$frames" --out /tmp/bench-path.png --stats-json "$j" > /dev/null 2>&1
    python3 - "$j" "$name" "$be" "$acc" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); b = j["bench_frames"]; ms = b["median_ms"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {ms:.2f} | {1920*1080/ms/1e3:.1f} | {j['rays']/ms/1e3:.1f} |")
PY
  done; done; done
done
