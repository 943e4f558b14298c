#!/bin/bash
# Renders every scene with one rill-trace and writes each output's sha256 to a list.
#   identity.sh RILL_TRACE OUT_LIST
exe=$1; list=$2; work=$(mktemp -d)
: > "$list"
run() {  # name scene backend strategy
  local name=$1 scene=$2 be=$3 st=$4 d=$work/$1-$3-$4
  mkdir -p "$d"
  if "$exe" render "$scene" --backend "$be" --strategy "$st" --size 48x36 --quiet \
      --out "$d/i.png" --pfm "$d/c.pfm" --depth "$d/d.pfm" --prim "$d/p.pfm" --normal "$d/n.pfm" \
      > "$d/log" 2>&1; then
    (cd "$d" && sha256sum i.png c.pfm d.pfm p.pfm n.pfm | sed "s#  #  $name/$be/$st/#") >> "$list"
  else
    echo "ERROR $name/$be/$st: $(tail -1 "$d/log")" >> "$list"
  fi
}
for s in thesis-a thesis-b cornell glass textured bounce empty; do
  for be in cpu simd opencl glsl glsl-compute; do
    run "$s" "builtin:$s" "$be" megakernel
  done
  for be in cpu opencl; do run "$s" "builtin:$s" "$be" multipass; done
done
for f in "$(dirname "$0")"/../../../scenes/*.json; do
  n=$(basename "$f" .json); run "file-$n" "$f" cpu megakernel
done
rm -rf "$work"
