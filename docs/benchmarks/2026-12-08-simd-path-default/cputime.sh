#!/bin/bash
# The same comparison by CPU time (user + sys of the process, GNU time), one thread, which the
# other sessions' load moves far less than the wall clock: per configuration and scene one run
# with --bench-frames 0 (start, scene, grid, kernels from the cache, the first frame) and, per
# round, one with --bench-frames 3; a frame's CPU time is the difference over 3.
B=${B:-build/apps/rill-trace/rill-trace}
ROUNDS=${ROUNDS:-2}
AREA=docs/benchmarks/2026-12-07-path/thesis-c-area.json
SCENES=${SCENES:-"builtin:cornell-path builtin:thesis-a builtin:thesis-b builtin:thesis-c builtin:cornell builtin:glass builtin:textured builtin:bounce $AREA"}
CONFIGS=${CONFIGS:-"cpu:megakernel:on simd:megakernel:on simd:megakernel:off simd:wavefront:on"}
cputime() { # scene extra... -- prints user+sys seconds
  local s=$1 be=$2 st=$3 regen=$4 n=$5; shift 5
  RILL_PATH_REGENERATE=$regen /usr/bin/time -f '%U %S' "$B" render "$s" "$@" --size 320x240 \
    --spp 4 --threads 1 --backend "$be" --strategy "$st" --bench-frames "$n" --out /dev/null \
    --quiet 2>&1 >/dev/null | tail -1 | awk '{printf "%.2f", $1 + $2}'
}
for round in 0 $(seq 1 "$ROUNDS"); do
  echo "# round $round ($([[ $round == 0 ]] && echo '--bench-frames 0' || echo '--bench-frames 3')), $(date -u +%H:%M:%S) UTC, load $(cut -d' ' -f1-3 /proc/loadavg)"
  for s in $SCENES; do
    extra=()
    [[ $s == builtin:cornell-path || $s == "$AREA" ]] || extra=(--integrator path)
    for c in $CONFIGS; do
      IFS=: read -r be st regen <<<"$c"
      n=3; [[ $round == 0 ]] && n=0
      echo "$(basename "$s" .json) $be $st regen=$regen round $round: $(cputime "$s" "$be" "$st" "$regen" "$n" "${extra[@]}") s"
    done
  done
done
