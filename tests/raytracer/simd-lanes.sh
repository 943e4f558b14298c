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
tag=simd-lanes
. "$(dirname "$0")/same-outputs.sh"
render() {  # NAME BACKEND LANES SCENE ARGS...
  r_name=$1; r_backend=$2; r_lanes=$3; r_scene=$4; shift 4
  render_outputs "$r_name" "RILL_SIMD_LANES=$r_lanes" "builtin:$r_scene" --backend "$r_backend" "$@"
}
for scene in thesis-b thesis-c glass textured; do
  render "$scene-cpu" cpu auto "$scene" --size 37x23
  render "$scene-8" simd 8 "$scene" --size 37x23
  render "$scene-auto" simd auto "$scene" --size 37x23
  same_outputs "$scene-cpu" "$scene-8"
  same_outputs "$scene-cpu" "$scene-auto"
done
for strategy in megakernel wavefront; do
  render "path-$strategy-cpu" cpu auto cornell-path --size 30x21 --spp 2 --strategy "$strategy"
  render "path-$strategy-8" simd 8 cornell-path --size 30x21 --spp 2 --strategy "$strategy"
  render "path-$strategy-auto" simd auto cornell-path --size 30x21 --spp 2 --strategy "$strategy"
  same_outputs "path-$strategy-cpu" "path-$strategy-8"
  same_outputs "path-$strategy-cpu" "path-$strategy-auto"
done
echo "simd-lanes: images the same at 8 lanes, at the default lanes and on cpu"
