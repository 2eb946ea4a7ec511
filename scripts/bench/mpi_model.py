#!/usr/bin/env python3
"""The cost of `mpirun -np K hba optimize`, modelled from measured runs.

From the report.json of a one-process run (per-layer wall times, windows,
keyframe points) it models the time of each layer on K processes: a layer's
windows split into K ranges, so ceil(W / K) windows' time, plus the exchange
after it (every process receives every window's keyframe and summary: the
bytes of the layer's message from an np-2 run, over a link of --bandwidth);
the stages that run in every process (closures, top layer, pose graph,
refinement, reading) as measured, per frame. It checks the model against a
measured K-process run, then extrapolates to N scans: layer l has about
N / stride^(l-1) frames, windows cost what they cost in the measured run's
layer (deeper layers as its deepest local one), the rest grows with N.

  python3 scripts/bench/mpi_model.py --one np1/report.json --many np2/report.json \
      --frames 1000000 --processes 1,8,64
"""
import argparse
import json
import math


def layer_figures(report):
    out = []
    for layer in report["layer_reports"]:
        out.append({"windows": layer["windows"], "frames": layer["frames"], "seconds": layer["seconds"],
                    "bytes": layer.get("exchange_bytes", 0), "global": layer["global"]})
    return out


def model_layers(layers, k, bandwidth):
    """Seconds of each layer on k processes, and the bytes each receives."""
    times, received = [], []
    for layer in layers:
        per_window = layer["seconds"] / max(layer["windows"], 1)
        t = math.ceil(layer["windows"] / k) * per_window
        # Each byte sent goes to about one process (the summaries, small, to all).
        r = layer["bytes"] / k if k > 1 else 0.0
        times.append(t + r / bandwidth)
        received.append(r)
    return times, received


def extrapolate(one, many, frames, window, stride):
    """The layers of an N-scan run, from the measured runs' per-window costs and bytes."""
    measured = layer_figures(one)
    bytes_per_window = [l["bytes"] / max(l["windows"], 1) for l in layer_figures(many)] if many else []
    local = [l for l in measured if not l["global"]]
    top = [l for l in measured if l["global"]]
    layers, n = [], frames
    level = 0
    while n > window:
        windows = math.ceil(max(n - window, 0) / stride) + 1
        source = local[min(level, len(local) - 1)]
        per_window = source["seconds"] / source["windows"]
        b = bytes_per_window[min(level, len(bytes_per_window) - 1)] if bytes_per_window else 0.0
        layers.append({"windows": windows, "frames": n, "seconds": windows * per_window,
                       "bytes": windows * b, "global": False})
        n = windows
        level += 1
    t = top[0]["seconds"] if top else 0.0
    layers.append({"windows": 1, "frames": n, "seconds": t, "bytes": 0.0, "global": True})
    return layers


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--one", required=True, help="report.json of a one-process run")
    parser.add_argument("--many", help="report.json of the same run on several processes (a check, and bytes)")
    parser.add_argument("--frames", type=int, default=1_000_000)
    parser.add_argument("--processes", default="1,8,64")
    parser.add_argument("--bandwidth", type=float, default=1.25e9, help="bytes/s each process receives")
    args = parser.parse_args()
    one = json.load(open(args.one))
    many = json.load(open(args.many)) if args.many else None
    window, stride = one["settings"]["window"], one["settings"]["stride"]
    layers = layer_figures(one)
    rest = one["seconds"]["total"] - sum(l["seconds"] for l in layers)
    n1 = one["frames"]
    print(f"measured, one process: {one['seconds']['total']:.1f} s for {n1} frames; "
          f"layers {sum(l['seconds'] for l in layers):.1f} s, the rest {rest:.1f} s "
          f"({1e3 * rest / n1:.1f} ms a frame, in every process)")
    if many:
        k = many["processes"]
        with_bytes = [dict(l, bytes=m["bytes"]) for l, m in zip(layers, layer_figures(many))]
        times, received = model_layers(with_bytes, k, args.bandwidth)
        measured = many["seconds"]["total"]
        modelled = sum(times) + rest
        print(f"check, {k} processes: modelled {modelled:.1f} s, measured {measured:.1f} s "
              f"({modelled / measured:.2f}); layers modelled "
              + ", ".join(f"{t:.2f}" for t in times) + " s, measured "
              + ", ".join(f"{l['seconds']:.2f}" for l in many["layer_reports"]) + " s")
        print("bytes exchanged after each layer (all processes' messages): "
              + ", ".join(f"{l['exchange_bytes'] / 1e6:.1f} MB" for l in many["layer_reports"]))
    big = extrapolate(one, many, args.frames, window, stride)
    rest_big = rest / n1 * args.frames
    print(f"\nN = {args.frames} frames: {len(big)} layers, windows "
          + ", ".join(str(l["windows"]) for l in big))
    print("| processes | layers (s) | the rest (s) | total (h) | speed-up | bytes each receives (GB) |")
    print("|---|---|---|---|---|---|")
    base = None
    for k in [int(x) for x in args.processes.split(",")]:
        times, received = model_layers(big, k, args.bandwidth)
        total = sum(times) + rest_big
        base = base or total
        print(f"| {k} | {sum(times):.0f} | {rest_big:.0f} | {total / 3600:.2f} | {base / total:.2f}x | "
              f"{sum(received) / 1e9:.1f} |")


if __name__ == "__main__":
    main()
