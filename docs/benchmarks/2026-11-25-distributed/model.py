#!/usr/bin/env python3
"""A model of the tile farm on N nodes, fitted to the H200 runs' --stats-json (issue 23).

Usage: model.py STATS_DIR OUT_DIR
  STATS_DIR: the JSON files of h200-model.sh (r{1,2,3}-8x2-*.json, seq-8x2.json, ...).
  OUT_DIR:   model.md (fit, check, predictions), model.svg and model.png (the plot; needs
             matplotlib: Debian's python3-matplotlib, under /usr/bin/python3).

What it models is the farm as built (apps/rill-trace/distributed/Farm.cpp): one queue at
rank 0, each rank holding two tiles, rank 0 handling the tiles that come back one at a
time. A node is the H200 host as measured: 8 ranks of 2 threads.

Fitted from the runs:
  - tile costs: a map of cost per pixel (from the 8x2 runs with tiles of 64: each tile's time
    over its pixels), plus a cost per launch c (least squares over tile sizes 64 and 128);
    the run-to-run spread of a tile's time, as log-normal noise;
  - rank 0's service time per tile back: s0 + bytes / B, from the `gather` figures of the
    runs with tiles of 64 and 128 (time from receiving a tile to having placed it and handed
    out the next);
  - an animation's tiles: seq-8x2.json's per_tile (24 frames of builtin:bounce at 1080p).
Assumed, not measured (one host only): the network between nodes, latency L and bandwidth
W per message, for 100 Gb/s InfiniBand (2 us, 12 GB/s) and 10 Gb Ethernet (30 us, 1.2 GB/s).

The simulation is event by event: ranks render their tiles back to back; a tile's pixels
reach rank 0 after L + bytes / W; rank 0 serves them in arrival order (s each), and its
answer (the next tile) reaches the rank after L. Rank 0 renders tiles too, without messages.
Efficiency at N nodes = (the work) / (8 N x the simulated time), where the work of a thesis C
frame is its cost in tiles of 128 (the one-node runs, which match one process within a few
per cent) and an animation's is the sum of its measured tiles.
"""
import glob
import heapq
import json
import math
import os
import random
import statistics
import sys

RANKS_PER_NODE = 8
AHEAD = 2  # tiles a rank holds (Farm.cpp, kAhead)
BYTES_PER_PIXEL = 3  # the PNG's 8-bit RGB, the only output of these runs


def load(path):
    with open(path) as f:
        return json.load(f)


def tiles_of(j):
    """[(x, y, w, h, frame, ms, rank)] of a run."""
    return [(t[3], t[4], t[5], t[6], t[7], t[2], t[1]) for t in j["distributed"]["per_tile"]]


def fit(stats):
    runs64 = [load(p) for p in sorted(glob.glob(f"{stats}/r*-8x2-t64-tail0.json"))]
    runs128 = [load(p) for p in sorted(glob.glob(f"{stats}/r*-8x2-t128-tail0.json"))]
    width, height = runs64[0]["width"], runs64[0]["height"]
    # Cost per pixel of each 64-pixel cell, the mean over the runs (ms at 2 threads).
    cells = {}
    for j in runs64:
        for x, y, w, h, _, ms, _ in tiles_of(j):
            cells.setdefault((x // 64, y // 64), []).append(ms / (w * h))
    cell_cost = {k: statistics.mean(v) for k, v in cells.items()}
    # The spread of one tile's time over the runs: the standard deviation of log(ms / mean).
    logs = []
    for k, v in cells.items():
        m = statistics.mean(v)
        logs += [math.log(x / m) for x in v if x > 0]
    sigma = statistics.pstdev(logs)

    def predicted(x, y, w, h):
        total = 0.0
        for cy in range(y // 64, (y + h - 1) // 64 + 1):
            for cx in range(x // 64, (x + w - 1) // 64 + 1):
                ox = min(x + w, (cx + 1) * 64) - max(x, cx * 64)
                oy = min(y + h, (cy + 1) * 64) - max(y, cy * 64)
                total += cell_cost[(cx, cy)] * ox * oy
        return total

    # A cost per launch: the 128-pixel tiles' times against the map's prediction of them
    # (which already holds one launch per 64-pixel tile: four per 128 tile).
    # ms128 = pred128 + c - 4c  ->  c = (pred128 - ms128) / 3, averaged.
    diffs = []
    for j in runs128:
        for x, y, w, h, _, ms, _ in tiles_of(j):
            launches_in_map = math.ceil(w / 64) * math.ceil(h / 64)
            if launches_in_map > 1:
                diffs.append((predicted(x, y, w, h) - ms) / (launches_in_map - 1))
    launch = max(0.0, statistics.mean(diffs))
    # Rank 0's service time: s = s0 + bytes / B through the two tile sizes' means.
    pts = []
    for j in runs64 + runs128:
        g = j["distributed"]["gather"]
        pts.append((g["bytes"] / g["tiles"], g["ms"] / g["tiles"]))
    b64 = [p for p in pts if p[0] < 20000]
    b128 = [p for p in pts if p[0] >= 20000]
    (x1, y1), (x2, y2) = [(statistics.mean(a for a, _ in v), statistics.mean(b for _, b in v)) for v in (b64, b128)]
    per_byte = max(0.0, (y2 - y1) / (x2 - x1))
    s0 = max(0.0, y1 - per_byte * x1)
    return {
        "width": width, "height": height, "cell_cost": cell_cost, "sigma": sigma,
        "launch_ms": launch, "s0_ms": s0, "per_byte_ms": per_byte,
        "predicted": predicted, "runs128": runs128, "runs64": runs64,
    }


def frame_tiles(model, tile, frames=1):
    """The tile costs (ms, bytes) of `frames` thesis C frames in tiles of `tile`."""
    out = []
    w, h = model["width"], model["height"]
    for _ in range(frames):
        for y in range(0, h, tile):
            for x in range(0, w, tile):
                tw, th = min(tile, w - x), min(tile, h - y)
                # The map holds one launch per 64-pixel cell; a tile is one launch.
                cells = math.ceil(tw / 64) * math.ceil(th / 64) if tile >= 64 else 1
                ms = model["predicted"](x, y, tw, th) - (cells - 1) * model["launch_ms"]
                if tile < 64:
                    ms += model["launch_ms"] * (1 - tw * th / 4096)
                out.append((ms, tw * th * BYTES_PER_PIXEL))
    return out


def simulate(model, tiles, nodes, latency_ms, bandwidth_bytes_per_ms, rng, noise=True,
             service_scale=1.0):
    """The farm's time for `tiles` [(ms, bytes)] in queue order on `nodes` nodes; rank 0's
    service time scaled by service_scale (a what-if)."""
    ranks = nodes * RANKS_PER_NODE
    queue = list(tiles)
    queue.reverse()  # pop() from the end: the front of the queue
    sigma = model["sigma"] if noise else 0.0
    s0, per_byte = model["s0_ms"] * service_scale, model["per_byte_ms"] * service_scale
    free_at = [0.0] * ranks  # when each rank's render thread is free
    events = []  # (time, kind, rank, bytes): 0 = a tile back at rank 0
    master_free = 0.0
    done_at = 0.0

    def assign(rank, at):
        # The rank gets the next tile at `at`; it starts once its thread is free.
        nonlocal done_at
        if not queue:
            return
        ms, nbytes = queue.pop()
        if sigma:
            ms *= math.exp(rng.gauss(-sigma * sigma / 2, sigma))
        start = max(at, free_at[rank])
        free_at[rank] = start + ms
        if rank == 0:
            heapq.heappush(events, (free_at[rank], 1, rank, 0))
        else:
            same_node = rank < RANKS_PER_NODE
            travel = 0.0 if same_node else latency_ms + nbytes / bandwidth_bytes_per_ms
            heapq.heappush(events, (free_at[rank] + travel, 0, rank, nbytes))

    for _ in range(AHEAD):
        for r in range(ranks):
            assign(r, 0.0)
    while events:
        t, kind, rank, nbytes = heapq.heappop(events)
        if kind == 1:  # rank 0's own tile: placed by rank 0's loop, no message
            done_at = max(done_at, t)
            assign(0, t)
            continue
        start = max(t, master_free)
        master_free = start + s0 + per_byte * nbytes
        done_at = max(done_at, master_free)
        same_node = rank < RANKS_PER_NODE
        assign(rank, master_free + (0.0 if same_node else latency_ms))
    return done_at


def efficiency(model, tiles, work, nodes, net, rng, reps=5, service_scale=1.0):
    """work: the workload's cost on one node without the farm's extra launches (so that
    smaller tiles pay for theirs)."""
    times = [simulate(model, tiles, nodes, net[0], net[1], rng, service_scale=service_scale)
             for _ in range(reps)]
    t = statistics.median(times)
    return work / (nodes * RANKS_PER_NODE * t), t


def main():
    stats, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    rng = random.Random(23)
    m = fit(stats)
    lines = ["# The farm model's fit and predictions (generated by model.py)", ""]
    lines += [
        f"- cost map: {len(m['cell_cost'])} cells of 64x64, mean "
        f"{statistics.mean(m['cell_cost'].values()) * 4096:.2f} ms per cell at 2 threads; "
        f"run-to-run spread of a tile (log sd) {m['sigma']:.3f}",
        f"- cost per launch: {m['launch_ms']:.3f} ms",
        f"- rank 0's service time per tile back: {m['s0_ms']:.3f} ms + "
        f"{m['per_byte_ms'] * 1e6:.3f} ms per MB "
        f"({m['s0_ms'] + m['per_byte_ms'] * 128 * 128 * 3:.3f} ms for a tile of 128)",
        "",
        "## Check: one node (8 ranks x 2 threads), against the runs",
        "",
        "| tiles | measured render ms (3 runs) | model ms (median of 5) |",
        "| ---: | --- | ---: |",
    ]
    for tile, runs in ((128, m["runs128"]), (64, m["runs64"])):
        measured = [round(j["time_ms"]["render"]) for j in runs]
        tiles = frame_tiles(m, tile)
        t = statistics.median(simulate(m, tiles, 1, 0, 1, rng) for _ in range(5))
        lines.append(f"| {tile} | {measured} | {t:.0f} |")
    # The animation: its own tiles, measured (tiles of 128 with the tail of 64).
    seq = load(f"{stats}/seq-8x2.json")
    seq_tiles = [(t[2], t[5] * t[6] * BYTES_PER_PIXEL) for t in
                 sorted(seq["distributed"]["per_tile"], key=lambda t: t[0])]
    t_seq = statistics.median(simulate(m, seq_tiles, 1, 0, 1, rng) for _ in range(5))
    lines.append(f"| bounce, 24 frames, 128 | [{round(seq['time_ms']['render'])}] | {t_seq:.0f} |")
    lines += ["", "## Predicted efficiency", ""]
    nets = {"100 Gb/s InfiniBand": (0.002, 12e6), "10 Gb Ethernet": (0.030, 1.2e6)}
    frame_work = sum(ms for ms, _ in frame_tiles(m, 128))
    seq_work = sum(ms for ms, _ in seq_tiles)
    workloads = {  # name: (tiles, work)
        "one 1080p frame, tiles of 128": (frame_tiles(m, 128), frame_work),
        "one 1080p frame, tiles of 64": (frame_tiles(m, 64), frame_work),
        "one 1080p frame, tiles of 32": (frame_tiles(m, 32), frame_work),
        "24 frames of bounce, tiles of 128": (seq_tiles, seq_work),
        "240 frames (thesis C), tiles of 128": (frame_tiles(m, 128, 240), 240 * frame_work),
        "240 frames (thesis C), tiles of 256": (frame_tiles(m, 256, 240), 240 * frame_work),
    }
    node_counts = [1, 2, 4, 8, 16, 32, 64, 128, 256]
    curves = {}
    header = "| workload | network | " + " | ".join(f"{n}" for n in (16, 64, 256)) + " |"
    lines += ["Nodes of 8 ranks x 2 threads; rank 0 as measured.", "", header,
              "| --- | --- | ---: | ---: | ---: |"]

    def row(name, tiles, work, net_name, net, scale=1.0):
        effs = [efficiency(m, tiles, work, n, net, rng, reps=3, service_scale=scale)[0]
                for n in node_counts]
        curves[(name, net_name)] = effs
        cells = [effs[node_counts.index(n)] for n in (16, 64, 256)]
        lines.append(f"| {name} | {net_name} | " + " | ".join(f"{e:.2f}" for e in cells) + " |")

    for name, (tiles, work) in workloads.items():
        for net_name, net in nets.items():
            row(name, tiles, work, net_name, net)
    # What would pay: rank 0 ten times quicker per tile (a queue per node that batches its
    # ranks' tiles, or a rank 0 that only serves), and whole frames per rank.
    ib = nets["100 Gb/s InfiniBand"]
    row("240 frames, tiles of 128, rank 0 10x quicker (what-if)",
        *workloads["240 frames (thesis C), tiles of 128"], "100 Gb/s InfiniBand", ib, 0.1)
    whole = frame_tiles(m, 4096, 240)  # a tile the size of the image: whole frames
    row("240 frames, whole frames per rank", whole, 240 * frame_work, "100 Gb/s InfiniBand", ib)
    with open(f"{out}/model.md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no matplotlib: no plot (apt-get install python3-matplotlib)")
        return
    fig, ax = plt.subplots(figsize=(8, 5))
    # InfiniBand only: the 10 GbE curves lie on them (rank 0's service time dominates).
    for (name, net_name), effs in curves.items():
        if not net_name.startswith("100"):
            continue
        ax.plot(node_counts, effs, "--" if "what-if" in name else "-", marker="o",
                markersize=3, label=name)
    ax.set_xscale("log", base=2)
    ax.set_xticks(node_counts)
    ax.set_xticklabels([str(n) for n in node_counts])
    ax.set_ylim(0, 1.05)
    ax.set_xlabel("nodes (8 ranks x 2 threads each)")
    ax.set_ylabel("parallel efficiency")
    ax.set_title("rill-trace tile farm: model fitted to the H200 runs (2026-11-25)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(f"{out}/model.svg")
    fig.savefig(f"{out}/model.png", dpi=80)
    print(f"wrote {out}/model.md, {out}/model.svg")


if __name__ == "__main__":
    main()
