#!/usr/bin/env python3
"""Where the time of one `hba optimize` run goes, by part of the method.

Samples the run with `perf record` (no call graphs: each sample is charged to
the function it was taken in), then sums the samples of each function into
the part of the method it belongs to (PARTS below, first match wins) and
prints a Markdown table of CPU seconds and shares; --output writes it with
the raw per-function figures beside it (.json). Run it on two builds to say
where a change moved the time (issue #40's "before/after profile").

  python3 scripts/bench/profile_parts.py --hba build/bin/hba DATASET [--flags "--no-refine ..."]
"""
import argparse
import json
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from tools import Tools

# (part, pattern on "dso symbol"), first match wins: the plane extraction's
# names come before TBB's, whose task names carry the lambda's function.
PARTS = [
    ("kernel and memory (page faults, zeroing, copies)",
     r"\[kernel|\[k\]|memset|memcpy|memmove|clear_page"),
    ("plane extraction: cells, octree, plane test, clusters",
     r"numberRange|assignCells|coarsenCells|membersOf|momentsOf|OctreeSplitter|planesOfCells|"
     r"placeInWorld|frameRunAt|seenByFrames|extractPlanes|pointIndicesPerScan|keepBestPlanes|"
     r"associationOf|CellTable|covarianceEigenvalues|symmetricEigenvalues|FrameCluster::FrameCluster|"
     r"SelfAdjointEigenSolver<Eigen::Matrix<double, 3, 3"),
    ("plane cost and derivatives (LM)",
     r"toWorld|planeTerms|addPlane|planeCost|planeScatter|linearize|FactoredSystem::FactoredSystem|"
     r"FactoredSystem::dense|PlaneProblem|PlaneObservation"),
    ("linear solve (CG products, factorizations)",
     r"FactoredSystem::multiply|solveDamped|LLT|LDLT|Cholesky|positiveInverse|gebp|gemm|"
     r"general_matrix|triangular_solve"),
    ("reading and downsampling scans", r"downsample|readPcd|Pcd|pcd|decode|ScanSource|parse|appendFinitePoints"),
    ("keyframes", r"buildKeyframe|addVoxels|keyframe"),
    ("loop closures", r"closure::"),
    ("pose graph (Ceres)", r"ceres|graph::"),
    ("rotations (SO(3) Exp and Log: priors, updates, features)", r"atan2|sincos|so3Exp|so3Log|se3Exp|se3Log"),
    ("malloc and free", r"malloc|free|_int_|unlink_chunk|cfree|operator new|operator delete"),
    ("threads (TBB scheduling, waiting)", r"tbb|pthread|futex|sched"),
]
SAMPLE_LINE = re.compile(r"^\s*([\d.]+)%\s+(\d+)\s+(\S+)\s+(.*)$")


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--hba", type=Path, required=True, help="the build's hba")
    parser.add_argument("dataset", type=Path)
    parser.add_argument("--flags", default="", help="more flags for hba optimize, in one string")
    parser.add_argument("--frequency", type=int, default=499, help="samples a second a thread")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--label", default=None, help="the build's name in the table (default: the path)")
    parser.add_argument("--output", type=Path, help="write the table here (.md) and the figures beside (.json)")
    return parser.parse_args(argv)


def part_of(dso, symbol):
    text = f"{dso} {symbol}"
    for name, pattern in PARTS:
        if re.search(pattern, text):
            return name
    return "other"


def sample(args, folder):
    data = folder / "perf.data"
    # Without the report page where the build has one, as the other timings.
    page_flag = ["--no-report-page"] if Tools(args.hba, "", args.jobs).writes_report_page() else []
    command = ["perf", "record", "-q", "-F", str(args.frequency), "-o", str(data), "--",
               str(args.hba), "optimize", str(args.dataset), "-o", str(folder / "out"), "--force",
               "--no-render", *page_flag, "-j", str(args.jobs), *shlex.split(args.flags)]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"profile_parts: the sampled run failed ({run.returncode}):\n{run.stderr[-2000:]}")
    report = subprocess.run(["perf", "report", "-i", str(data), "--no-children", "-q", "-n", "--stdio",
                             "--sort", "dso,sym"], capture_output=True, text=True, check=True)
    functions = []
    for line in report.stdout.splitlines():
        match = SAMPLE_LINE.match(line)
        if match:
            _, count, dso, symbol = match.groups()
            symbol = symbol.removeprefix("[.] ").removeprefix("[k] ").strip()
            functions.append({"dso": dso, "symbol": symbol, "samples": int(count)})
    wall = json.loads((folder / "out" / "report.json").read_text())["seconds"]["total"]
    return functions, wall


def table(functions, wall, frequency, label):
    parts = {}
    for f in functions:
        parts.setdefault(part_of(f["dso"], f["symbol"]), 0)
        parts[part_of(f["dso"], f["symbol"])] += f["samples"]
    total = sum(parts.values())
    order = [name for name, _ in PARTS] + ["other"]
    lines = [f"{label}: wall {wall:.1f} s, {total / frequency:.1f} CPU s sampled",
             "", "| part | CPU s | share |", "|---|---|---|"]
    for name in order:
        if name in parts:
            lines.append(f"| {name} | {parts[name] / frequency:.1f} | {100.0 * parts[name] / total:.0f} % |")
    return "\n".join(lines) + "\n", parts


def main(argv):
    args = parse_args(argv)
    if not shutil.which("perf"):
        sys.exit("profile_parts: perf is not installed (Debian: linux-perf)")
    with tempfile.TemporaryDirectory(prefix="hba-profile-") as tmp:
        functions, wall = sample(args, Path(tmp))
    text, parts = table(functions, wall, args.frequency, args.label or str(args.hba))
    print(text)
    if args.output:
        args.output.parent.mkdir(parents=True, exist_ok=True)
        args.output.write_text(text)
        top = sorted(functions, key=lambda f: -f["samples"])[:60]
        args.output.with_suffix(".json").write_text(json.dumps(
            {"hba": str(args.hba), "dataset": str(args.dataset), "frequency": args.frequency,
             "wall_s": wall, "parts_samples": parts, "top_functions": top}, indent=1) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
