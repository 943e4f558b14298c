#!/bin/sh
# The simd backend's compacted masked launches (HostKernel.cpp, RILL_SIMD_COMPACT) change no
# bit: the wavefront path tracer (cornell-path, whose paths end at scattered depths under
# Russian roulette) and the multipass Whitted tracer (thesis-a, masked to each ray state) give
# the same colour and depth with compaction on and off, and the wavefront's equal the
# megakernel's (which launches unmasked).
#   simd-compact.sh RILL_TRACE WORK_DIR
set -eu
exe=$1; work=$2
mkdir -p "$work"
tag=simd-compact
. "$(dirname "$0")/same-outputs.sh"
render() {  # NAME COMPACT SCENE ARGS...
  name=$1; compact=$2; scene=$3; shift 3
  render_outputs "$name" "RILL_SIMD_COMPACT=$compact" "builtin:$scene" --backend simd "$@"
}
render wave-on on cornell-path --size 64x48 --spp 2 --strategy wavefront
render wave-off off cornell-path --size 64x48 --spp 2 --strategy wavefront
render mega on cornell-path --size 64x48 --spp 2 --strategy megakernel
same_outputs wave-on wave-off
same_outputs wave-on mega
render multi-on on thesis-a --size 64x48 --strategy multipass
render multi-off off thesis-a --size 64x48 --strategy multipass
same_outputs multi-on multi-off
# A bad setting is an error that names it.
if RILL_SIMD_COMPACT=maybe "$exe" render builtin:cornell-path --backend simd --size 8x6 \
    --strategy wavefront --quiet --out "$work/bad.png" 2> "$work/bad.txt"; then
  echo "simd-compact: RILL_SIMD_COMPACT=maybe was accepted"
  exit 1
fi
grep -q "RILL_SIMD_COMPACT='maybe': expected on or off" "$work/bad.txt"
echo "simd-compact: wavefront and multipass images the same with compaction on and off"
