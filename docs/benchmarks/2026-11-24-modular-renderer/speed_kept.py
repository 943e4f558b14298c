#!/usr/bin/env python3
"""Speed kept across the modular-renderer restructure (issue 18 item 1), measured side by side.

Runs two rill-trace binaries, BEFORE and AFTER, alternately (the order flips every repeat)
on builtin:thesis-b at 256x192 for each backend and workload:

  full       rill-trace render builtin:thesis-b (the scene's defaults)
  primary    the same scene with shadows off and --max-depth 0 (thesis-b-primary.json next
             to this script: rill-trace has no shadows switch)
  multipass  full, with --strategy multipass

and reads trace_ms (time_ms.trace) from --stats-json. Each binary has private caches (Rill's,
PoCL's, Mesa's) and renders every row once untimed first, so the timed runs load warm
kernels. Every timed render also writes --pfm; the script checks that BEFORE's and AFTER's
images are bitwise identical (cmp) for every row.

  speed_kept.py BEFORE AFTER [--reps 9] [--backends cpu,simd,opencl,glsl]
                [--workloads full,primary,multipass] [--size 256x192] [--json out.json]
  speed_kept.py --table out.json          # the table of an earlier run

Prints a Markdown table: medians, AFTER/BEFORE of the medians, the median of the per-repeat
ratios (each from two runs next to each other in time) with its min..max, the ratio of the
fastest runs, and each binary's min..max.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SIZE = "256x192"  # --size changes it
WORKLOADS = {
    "full": ["builtin:thesis-b"],
    "primary": [os.path.join(HERE, "thesis-b-primary.json"), "--max-depth", "0"],
    "multipass": ["builtin:thesis-b", "--strategy", "multipass"],
}


def render(binary, env, backend, workload, out_dir, tag):
    """Runs one render; returns (trace_ms, path of its PFM)."""
    stats = os.path.join(out_dir, f"{tag}.json")
    pfm = os.path.join(out_dir, f"{tag}.pfm")
    cmd = [binary, "render"] + WORKLOADS[workload] + [
        "--backend", backend, "--size", SIZE, "--stats-json", stats, "--pfm", pfm, "--quiet"]
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"speed_kept.py: {' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()}")
    with open(stats) as f:
        return json.load(f)["time_ms"]["trace"], pfm


def private_env(root):
    env = dict(os.environ)
    for var, sub in (("RILL_CACHE_DIR", "rill"), ("POCL_CACHE_DIR", "pocl"),
                     ("MESA_SHADER_CACHE_DIR", "mesa"), ("XDG_CACHE_HOME", "xdg")):
        env[var] = os.path.join(root, sub)
        os.makedirs(env[var], exist_ok=True)
    return env


def main():
    global SIZE
    if len(sys.argv) == 3 and sys.argv[1] == "--table":  # re-print a --json file's table
        with open(sys.argv[2]) as f:
            saved = json.load(f)
        print_table(saved["rows"], saved["reps"], saved["size"])
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--reps", type=int, default=9)
    ap.add_argument("--backends", default="cpu,simd,opencl,glsl")
    ap.add_argument("--workloads", default="full,primary,multipass")
    ap.add_argument("--json", help="write every measurement here")
    ap.add_argument("--size", default=SIZE, help="image size WxH (default %(default)s)")
    a = ap.parse_args()
    SIZE = a.size
    backends = a.backends.split(",")
    workloads = a.workloads.split(",")
    rows = [(b, w) for b in backends for w in workloads]

    work = tempfile.mkdtemp(prefix="rill-speed-kept-")
    bins = {"before": os.path.abspath(a.before), "after": os.path.abspath(a.after)}
    envs = {k: private_env(os.path.join(work, k)) for k in bins}
    for k in bins:  # warm the private caches
        for b, w in rows:
            render(bins[k], envs[k], b, w, work, f"warm-{k}")

    times = {row: {"before": [], "after": []} for row in rows}
    identical = {row: True for row in rows}
    for rep in range(a.reps):
        order = ["before", "after"] if rep % 2 == 0 else ["after", "before"]
        for row in rows:
            pfms = {}
            for k in order:
                ms, pfms[k] = render(bins[k], envs[k], row[0], row[1], work, k)
                times[row][k].append(ms)
            same = subprocess.run(["cmp", "-s", pfms["before"], pfms["after"]]).returncode == 0
            identical[row] = identical[row] and same
        print(f"repeat {rep + 1}/{a.reps} done", file=sys.stderr)

    result = [{"backend": b, "workload": w, "before_ms": times[(b, w)]["before"],
               "after_ms": times[(b, w)]["after"], "identical": identical[(b, w)]}
              for b, w in rows]
    print_table(result, a.reps, SIZE)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"size": SIZE, "reps": a.reps, "rows": result}, f, indent=1)
    return 0 if all(identical.values()) else 1


def print_table(rows, reps, size):
    """The Markdown table of a run's rows (as written to --json)."""
    print(f"thesis-b {size}, trace_ms, {reps} alternating repeats per binary\n")
    print("| backend | workload | BEFORE median ms | AFTER median ms | AFTER/BEFORE "
          "| per-repeat ratio median (min..max) | min AFTER/min BEFORE | BEFORE spread ms "
          "| AFTER spread ms | images |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        tb, ta = r["before_ms"], r["after_ms"]
        mb, ma = statistics.median(tb), statistics.median(ta)
        ratios = [x / y for x, y in zip(ta, tb)]
        print(f"| {r['backend']} | {r['workload']} | {mb:.1f} | {ma:.1f} | {ma / mb:.3f} "
              f"| {statistics.median(ratios):.3f} ({min(ratios):.3f}..{max(ratios):.3f}) "
              f"| {min(ta) / min(tb):.3f} | {min(tb):.1f}..{max(tb):.1f} "
              f"| {min(ta):.1f}..{max(ta):.1f} "
              f"| {'identical' if r['identical'] else 'DIFFER'} |")


if __name__ == "__main__":
    sys.exit(main())
