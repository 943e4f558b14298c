#!/bin/sh
# The simd backend's lane count (16 in strict where the CPU has AVX-512, else 8;
# RILL_SIMD_LANES) changes no bit: Whitted scenes with reflections, refraction and textures,
# thesis C (61,562 triangles: simd's grid density rule), and the path tracer's megakernel and
# wavefront, each at 8 lanes and at the default lanes, give cpu's colour and depth. The sizes
# are not multiples of the 4 x 2 or 4 x 4 tiles, so partial tiles at the right edge and in
# the last rows are rendered too.
#   simd-lanes.sh RILL_TRACE WORK_DIR
set -eu
exe=$1; work=$2
mkdir -p "$work"
render() {  # NAME BACKEND LANES SCENE ARGS...
  name=$1; backend=$2; lanes=$3; scene=$4; shift 4
  RILL_SIMD_LANES=$lanes "$exe" render "builtin:$scene" --backend "$backend" --quiet "$@" \
    --out "$work/$name.png" --pfm "$work/$name.pfm" --depth "$work/$name.depth.pfm" > /dev/null
}
same() {  # A B
  for ext in pfm depth.pfm; do
    if ! cmp -s "$work/$1.$ext" "$work/$2.$ext"; then
      echo "simd-lanes: $1.$ext and $2.$ext differ"
      exit 1
    fi
  done
}
for scene in thesis-b thesis-c glass textured; do
  render "$scene-cpu" cpu auto "$scene" --size 37x23
  render "$scene-8" simd 8 "$scene" --size 37x23
  render "$scene-auto" simd auto "$scene" --size 37x23
  same "$scene-cpu" "$scene-8"
  same "$scene-cpu" "$scene-auto"
done
for strategy in megakernel wavefront; do
  render "path-$strategy-cpu" cpu auto cornell-path --size 30x21 --spp 2 --strategy "$strategy"
  render "path-$strategy-8" simd 8 cornell-path --size 30x21 --spp 2 --strategy "$strategy"
  render "path-$strategy-auto" simd auto cornell-path --size 30x21 --spp 2 --strategy "$strategy"
  same "path-$strategy-cpu" "path-$strategy-8"
  same "path-$strategy-cpu" "path-$strategy-auto"
done
echo "simd-lanes: images the same at 8 lanes, at the default lanes and on cpu"
