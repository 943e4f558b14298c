#!/bin/bash
# Grid density 4 against 16 on simd under the path integrator (thesis C, with and without an
# area light), cpu at its 4 beside; CPU time of one thread, a frame = (T(3 frames) - T(0)) / 3.
# Run with the rill-trace from before the change (B=...), whose simd regenerated paths by default
# (hence RILL_PATH_REGENERATE=off on simd: the new default).
B=${B:-build/apps/rill-trace/rill-trace}
AREA=docs/benchmarks/2026-12-07-path/thesis-c-area.json
t() { /usr/bin/time -f '%U %S' $B render "$@" --size 320x240 --spp 4 --threads 1 --out /dev/null --quiet 2>&1 >/dev/null | tail -1 | awk '{printf "%.2f", $1+$2}'; }
for r in 1 2; do for s in builtin:thesis-c $AREA; do for c in cpu:4 simd:4 simd:16; do
 IFS=: read -r be gd <<<"$c"; ex=(); [[ $s == $AREA ]] || ex=(--integrator path)
 rg=on; [[ $be == simd ]] && rg=off
 a=$(RILL_PATH_REGENERATE=$rg t $s "${ex[@]}" --backend $be --grid-density $gd --bench-frames 0); b=$(RILL_PATH_REGENERATE=$rg t $s "${ex[@]}" --backend $be --grid-density $gd --bench-frames 3)
 echo "$(basename $s .json) $be density $gd regen=$rg r$r: bf0 $a bf3 $b frame $(echo "scale=3; ($b - $a)/3" | bc)"; done; done; done
