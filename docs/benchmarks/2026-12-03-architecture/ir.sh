#!/bin/bash
# Instructions executed (valgrind callgrind's Ir, whole process) by a rill-trace render with
# 3 bench frames, before and after, for cpu and simd, full and primary (--max-depth 0).
: "${BEFORE:?set BEFORE and AFTER to the two rill-trace binaries}" "${AFTER:?}"
for be in cpu simd; do for cfg in full primary; do
  extra=""; [ $cfg = primary ] && extra="--max-depth 0"
  for tag in before after; do
    exe=$BEFORE; [ $tag = after ] && exe=$AFTER
    out=/tmp/cg-$be-$cfg-$tag.out
    valgrind --tool=callgrind --callgrind-out-file=$out $exe render builtin:thesis-b --backend $be --size 256x192 --bench-frames 3 --threads 1 --quiet --out /dev/null $extra > /tmp/cg-$be-$cfg-$tag.log 2>&1
    ir=$(grep -m1 "^summary:" $out | awk '{print $2}')
    echo "$be $cfg $tag $ir"
  done
done; done
