#!/usr/bin/env python3
# Compares the launch section of two rill-bench-compile binaries (say, built before and after a
# change): runs them interleaved, N times each, and prints the median of every column per
# backend side by side (docs/benchmarks/2026-11-24-compile-launch.md).
#
#   bench/compare_launch.py BEFORE AFTER N [rill-bench-compile options...]
import subprocess, sys, statistics, collections
before, after, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
extra = sys.argv[4:]
cols = ["1 elem", "1024", "kernel", "overhead", "cnt launch", "cnt kernel", "pass", "pass-kern"]
data = collections.defaultdict(list)
for i in range(n):
    for tag, exe in (("before", before), ("after", after)):
        out = subprocess.run([exe, "--sections", "launch"] + extra, capture_output=True, text=True).stdout
        for line in out.splitlines():
            f = line.split()
            if len(f) >= 11 and f[0] in ("cpu", "simd", "opencl", "glsl") and f[5] == "|":
                vals = [float(x) for x in f[1:5] + f[6:10]]
                data[(f[0], tag)].append(vals)
print("median of %d interleaved runs (us)" % n)
print("%-8s %-6s " % ("backend", "") + " ".join("%10s" % c for c in cols))
for be in ("cpu", "simd", "opencl", "glsl"):
    for tag in ("before", "after"):
        rows = data.get((be, tag))
        if not rows: continue
        med = [statistics.median(r[j] for r in rows) for j in range(len(cols))]
        print("%-8s %-6s " % (be, tag) + " ".join("%10.1f" % v for v in med))
