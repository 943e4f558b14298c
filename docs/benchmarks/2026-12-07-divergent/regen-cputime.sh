#!/bin/bash
# Path regeneration on and off (RILL_PATH_REGENERATE), simd and cpu, one thread, cornell-path
# 320x240 at 4 and 16 spp, 4 frames after the first: the process's CPU time (user + sys,
# GNU time), which the other processes on a loaded machine disturb less than the wall time
# (they still share its caches). The four configurations interleaved per round. Run from the
# repository root after a build; ROUNDS=n to change the 3 rounds.
B=build/apps/rill-trace/rill-trace
for spp in 4 16; do
  for round in $(seq "${ROUNDS:-3}"); do
    for cfg in "simd on" "cpu on" "simd off" "cpu off"; do
      set -- $cfg
      t=$( { RILL_PATH_REGENERATE=$2 /usr/bin/time -f "%U %S" $B render builtin:cornell-path --size 320x240 \
            --spp $spp --backend $1 --threads 1 --bench-frames 4 --out /dev/null --quiet > /dev/null; } 2>&1 | tail -1)
      echo "cornell-path 320x240 spp$spp $1 regenerate=$2 round $round: cpu seconds $(echo $t | awk '{print $1 + $2}')"
    done
  done
done
