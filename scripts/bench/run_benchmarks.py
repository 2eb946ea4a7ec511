#!/usr/bin/env python3
"""hba's benchmark harness: times `hba optimize` on simulated and real sequences,
checks its accuracy, and rewrites the generated section of BENCHMARKS.md.

Raw numbers go to RESULTS_DIR/results.json, the plot to RESULTS_DIR/scaling.png.
Exits non-zero when a command fails or a run's ATE after optimization is worse
than before, after writing everything it measured. scripts/benchmark.sh builds
the tools first; see docs in BENCHMARKS.md and README.md ("Benchmarks").
"""
import argparse
import json
import os
import sys
import time
from pathlib import Path

import analysis
import machine
import plot
import report_md
from measure import measure_scenario
from process import CommandFailed
from scenarios import DataStore, scenario_set
from tools import Tools

REPO = Path(__file__).resolve().parents[2]
# Sequences up to this long are optimized 3 times by default (medians), longer ones once.
REPEATED_MAX_FRAMES = 1000


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].replace("\n", " "))
    parser.add_argument("--quick", action="store_true",
                        help="tiny scenarios (HDL-32 100/200 frames, Livox 100, hku1), one run each")
    parser.add_argument("--only", help="comma-separated scenario names to run, e.g. "
                                       "sim-hdl32-1000-drift,hku1 (the others keep their previous "
                                       "results)")
    parser.add_argument("--runs", type=int, help="optimize runs per scenario (default: 3 up to "
                                                 f"{REPEATED_MAX_FRAMES} frames, else 1; --quick: 1)")
    parser.add_argument("--data-dir", type=Path,
                        default=Path(os.environ.get("HBA_BENCH_DATA", "/work/hba-bench-data")),
                        help="simulated data and run outputs (default: $HBA_BENCH_DATA or "
                             "/work/hba-bench-data)")
    parser.add_argument("--hba", type=Path, default=REPO / "build/bin/hba", help="the hba tool")
    parser.add_argument("--io-floor", type=Path, default=REPO / "build/bin/io_floor",
                        help="the io_floor tool (bench/io)")
    parser.add_argument("--hku1", type=Path, default=REPO.parent / "shared/data/hku1",
                        help="the real hku1 sequence (skipped when absent)")
    parser.add_argument("--output", type=Path, default=REPO / "BENCHMARKS.md",
                        help="the Markdown file whose generated section is rewritten")
    parser.add_argument("--results-dir", type=Path, default=REPO / "bench/results",
                        help="where results.json and scaling.png go")
    parser.add_argument("--jobs", type=int, default=2, help="threads (-j) of every command")
    args = parser.parse_args(argv)
    if args.runs is not None and args.runs < 1:
        parser.error("--runs must be at least 1")
    args.data_dir = args.data_dir.resolve()  # commands name it in full; the report shortens it
    return args


class Progress:
    """Progress lines on stderr: which scenario, what step, time since the start."""

    def __init__(self):
        self.start = time.monotonic()
        self.scenario = ""

    def __call__(self, message):
        elapsed = int(time.monotonic() - self.start)
        print(f"[bench +{elapsed // 60:02d}:{elapsed % 60:02d}] {self.scenario}{message}",
              file=sys.stderr, flush=True)


def chosen_scenarios(scenarios, only):
    if not only:
        return scenarios
    names = [name.strip() for name in only.split(",") if name.strip()]
    known = {scenario.name for scenario in scenarios}
    unknown = [name for name in names if name not in known]
    if unknown:
        sys.exit(f"unknown scenario(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}")
    return [scenario for scenario in scenarios if scenario.name in names]


def runs_for(scenario, args):
    if args.runs:
        return args.runs
    return 1 if args.quick or scenario.frames > REPEATED_MAX_FRAMES else 3


def previous_records(results_json):
    try:
        return json.loads(results_json.read_text())["records"]
    except (OSError, ValueError, KeyError):
        return {}


def measure_all(args, scenarios, records, log):
    """Measures the chosen scenarios into records; returns {name: failure message}."""
    tools = Tools(args.hba, args.io_floor, args.jobs)
    store = DataStore(args.data_dir, tools, args.hku1, log)
    failures = {}
    chosen = chosen_scenarios(scenarios, args.only)
    for index, scenario in enumerate(chosen, start=1):
        log.scenario = f"{index}/{len(chosen)} {scenario.name}: "
        if scenario.variant in ("real", "sparse") and not args.hku1.is_dir():
            log(f"skipped: {args.hku1} not found")
            continue
        try:
            inputs = store.inputs(scenario)
            records[scenario.name] = measure_scenario(scenario, inputs, tools,
                                                      runs_for(scenario, args),
                                                      args.data_dir / "runs", log)
        except CommandFailed as failure:
            records.pop(scenario.name, None)  # an older figure would pass for a current one
            failures[scenario.name] = str(failure)
            print(f"FAILED: {scenario.name}: {failure}", file=sys.stderr, flush=True)
    log.scenario = ""
    return failures


def draw_plot(args, records, summaries, log):
    """Returns the plot's path, or None when gnuplot is missing."""
    png = args.results_dir / "scaling.png"
    if plot.draw(records, summaries, png):
        return png
    png.unlink(missing_ok=True)  # an older picture would no longer match the tables
    log("no plot: gnuplot is not installed (bash scripts/install_deps.sh --bench)")
    return None


def write_outputs(args, scenarios, records, failures, log):
    """results.json, the plot and BENCHMARKS.md; returns the accuracy regressions."""
    summaries = {name: analysis.summarize(record) for name, record in records.items()}
    description = machine.describe(args.hba.resolve().parents[1], REPO)
    args.results_dir.mkdir(parents=True, exist_ok=True)
    report_md.write_atomically(args.results_dir / "results.json", json.dumps(
        {"machine": description, "quick": args.quick, "jobs": args.jobs, "records": records,
         "failures": failures}, indent=2) + "\n")
    png = draw_plot(args, records, summaries, log)
    regressions = {name: analysis.accuracy_regressions(name, record)
                   for name, record in records.items()}
    data_dir, repo = str(args.data_dir), str(REPO) + "/"
    context = {
        "machine": description, "jobs": args.jobs, "quick": args.quick, "records": records,
        "summaries": summaries, "failures": failures,
        "regressed": {name for name, messages in regressions.items() if messages},
        "missing": [s.name for s in scenarios if s.name not in records and s.name not in failures],
        "plot": os.path.relpath(png, args.output.resolve().parent) if png else None,
        "shorten": lambda line: line.replace(data_dir, "$DATA").replace(repo, ""),
    }
    document = args.output.read_text(encoding="utf-8") if args.output.exists() else ""
    report_md.write_atomically(args.output, report_md.splice(document, report_md.render(context)))
    log(f"wrote {args.output}, {args.results_dir / 'results.json'}")
    return [message for messages in regressions.values() for message in messages]


def main(argv):
    args = parse_args(argv)
    log = Progress()
    scenarios = scenario_set(args.quick)
    previous = previous_records(args.results_dir / "results.json")
    # Keep the earlier figures of this set's other scenarios, in the set's order.
    records = {s.name: previous[s.name] for s in scenarios if s.name in previous}
    failures = measure_all(args, scenarios, records, log)
    records = {s.name: records[s.name] for s in scenarios if s.name in records}
    regressions = write_outputs(args, scenarios, records, failures, log)
    for message in regressions:
        print(message, file=sys.stderr)
    for name, message in failures.items():
        print(f"FAILED: {name}: {message}", file=sys.stderr)
    return 1 if regressions or failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
