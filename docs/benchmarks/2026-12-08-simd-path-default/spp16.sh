#!/bin/bash
# Path regeneration on and off on simd at 16 samples (cpu with it on, its default), CPU time of
# one thread, one frame: T(--bench-frames 1) - T(--bench-frames 0). Run with the rill-trace from
# before the change.
B=build/apps/rill-trace/rill-trace
t() { /usr/bin/time -f '%U %S' $B render "$@" --size 320x240 --threads 1 --out /dev/null --quiet 2>&1 >/dev/null | tail -1 | awk '{printf "%.2f", $1+$2}'; }
for r in 1 2; do for s in cornell-path glass bounce thesis-b; do for c in cpu:on simd:on simd:off; do
 IFS=: read -r be rg <<<"$c"; ex=(); [[ $s == cornell-path ]] || ex=(--integrator path)
 a=$(RILL_PATH_REGENERATE=$rg t builtin:$s "${ex[@]}" --spp 16 --backend $be --bench-frames 0); b=$(RILL_PATH_REGENERATE=$rg t builtin:$s "${ex[@]}" --spp 16 --backend $be --bench-frames 1)
 echo "$s spp16 $be regen=$rg r$r: bf0 $a bf1 $b frame $(echo "$b - $a" | bc)"; done; done; done
