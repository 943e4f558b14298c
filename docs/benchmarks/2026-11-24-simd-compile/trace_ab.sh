#!/bin/bash
# trace_ab.sh SCENE SIZE REPS FILES...: simd trace ms (min, median over REPS interleaved runs, warm private cache)
# of rill-trace ($RILL_TRACE) with its megakernel's C replaced by each FILE ("cpu": the cpu backend).
scene=$1; size=$2; reps=$3; shift 3
declare -A C
for v in "$@"; do C[$v]=$(mktemp -d); done
for r in $(seq 0 $reps); do
  for v in "$@"; do
    b=simd; s=${v%%:*}; x=""; [[ $v == *:* ]] && x="${v#*:}"; [ $v = cpu ] && { b=cpu; s=""; }
    RILL_CACHE_DIR=${C[$v]} RILL_CC=$(cd $(dirname $0) && pwd)/ccswap.sh SWAP_SRC=$s RILL_EXTRA_FLAGS="$x" ${RILL_TRACE:-build/examples/raytracer/rill-trace} render $scene --backend $b --size $size --quiet --stats-json /tmp/trace_ab.json --out /tmp/trace_ab_$(basename ${v%%:*})$r.png >/dev/null
    [ $r -gt 0 ] && python3 -c "import json;d=json.load(open('/tmp/trace_ab.json'));print('$v',d['time_ms']['trace'])"
  done
done | python3 -c "
import sys,statistics as st
d={}
for l in sys.stdin:
  k,t=l.split(); d.setdefault(k,[]).append(float(t))
for k,t in d.items(): print('%-40s trace ms min %7.1f med %7.1f  (%d runs)'%(k,min(t),st.median(t),len(t)))
"
