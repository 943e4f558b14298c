#!/bin/bash
# simd against cpu on the path tracer, as a user runs it: every built-in scene under the path
# integrator (cornell-path as it is, the others with --integrator path), thesis C with an area
# light, 320x240, 4 samples, `--bench-frames 3` (the median of 3 frames after the first).
# Per scene and round the configurations run one after the other, so that each round's figures
# share the machine's load: cpu and simd with the megakernel (regeneration on, the default
# before this change), simd's megakernel with regeneration off, and the wavefront on both.
# STRATEGIES overrides the list (e.g. "auto" after the change). Run from the repository root.
B=${B:-build/apps/rill-trace/rill-trace}
ROUNDS=${ROUNDS:-3}
AREA=docs/benchmarks/2026-12-07-path/thesis-c-area.json
SCENES=${SCENES:-"builtin:cornell-path builtin:thesis-a builtin:thesis-b builtin:thesis-c builtin:cornell builtin:glass builtin:textured builtin:bounce $AREA"}
CONFIGS=${CONFIGS:-"cpu:megakernel:on cpu:wavefront:on simd:megakernel:on simd:megakernel:off simd:wavefront:on"}
median() { grep -o 'after the first: median [0-9.]* ms' | grep -o '[0-9.]* ms' | head -1; }
for round in $(seq 1 "$ROUNDS"); do
  echo "# round $round, $(date -u +%H:%M:%S) UTC, load $(cut -d' ' -f1-3 /proc/loadavg)"
  for s in $SCENES; do
    extra=()
    [[ $s == builtin:cornell-path || $s == "$AREA" ]] || extra=(--integrator path)
    for c in $CONFIGS; do
      IFS=: read -r be st regen <<<"$c"
      t=$(RILL_PATH_REGENERATE=$regen "$B" render "$s" "${extra[@]}" --size 320x240 --spp 4 \
            --backend "$be" --strategy "$st" --bench-frames 3 --out /dev/null --quiet 2>&1 | median)
      echo "$(basename "$s" .json) $be $st regen=$regen round $round: ${t:-FAILED}"
    done
  done
done
