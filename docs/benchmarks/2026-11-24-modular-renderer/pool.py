#!/usr/bin/env python3
"""Pools the AFTER/BEFORE ratios of several speed_kept.py runs (their --json files).

Each repeat of a run gives one ratio AFTER/BEFORE from two renders next to each other in
time; on a shared machine whose load changes by the minute these pairs are the fair
comparison. Per backend and workload this prints the number of pairs, the median ratio and
a 95% bootstrap interval of that median (10000 resamples, fixed seed, so the output is
reproducible), and whether the interval lies within 1.03.

  pool.py run1.json run2.json ...
"""
import json
import random
import statistics
import sys


def main():
    pairs = {}
    for path in sys.argv[1:]:
        with open(path) as f:
            run = json.load(f)
            for r in run["rows"]:
                # Runs at another size than the brief's 256x192 are rows of their own.
                size = "" if run["size"] == "256x192" else " " + run["size"]
                key = (r["backend"], r["workload"] + size)
                pairs.setdefault(key, []).extend(
                    a / b for a, b in zip(r["after_ms"], r["before_ms"]))
    if not pairs:
        sys.exit("usage: pool.py RUN.json ...")
    rng = random.Random(18)
    print("| backend | workload | pairs | median AFTER/BEFORE | 95% interval | within 3% |")
    print("|---|---|---|---|---|---|")
    for (backend, workload), ratios in pairs.items():
        meds = sorted(statistics.median(rng.choices(ratios, k=len(ratios)))
                      for _ in range(10000))
        lo, hi = meds[250], meds[9749]
        verdict = "yes" if hi <= 1.03 else ("no" if lo > 1.03 else "not resolved")
        print(f"| {backend} | {workload} | {len(ratios)} | {statistics.median(ratios):.3f} "
              f"| {lo:.3f}..{hi:.3f} | {verdict} |")


if __name__ == "__main__":
    main()
