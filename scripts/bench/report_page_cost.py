#!/usr/bin/env python3
"""What the report page costs: `hba optimize` with and without report.html on
the same data, runs interleaved, medians; the page's own time and size as the
run logs them, and the peak memory with and without it.

Writes a Markdown table to --output (.md) and the raw numbers to the .json
beside it. The page must stay within 30 MB at 1000 frames and within a tenth
of the run's time (issue #41).
"""
import argparse
import datetime
import json
import re
import shutil
import statistics
import sys
from pathlib import Path

import machine
import process
import report_md
from scenarios import add_data_arguments, HKU1, NCLT, DataStore, simulated
from tools import Tools

REPO = Path(__file__).resolve().parents[2]
PAGE_LINE = re.compile(r"report\.html: (\d+) points \(voxel ([\d.]+) m\), ([\d.]+) MB, in ([\d.]+) s")


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].replace("\n", " "))
    parser.add_argument("--hba", type=Path, default=REPO / "build/bin/hba")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--only", default="sim-hdl32-1000-drift,hku1,nclt")
    add_data_arguments(parser, REPO)
    parser.add_argument("--output", type=Path, default=REPO / "bench/results/report_page.md")
    parser.add_argument("--jobs", type=int, default=2)
    return parser.parse_args(argv)


def log(message):
    print(f"[report page] {message}", file=sys.stderr, flush=True)


def one_run(tools, inputs, out, page):
    shutil.rmtree(out, ignore_errors=True)
    # The log (stderr) goes to a file beside the output: it names the page's time and size.
    log_file = out.with_suffix(".log")
    log_file.parent.mkdir(parents=True, exist_ok=True)
    log_file.unlink(missing_ok=True)
    argv = [tools.hba, "-q", "--log-file", str(log_file), "-j", str(tools.jobs), "optimize", str(inputs.dataset),
            *inputs.pose_args(), "-o", str(out), "--no-render", "--force"] + ([] if page else ["--no-report-page"])
    _, usage = process.run(argv)
    run = {"wall_s": usage.wall_s, "peak_rss_mib": usage.peak_rss_mib}
    if page:
        text = log_file.read_text(encoding="utf-8", errors="replace")
        match = PAGE_LINE.search(text)
        if not match:
            raise process.CommandFailed(argv, "no 'report.html: ...' line in " + str(log_file), text)
        run.update(points=int(match.group(1)), voxel_m=float(match.group(2)), page_mb=float(match.group(3)),
                   page_s=float(match.group(4)), bytes=(out / "report.html").stat().st_size)
    return run


def median(runs, key):
    return statistics.median(run[key] for run in runs)


def row(name, frames, record):
    with_page, without = record["page"], record["no_page"]
    wall, wall0 = median(with_page, "wall_s"), median(without, "wall_s")
    page_s = median(with_page, "page_s")
    last = with_page[-1]
    return (f"| `{name}` | {frames} | {last['points'] / 1e6:.2f} M at {last['voxel_m']:.2f} m | "
            f"{last['bytes'] / 1e6:.1f} MB | {page_s:.2f} s | {wall0:.2f} s | {wall:.2f} s | "
            f"{100 * page_s / wall0:.1f} % | {100 * (wall - wall0) / wall0:.1f} % | "
            f"{median(without, 'peak_rss_mib'):.0f} → {median(with_page, 'peak_rss_mib'):.0f} |")


def main(argv):
    args = parse_args(argv)
    tools = Tools(args.hba, REPO / "build/bin/io_floor", args.jobs)
    store = DataStore(args.data_dir, tools, args.hku1, log, {"nclt": args.nclt})
    known = {s.name: s for s in [simulated("hdl32", 1000, "drift"), simulated("livox", 1000, "drift"), HKU1, NCLT]}
    records, lines = {}, []
    for name in [n.strip() for n in args.only.split(",") if n.strip()]:
        scenario = known[name]
        if scenario.variant == "real" and not store.real_dirs[name].is_dir():
            log(f"{name}: skipped ({store.real_dirs[name]} not found)")
            continue
        inputs = store.inputs(scenario)
        record = {"page": [], "no_page": []}
        for k in range(args.runs):
            for page in ((True, False) if k % 2 == 0 else (False, True)):
                log(f"{name}: run {k + 1}/{args.runs}, {'with' if page else 'without'} the page")
                key = "page" if page else "no_page"
                record[key].append(one_run(tools, inputs, args.data_dir / "report_page" / name / key, page))
        records[name] = record
        lines.append(row(name, scenario.frames, record))
    text = (f"Measured {datetime.datetime.now().astimezone().isoformat(timespec='minutes')}, `-j {args.jobs}`, "
            f"`hba optimize --no-render` with and without the page, medians of {args.runs} interleaved runs; "
            f"`{args.hba}`.\n\n"
            "| scenario | frames | points on the page | page size | page time (logged) | run without | "
            "run with | page / run | run's growth | peak RSS without → with (MiB) |\n"
            "|---|---|---|---|---|---|---|---|---|---|\n" + "\n".join(lines) + "\n")
    print(text)
    args.output.parent.mkdir(parents=True, exist_ok=True)
    report_md.write_atomically(args.output, text)
    report_md.write_atomically(args.output.with_suffix(".json"), json.dumps(
        {"machine": machine.describe(args.hba.resolve().parents[1], REPO), "records": records}, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
