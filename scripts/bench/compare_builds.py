#!/usr/bin/env python3
"""Two builds of hba side by side in one sitting: the same scenarios, runs of
the two builds interleaved (A B, then B A, ...), medians and the ratios B / A.

Every speed claim should be such a ratio: the machine's speed drifts between
sittings by more than most changes gain. scripts/compare_builds.sh builds two
git revisions and calls this; it prints a Markdown table and writes it, with
the raw numbers, to --output (.md) and the .json beside it.
"""
import argparse
import datetime
import json
import os
import shutil
import statistics
import sys
from pathlib import Path

import machine
import report_md
from measure import MME_MAX_FRAMES, SCAN_VOXEL_M
from process import CommandFailed
from scenarios import add_data_arguments, HKU1, NCLT, SPARSE_TWIN, DataStore, scenario_set
from tools import Tools, add_build_arguments

REPO = Path(__file__).resolve().parents[2]
DEFAULT_SCENARIOS = "sim-hdl32-1000-drift,sim-hdl32-1000-loop,sim-livox-1000-drift,hku1,nclt"


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].replace("\n", " "))
    add_build_arguments(parser)
    parser.add_argument("--io-floor", type=Path, default=REPO / "build/bin/io_floor")
    parser.add_argument("--only", default=DEFAULT_SCENARIOS,
                        help=f"comma-separated scenarios (default {DEFAULT_SCENARIOS}; any of the "
                             "harness's, quick ones included)")
    parser.add_argument("--runs", type=int, default=3, help="optimize runs per build and scenario")
    parser.add_argument("--render", action="store_true",
                        help="also time one default run (with before_after.png) per build")
    add_data_arguments(parser, REPO)
    parser.add_argument("--output", type=Path, default=REPO / "bench/results/compare.md")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    if args.runs < 1:
        parser.error("--runs must be at least 1")
    args.data_dir = args.data_dir.resolve()
    return args


def log(message):
    print(f"[compare] {message}", file=sys.stderr, flush=True)


def chosen(names):
    known = {s.name: s for s in scenario_set(False) + scenario_set(True) + [HKU1, NCLT, SPARSE_TWIN]}
    wanted = [n.strip() for n in names.split(",") if n.strip()]
    unknown = [n for n in wanted if n not in known]
    if unknown:
        sys.exit(f"unknown scenario(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}")
    return [known[n] for n in wanted]


def one_run(tools, inputs, out, render):
    shutil.rmtree(out, ignore_errors=True)
    usage, report = tools.optimize(inputs.dataset, inputs.pose_args(), out, render=render)
    run = {"wall_s": usage.wall_s, "cpu_s": usage.cpu_s, "peak_rss_mib": usage.peak_rss_mib,
           "stage_seconds": report.get("seconds", {})}
    if inputs.ground_truth and not render:
        run["ate_m"] = tools.eval(inputs.ground_truth, out / "pose.json",
                                  out.parent / f"{out.name}_eval.json")["ate_translation_m"]
    return run


def measure(scenario, inputs, builds, runs, render, work):
    """Raw runs of both builds on one scenario, interleaved."""
    record = {"frames": scenario.frames, "load_average_1min": os.getloadavg()[0],
              "builds": {label: {"runs": []} for label in builds}}
    labels = list(builds)
    for k in range(runs):
        for label in (labels if k % 2 == 0 else labels[::-1]):
            log(f"{scenario.name}: {label}, run {k + 1}/{runs}")
            record["builds"][label]["runs"].append(
                one_run(builds[label], inputs, work / scenario.name / label, False))
    for label in labels:
        entry = record["builds"][label]
        if scenario.frames <= MME_MAX_FRAMES:
            poses = work / scenario.name / label / "pose.json"
            entry["mme"] = builds[label].mme(inputs.dataset, ["--poses", str(poses), "--format", "hba"])
        if render:
            log(f"{scenario.name}: {label}, with the picture")
            entry["render_run"] = one_run(builds[label], inputs, work / scenario.name / f"{label}-render", True)
    return record


def median(runs, key):
    values = [run[key] for run in runs if key in run]
    return statistics.median(values) if values else None


def fmt(value, digits=3):
    return "—" if value is None else f"{value:.{digits}g}"


def ratio(b, a):
    return "—" if a is None or b is None or a == 0 else f"{b / a:.2f}×"


def table(records, labels, floors):
    a, b = labels
    lines = [f"| scenario | frames | wall {a} (s) | wall {b} (s) | {b}/{a} | CPU {b}/{a} | "
             f"peak RSS {a} → {b} (MiB) | {b} ms/frame | {b} / I/O floor | ATE {a} → {b} (mm) | "
             f"MME {a} → {b} |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, record in records.items():
        ra, rb = (record["builds"][label]["runs"] for label in labels)
        wa, wb = median(ra, "wall_s"), median(rb, "wall_s")
        ca, cb = median(ra, "cpu_s"), median(rb, "cpu_s")
        ma, mb = median(ra, "peak_rss_mib"), median(rb, "peak_rss_mib")
        ate = [median(r, "ate_m") for r in (ra, rb)]
        ate_text = "—" if None in ate else f"{1000 * ate[0]:.3f} → {1000 * ate[1]:.3f}"
        mme = [record["builds"][label].get("mme") for label in labels]
        mme_text = "—" if None in mme else f"{mme[0]:.4f} → {mme[1]:.4f}"
        floor = floors.get(name)
        lines.append(f"| `{name}` | {record['frames']} | {fmt(wa)} | {fmt(wb)} | {ratio(wb, wa)} | "
                     f"{ratio(cb, ca)} | {ma:.0f} → {mb:.0f} | {1000 * wb / record['frames']:.1f} | "
                     f"{fmt(wb / floor if floor else None)} | {ate_text} | {mme_text} |")
    render_rows = [(name, record) for name, record in records.items()
                   if all("render_run" in record["builds"][label] for label in labels)]
    if render_rows:
        lines += ["", f"Default run (with `before_after.png`), one run each, against the median "
                      f"`--no-render` run of the same build:", "",
                  f"| scenario | {a}: picture / no picture (time) | {a}: peak RSS | "
                  f"{b}: picture / no picture (time) | {b}: peak RSS |", "|---|---|---|---|---|"]
        for name, record in render_rows:
            cells = []
            for label in labels:
                entry = record["builds"][label]
                plain = median(entry["runs"], "wall_s")
                pic = entry["render_run"]
                cells.append(f"{ratio(pic['wall_s'], plain)} | {pic['peak_rss_mib']:.0f} MiB "
                             f"(without: {median(entry['runs'], 'peak_rss_mib'):.0f})")
            lines.append(f"| `{name}` | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv):
    args = parse_args(argv)
    builds = {args.label_a: Tools(args.hba_a, args.io_floor, args.jobs),
              args.label_b: Tools(args.hba_b, args.io_floor, args.jobs)}
    # The data is made by the candidate build; both read the same files.
    store = DataStore(args.data_dir, builds[args.label_b], args.hku1, log, {"nclt": args.nclt})
    records, floors, failures = {}, {}, {}
    for scenario in chosen(args.only):
        if scenario.variant == "real" and not store.real_dirs[scenario.name].is_dir():
            log(f"{scenario.name}: skipped ({store.real_dirs[scenario.name]} not found)")
            continue
        try:
            inputs = store.inputs(scenario)
            floors[scenario.name] = builds[args.label_b].io_floor(inputs.dataset, SCAN_VOXEL_M)["seconds_wall"]
            records[scenario.name] = measure(scenario, inputs, builds, args.runs, args.render,
                                             args.data_dir / "compare")
        except CommandFailed as failure:
            failures[scenario.name] = str(failure)
            log(f"FAILED: {scenario.name}: {failure}")
    labels = [args.label_a, args.label_b]
    text = (f"Measured {datetime.datetime.now().astimezone().isoformat(timespec='minutes')}, "
            f"`-j {args.jobs}`, medians of {args.runs} interleaved runs per build; "
            f"{args.label_a}: `{args.hba_a}`, {args.label_b}: `{args.hba_b}`.\n\n"
            + table(records, labels, floors) + "\n")
    print(text)
    args.output.parent.mkdir(parents=True, exist_ok=True)
    report_md.write_atomically(args.output, text)
    report_md.write_atomically(args.output.with_suffix(".json"), json.dumps(
        {"machine": machine.describe(args.hba_b.resolve().parents[1], REPO), "labels": labels,
         "io_floor_s": floors, "records": records, "failures": failures}, indent=2) + "\n")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
