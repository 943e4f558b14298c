#!/bin/bash
# Writes the sha256 of every generated kernel source (--source) for the built-in scenes on every
# backend and both loop shapes.   source-identity.sh RILL_TRACE OUT_LIST
exe=$1; list=$2; work=$(mktemp -d); : > "$list"
for s in thesis-a thesis-b cornell glass textured bounce empty; do
  for be in cpu simd opencl glsl glsl-compute; do
    for loop in ray segment; do
      f=$work/$s-$be-$loop.src
      "$exe" render "builtin:$s" --backend "$be" --loop "$loop" --size 16x12 --quiet --out "$work/x.png" --source "$f" > /dev/null 2>&1 \
        && echo "$(sha256sum < "$f" | cut -c1-64)  $s/$be/$loop" >> "$list" || echo "ERROR $s/$be/$loop" >> "$list"
    done
  done
done
rm -rf "$work"
