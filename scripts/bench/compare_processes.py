#!/usr/bin/env python3
"""Two builds of hba under `mpirun -np K` (one thread a process) in one
sitting: runs interleaved (A B, then B A, ...), medians of the whole run and
of its stages, and each run's pose.json digest (the poses must be those of
one process, for every K and both builds' own).

Writes a Markdown table to --output (.md) and the raw numbers beside it
(.json). Needs Open MPI's mpirun (scripts/install_deps.sh installs it).
"""
import argparse
import datetime
import hashlib
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from tools import add_build_arguments

REPO = Path(__file__).resolve().parents[2]


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].replace("\n", " "))
    add_build_arguments(parser)
    parser.add_argument("--data", type=Path, required=True, help="the dataset folder to optimize")
    parser.add_argument("--processes", default="1,2", help="comma-separated process counts K")
    parser.add_argument("--runs", type=int, default=3, help="runs per build and K")
    parser.add_argument("--output", type=Path, default=REPO / "bench/results/compare_processes.md")
    args = parser.parse_args(argv)
    if args.runs < 1:
        parser.error("--runs must be at least 1")
    args.counts = [int(k) for k in args.processes.split(",") if k.strip()]
    if not args.counts or min(args.counts) < 1:
        parser.error("--processes: counts of at least 1")
    for hba in (args.hba_a, args.hba_b):
        if not hba.is_file():
            parser.error(f"{hba}: no such build")
    if not args.data.is_dir():
        parser.error(f"{args.data}: no such dataset folder")
    if shutil.which("mpirun") is None:
        parser.error("mpirun not found (install libopenmpi-dev / openmpi-bin)")
    return args


def log(message):
    print(f"[processes] {message}", file=sys.stderr, flush=True)


def run_once(hba, processes, data, out):
    """One optimize under mpirun; its wall time, stages and poses' digest."""
    argv = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(processes), str(hba), "-q", "-j", "1",
            "optimize", str(data), "-o", str(out), "--no-render", "--no-report-page", "--force"]
    start = time.monotonic()
    done = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                          text=True, check=False)
    wall = time.monotonic() - start
    if done.returncode != 0:
        tail = "\n".join(done.stdout.strip().splitlines()[-15:])
        raise RuntimeError(f"command failed ({done.returncode}): {' '.join(argv)}\n{tail}")
    report = json.loads((out / "report.json").read_text(encoding="utf-8"))
    layers = sum(layer["seconds"] for layer in report["layer_reports"])
    return {
        "wall_s": wall,
        "closures_s": report["closure"]["seconds"],
        "layers_s": layers,
        "refinement_s": report["refinement"]["seconds"],
        "processes": report["processes"],
        "poses_md5": hashlib.md5((out / "pose.json").read_bytes()).hexdigest()[:8],
    }


def median(runs, key):
    return statistics.median(run[key] for run in runs)


def main(argv):
    args = parse_args(argv)
    builds = [(args.label_a, args.hba_a), (args.label_b, args.hba_b)]
    results = {label: {k: [] for k in args.counts} for label, _ in builds}
    with tempfile.TemporaryDirectory(prefix="hba-processes-") as scratch:
        for r in range(args.runs):
            for k in args.counts:
                order = builds if r % 2 == 0 else builds[::-1]
                for label, hba in order:
                    log(f"run {r + 1}/{args.runs}, {k} process(es), build {label}")
                    results[label][k].append(run_once(hba, k, args.data, Path(scratch) / "out"))
    when = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="minutes")
    lines = [f"Measured {when}: `mpirun -np K hba -q -j 1 optimize {args.data.name} --no-render "
             f"--no-report-page`, {args.runs} interleaved runs per build and K, medians (s); "
             f"{args.label_a}: `{args.hba_a}`, {args.label_b}: `{args.hba_b}`.", "",
             "| build | K | wall | closures | layers | refinement | wall / K = 1 | `pose.json` md5 |",
             "|---|---|---|---|---|---|---|---|"]
    for label, _ in builds:
        one = median(results[label][args.counts[0]], "wall_s")
        for k in args.counts:
            runs = results[label][k]
            digests = sorted({run["poses_md5"] for run in runs})
            lines.append(f"| {label} | {k} | {median(runs, 'wall_s'):.2f} | {median(runs, 'closures_s'):.2f} | "
                         f"{median(runs, 'layers_s'):.2f} | {median(runs, 'refinement_s'):.2f} | "
                         f"{median(runs, 'wall_s') / one:.2f} | {', '.join(digests)} |")
    table = "\n".join(lines) + "\n"
    print(table)
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(table, encoding="utf-8")
    args.output.with_suffix(".json").write_text(json.dumps(
        {"measured": when, "data": str(args.data), "builds": {label: str(hba) for label, hba in builds},
         "runs": {label: {str(k): v for k, v in per.items()} for label, per in results.items()}},
        indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
