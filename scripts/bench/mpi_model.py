#!/usr/bin/env python3
"""The cost of `mpirun -np K hba optimize`, modelled from measured runs.

From the report.json of a one-process run (per-layer wall times, windows,
keyframe points) and of the same run on two processes (the bytes they sent
each other) it models each layer on K processes: its windows split into K
ranges, so ceil(W / K) windows' time, plus the exchange after it. Each
window's summary goes to every process; a keyframe goes only to the process
whose next-layer windows read it: those across the edge of its range (as
many as the two-process run sent), all of them to the one process that runs
the top layer's window. The closure stage's verifications are spread evenly
(its seconds / K). The refinement is part spread (its planes' sums) and
part done by every process whole (reading a block's scans, the groups):
the part spread is what the two-process run saved, twice over, and it
divides among at most --chunks processes. What is not spread (reading, the
pose graph) runs in the first process, as measured, per frame. The model is checked against the
two-process run, then extrapolated to N scans: layer l has about
N / stride^(l-1) frames, its windows cost what they cost in the measured
run's layer (deeper layers as its deepest local one), the rest grows with N.

  python3 scripts/bench/mpi_model.py --one np1/report.json --many np2/report.json \\
      --frames 1000000 --processes 1,8,64
"""
import argparse
import json
import math

KEYFRAME_BYTES_PER_POINT = 16  # float x, y, z and intensity


def summary_bytes(frames):
    """A window's summary as window_exchange.cpp packs it: poses, one factor a
    neighbouring pair (indices, pose, 6x6 information), figures."""
    return 56 * frames + 360 * max(frames - 1, 0) + 150


def measured_layers(one, many):
    """Per layer: windows, per-window seconds, keyframe and summary bytes, and
    the keyframes a process gets from the others (measured on two)."""
    reports = one["layer_reports"]
    window = one["settings"]["window"]
    out = []
    for i, layer in enumerate(reports):
        windows = max(layer["windows"], 1)
        # This layer's keyframes are the next layer's clouds.
        keyframe = (reports[i + 1]["cloud_points"] / windows * KEYFRAME_BYTES_PER_POINT
                    if i + 1 < len(reports) else 0.0)
        summary = summary_bytes(min(window, layer["frames"]))
        crossing = 0.0
        if many and keyframe > 0:
            sent = many["layer_reports"][i]["exchange_bytes"]
            crossing = max(sent - windows * summary, 0.0) / keyframe
        out.append({"windows": layer["windows"], "per_window": layer["seconds"] / windows,
                    "keyframe": keyframe, "summary": summary, "crossing": crossing, "global": layer["global"]})
    return out


def layer_sent(layer, k, feeds_top):
    """The bytes a process sends after a layer on k processes: its windows'
    summaries to every other, its keyframes that others read."""
    if k == 1:
        return 0.0
    mine = math.ceil(layer["windows"] / k)
    return (k - 1) * mine * layer["summary"] + (mine if feeds_top else layer["crossing"]) * layer["keyframe"]


def layer_time(layer, k, feeds_top, bandwidth):
    """Seconds of a layer on k processes, and the bytes its busiest process receives."""
    t = math.ceil(layer["windows"] / k) * layer["per_window"]
    if k == 1:
        return t, 0.0
    received = (k - 1) * math.ceil(layer["windows"] / k) * layer["summary"]
    # The top layer's process gets every keyframe it does not hold; another
    # process, those its next windows read across its range's edge.
    received += ((k - 1) / k * layer["windows"] if feeds_top else layer["crossing"]) * layer["keyframe"]
    return t + received / bandwidth, received


def model(layers, k, bandwidth):
    times, received = [], []
    for i, layer in enumerate(layers):
        t, r = layer_time(layer, k, i + 2 == len(layers), bandwidth)
        times.append(t)
        received.append(r)
    return times, received


def extrapolate(layers, frames, window, stride):
    local = [l for l in layers if not l["global"]]
    top = [l for l in layers if l["global"]]
    out, n, level = [], frames, 0
    while n > window:
        windows = math.ceil(max(n - window, 0) / stride) + 1
        source = local[min(level, len(local) - 1)]
        # Deeper layers cross as many keyframes as the deepest measured one
        # that does not feed the top (which sends them all).
        crossing = max(l["crossing"] for l in local[:-1]) if len(local) > 1 else source["crossing"]
        out.append(dict(source, windows=windows, crossing=crossing if level >= len(local) - 1 else source["crossing"]))
        n = windows
        level += 1
    out.append(dict(top[0], windows=1) if top else {"windows": 1, "per_window": 0.0, "keyframe": 0.0,
                                                    "summary": 0.0, "global": True})
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--one", required=True, help="report.json of a one-process run")
    parser.add_argument("--many", help="report.json of the same run on two processes (a check, and bytes)")
    parser.add_argument("--frames", type=int, default=1_000_000)
    parser.add_argument("--processes", default="1,8,64")
    parser.add_argument("--bandwidth", type=float, default=1.25e9, help="bytes/s a process receives")
    parser.add_argument("--chunks", type=int, default=35,
                        help="chunks of a refinement block's sums (at most 64; 35 for 740-frame blocks)")
    args = parser.parse_args()
    one = json.load(open(args.one))
    many = json.load(open(args.many)) if args.many else None
    # The window and stride used (report.json's "windows"; the settings' stride 0 means automatic).
    used = one.get("windows", one["settings"])
    window, stride = used["window"], used["stride"]
    layers = measured_layers(one, many)
    layer_seconds = sum(l["seconds"] for l in one["layer_reports"])
    closures = one.get("closure", {}).get("seconds", 0.0)
    refinement = one.get("refinement", {}).get("seconds", 0.0)
    # The refinement's part spread: what two processes saved, twice over
    # (none when the two-process run's refinement ran in one process).
    spread = 0.0
    if many and many.get("processes", 1) == 2:
        spread = min(max(2.0 * (refinement - many.get("refinement", {}).get("seconds", refinement)), 0.0),
                     refinement)
    whole = refinement - spread
    rest = one["seconds"]["total"] - layer_seconds - closures - refinement
    n1 = one["frames"]

    def refinement_on(k, scale=1.0):
        return scale * (whole + spread / min(k, args.chunks))

    print(f"measured, one process: {one['seconds']['total']:.1f} s for {n1} frames; layers {layer_seconds:.1f} s, "
          f"closures {closures:.1f} s (spread), refinement {refinement:.1f} s ({spread:.1f} s of it spread), "
          f"the rest {rest:.1f} s ({1e3 * rest / n1:.1f} ms a frame, in the first process)")
    if many:
        k = many["processes"]
        times, _ = model(layers, k, args.bandwidth)
        measured = many["seconds"]["total"]
        modelled = sum(times) + closures / k + refinement_on(k) + rest
        print(f"check, {k} processes: modelled {modelled:.1f} s, measured {measured:.1f} s "
              f"({modelled / measured:.2f}); layers modelled " + ", ".join(f"{t:.2f}" for t in times)
              + " s, measured " + ", ".join(f"{l['seconds']:.2f}" for l in many["layer_reports"]) + " s")
        print("bytes sent after each layer: " + ", ".join(f"{l['exchange_bytes'] / 1e6:.1f} MB"
                                                        for l in many["layer_reports"])
              + "; a summary " + ", ".join(f"{l['summary'] / 1e3:.1f} kB" for l in layers)
              + ", a keyframe " + ", ".join(f"{l['keyframe'] / 1e3:.0f} kB" for l in layers)
              + ", keyframes crossing " + ", ".join(f"{l['crossing']:.1f}" for l in layers))
    big = extrapolate(layers, args.frames, window, stride)
    rest_big = rest / n1 * args.frames
    closures_big = closures / n1 * args.frames
    scale = args.frames / n1
    print(f"\nN = {args.frames} frames: {len(big)} layers, windows " + ", ".join(str(l["windows"]) for l in big))
    print("| processes | layers (s) | closures (s) | refinement (s) | the rest (s) | total (h) | speed-up | "
          "a process sends (GB) | the busiest receives (GB) |")
    print("|---|---|---|---|---|---|---|---|---|")
    base = None
    for k in [int(x) for x in args.processes.split(",")]:
        times, received = model(big, k, args.bandwidth)
        total = sum(times) + closures_big / k + refinement_on(k, scale) + rest_big
        base = base or total
        sent = sum(layer_sent(l, k, i + 2 == len(big)) for i, l in enumerate(big))
        print(f"| {k} | {sum(times):.0f} | {closures_big / k:.0f} | {refinement_on(k, scale):.0f} | "
              f"{rest_big:.0f} | {total / 3600:.2f} | "
              f"{base / total:.2f}x | "
              f"{sent / 1e9:.2f} | {sum(received) / 1e9:.1f} |")


if __name__ == "__main__":
    main()
