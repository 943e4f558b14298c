#!/bin/bash
# Before and after this change's defaults, side by side: cpu's default, simd's old default
# (BEFORE: a rill-trace built from main before the change, RILL_PATH_REGENERATE unset: 16
# samples per launch, density 16 on thesis C), simd's new default (one sample per launch,
# density 4) and the wavefront on simd, per scene one after the other in each round.
# MODE=wall: the median of --bench-frames 3, 2 threads, as a user runs it.
# MODE=cpu: CPU time (user + sys), one thread, (T(--bench-frames 3) - T(--bench-frames 0)) / 3,
# a frame's CPU time with the start, scene, grid and first frame taken off.
# EXTRA: more render options for every run (e.g. "--max-depth 8").
# Usage: BEFORE=path/to/old/rill-trace MODE=wall|cpu after.sh (from the repository root).
AFTER=${AFTER:-build/apps/rill-trace/rill-trace}
BEFORE=${BEFORE:?the rill-trace of main before the change}
MODE=${MODE:-wall}
ROUNDS=${ROUNDS:-3}
AREA=docs/benchmarks/2026-12-07-path/thesis-c-area.json
SCENES=${SCENES:-"builtin:cornell-path builtin:thesis-a builtin:thesis-b builtin:thesis-c builtin:cornell builtin:glass builtin:textured builtin:bounce $AREA"}
CONFIGS=${CONFIGS:-"cpu:megakernel:after simd:megakernel:before simd:megakernel:after simd:wavefront:after"}
wall() { "$@" --threads 2 --bench-frames 3 --out /dev/null --quiet 2>&1 |
  grep -o 'after the first: median [0-9.]* ms' | grep -o '[0-9.]*' | head -1; }
cpu() { /usr/bin/time -f '%U %S' "$@" --threads 1 --out /dev/null --quiet 2>&1 >/dev/null |
  tail -1 | awk '{printf "%.3f", $1 + $2}'; }
for round in $(seq 1 "$ROUNDS"); do
  echo "# $MODE round $round, $(date -u +%H:%M:%S) UTC, load $(cut -d' ' -f1-3 /proc/loadavg)"
  for s in $SCENES; do
    extra=()
    [[ $s == builtin:cornell-path || $s == "$AREA" ]] || extra=(--integrator path)
    for c in $CONFIGS; do
      IFS=: read -r be st bin <<<"$c"
      B=$AFTER; [[ $bin == before ]] && B=$BEFORE
      cmd=(env -u RILL_PATH_REGENERATE "$B" render "$s" "${extra[@]}" --size 320x240 --spp 4
           --backend "$be" --strategy "$st" $EXTRA)
      if [[ $MODE == wall ]]; then
        v="$(wall "${cmd[@]}") ms"
      else
        t0=$(cpu "${cmd[@]}" --bench-frames 0); t3=$(cpu "${cmd[@]}" --bench-frames 3)
        v="$(echo "scale=3; ($t3 - $t0) / 3" | bc) s a frame"
      fi
      echo "$(basename "$s" .json)${EXTRA:+ ($EXTRA)} $be $st $bin round $round: $v"
    done
  done
done
