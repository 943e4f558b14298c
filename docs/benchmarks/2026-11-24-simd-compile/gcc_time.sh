#!/bin/bash
# gcc_time.sh N file [extra flags]: min and median user+sys seconds of N compiles with the simd/cpu flags
F="-std=c99 -O2 -fPIC -shared -fno-math-errno -fwrapv -fno-strict-aliasing -fno-tree-slp-vectorize -w -fno-fast-math -ffp-contract=off -fexcess-precision=standard"
n=$1; f=$2; shift 2
for i in $(seq $n); do /usr/bin/time -f "%U %S" cc $F "$@" -o /tmp/gcc_time_$$.so $f -lm 2>&1 | tail -1; done | awk '{print $1+$2}' | sort -n | awk '{a[NR]=$1} END{printf "min %.2f med %.2f\n", a[1], a[int((NR+1)/2)]}'
