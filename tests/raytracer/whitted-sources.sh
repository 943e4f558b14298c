#!/bin/sh
# The Whitted integrator's kernels are the ones from before the path integrator (issue 48: "a
# Whitted scene without emitters generates the same kernel source"): the cpu backend's
# generated megakernel source (segment loop) of five built-in scenes, which between them take
# every Whitted shader, textures, refraction with its ray stack and a dynamic scene's BVH, has
# the sha256 recorded in data/whitted-sources.sha256. They were 6187a3b's (the commit before
# the path integrator) until one kernel came to serve every output (issue 50, item 8): since
# then the list is that of 4d90ac4's variant with the colour and the AOVs (its `--pfm --depth`
# render), which the one kernel is byte for byte, 4d90ac4's `--out` variant having been 6187a3b's.
# The sources are printed as one function (RILL_CPU_OUTLINE=off): the outlined layout the cpu
# backend compiles since 2026-12-07 is the same statements cut into functions (Outline.h), and
# this check is about the statements.
# A change to the Whitted kernels that is meant fails here: regenerate the list with the
# command in the loop below and say why in the commit.
#   whitted-sources.sh RILL_TRACE DATA_DIR WORK_DIR
set -eu
exe=$1; data=$2; work=$3
mkdir -p "$work"
status=0
while read -r want scene; do
  src="$work/$scene.c"
  RILL_CPU_OUTLINE=off "$exe" render "builtin:$scene" --backend cpu --loop segment --size 16x12 --quiet \
    --out "$work/$scene.png" --source "$src" > /dev/null
  got=$(sha256sum < "$src" | cut -c1-64)
  if [ "$got" != "$want" ]; then
    echo "whitted-sources: $scene: the cpu megakernel's source changed ($got, was $want)"
    status=1
  fi
done < "$data/whitted-sources.sha256"
[ $status -eq 0 ] && echo "whitted-sources: 5 kernel sources as before the path integrator"
exit $status
