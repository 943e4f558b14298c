#!/bin/bash
# Path regeneration in the path megakernel (RILL_PATH_REGENERATE on: up to 16 samples per
# launch, a pixel whose path ended starting its next sample at once; off: one sample per
# launch, as before), simd against cpu, cornell-path at 320x240 with 4 and 16 spp, the four
# configurations interleaved per round. Then the same for opencl (PoCL on these cores), on
# and off. Run from the repository root after a build; ROUNDS=n to change the 3 rounds.
B=build/apps/rill-trace/rill-trace
frame() {  # REGENERATE SPP BACKEND FRAMES
  RILL_PATH_REGENERATE=$1 $B render builtin:cornell-path --size 320x240 --spp "$2" --backend "$3" \
    --bench-frames "$4" --out /dev/null --quiet | grep -o 'after the first: median [0-9.]* ms'
}
for spp in 4 16; do
  frames=$([ "$spp" = 4 ] && echo 5 || echo 3)
  for round in $(seq "${ROUNDS:-3}"); do
    for cfg in "simd on" "cpu on" "simd off" "cpu off"; do
      set -- $cfg
      echo "cornell-path spp$spp $1 regenerate=$2 round $round: $(frame "$2" "$spp" "$1" "$frames")"
    done
  done
done
for round in $(seq "${ROUNDS:-3}"); do
  for r in on off; do
    echo "cornell-path spp4 opencl regenerate=$r round $round: $(frame "$r" 4 opencl 3)"
  done
done
