#!/bin/bash
# Issue 52 item 5 on the 2-core development machine (OpenCL on PoCL): --overlap on against off
# in interleaved rounds, for ratios only (PoCL's read-back is a copy on the cores that trace).
#  - rill-trace render S --size 640x480 --backend opencl --bench-frames 20: the median frame;
#  - rill-trace render builtin:bounce --size 320x240 --backend opencl --frames 0:20: the
#    command's wall time (kernels from PoCL's cache after the first round).
# Run from the repository root after building rill-trace; ROUNDS (default 5). Prints a table.
B=${B:-build/apps/rill-trace/rill-trace}
D=$(mktemp -d)
echo "| round | case | overlap | ms |"
echo "| --- | --- | --- | --- |"
for k in $(seq 1 "${ROUNDS:-5}"); do
  for scene in builtin:thesis-a builtin:thesis-c; do
    for ov in on off; do
      "$B" render "$scene" --size 640x480 --backend opencl --bench-frames 20 --overlap "$ov" \
        --out "$D/b-$ov.png" --stats-json "$D/s.json" > /dev/null 2>&1 || { echo "| $k | $scene | $ov | failed |"; continue; }
      python3 -c "import json,sys; print(f'| $k | $scene --bench-frames 20 | $ov | {json.load(open(sys.argv[1]))[\"bench_frames\"][\"median_ms\"]:.2f} |')" "$D/s.json"
    done
  done
  for ov in on off; do
    mkdir -p "$D/$ov"
    t0=$(date +%s%N)
    "$B" render builtin:bounce --size 320x240 --backend opencl --frames 0:20 --overlap "$ov" --quiet \
      --out "$D/$ov/f-%02d.png" > /dev/null 2>&1 || { echo "| $k | bounce --frames 0:20 | $ov | failed |"; continue; }
    echo "| $k | bounce --frames 0:20 (whole command) | $ov | $(( ($(date +%s%N) - t0) / 1000000 )) |"
  done
  diff -rq "$D/on" "$D/off" > /dev/null && echo "| $k | bounce: the 21 PNGs on and off | | the same bytes |"
done
rm -rf "$D"
