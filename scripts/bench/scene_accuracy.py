#!/usr/bin/env python3
"""Accuracy of two builds of hba on the scene set, in one sitting.

The gate of every speed change (issue #13, item 3): each simulated scene
(city, indoor and open, a spinning HDL-32 and a solid-state Livox; a mixed
scene with three seeds; 5000 frames unless --no-long) is optimized by both
builds with the defaults and scored by its ATE against the ground truth;
hku1 and nclt, which have none, by their mean map entropy. Scenes are simulated once into --data-dir/scenes
(by build A, kept while their flags are unchanged). Prints a Markdown table
and writes it to --output.

  python3 scripts/bench/scene_accuracy.py --hba-a OLD/hba --hba-b NEW/hba
"""
import argparse
import datetime
import os
import sys
import tempfile
from pathlib import Path

from tools import Tools, add_build_arguments

REPO = Path(__file__).resolve().parents[2]
FRAMES = 400
SCENES = [(f"{scene}-{sensor}", ["--scene", scene, "--sensor", sensor, "--frames", str(FRAMES), "--seed", "1"])
          for scene in ("city", "indoor", "open") for sensor in ("hdl32", "livox")]
SCENES += [(f"mixed-hdl32-s{seed}", ["--sensor", "hdl32", "--frames", str(FRAMES), "--seed", str(seed)])
           for seed in (1, 2, 3)]
SCENES += [("mixed-livox-300", ["--sensor", "livox", "--frames", "300", "--seed", "1"])]
# A sequence long enough for several refinement blocks and the groups after
# them: what only long sequences use went 2.29 -> 3.85 mm unseen
# (docs/history/benchmarks.md, session 44). About two minutes a build.
LONG_SCENES = [("long-hdl32-5000", ["--sensor", "hdl32", "--frames", "5000", "--seed", "1"])]


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_build_arguments(parser)
    parser.add_argument("--data-dir", type=Path,
                        default=Path(os.environ.get("HBA_BENCH_DATA", "/work/hba-bench-data")))
    parser.add_argument("--real", nargs="*", type=Path,
                        default=[REPO.parent / "shared/data/hku1", REPO.parent / "shared/data/nclt"],
                        help="real sequences, scored by map entropy (skipped where absent)")
    parser.add_argument("--output", type=Path, default=REPO / "bench/results/scene_accuracy.md")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--long", action=argparse.BooleanOptionalAction, default=True,
                        help="also the 5000-frame sequence (several refinement blocks, the groups)")
    return parser.parse_args(argv)


def log(message):
    print(f"[scenes] {message}", file=sys.stderr, flush=True)


def simulated(tools, root, name, flags):
    """The scene's folder, simulated again only when its flags changed."""
    folder, stamp = root / name, root / f"{name}.stamp"
    wanted = " ".join(flags) + "\n"
    if not (folder.is_dir() and stamp.is_file() and stamp.read_text() == wanted):
        log(f"simulating {name}")
        stamp.unlink(missing_ok=True)
        root.mkdir(parents=True, exist_ok=True)
        tools.simulate(flags, folder)
        stamp.write_text(wanted)
    return folder


def main(argv):
    args = parse_args(argv)
    builds = [Tools(args.hba_a, "", args.jobs), Tools(args.hba_b, "", args.jobs)]
    scenes = args.data_dir.resolve() / "scenes"
    rows = []
    with tempfile.TemporaryDirectory(prefix="hba-scenes-") as scratch:
        work = Path(scratch)
        for name, flags in SCENES + (LONG_SCENES if args.long else []):
            folder = simulated(builds[0], scenes, name, flags)
            ates = []
            for k, tools in enumerate(builds):
                log(f"{name}: build {'AB'[k]}")
                out = work / f"{name}-{k}"
                tools.optimize(folder, [], out)
                ates.append(tools.eval(folder / "gt.txt", out / "pose.json", work / f"{name}-{k}.json"))
            rows.append((name, "ATE (mm)", *(1000.0 * a["ate_translation_m"] for a in ates)))
        for folder in args.real:
            if not folder.is_dir():
                log(f"{folder}: absent, skipped")
                continue
            mmes = []
            for k, tools in enumerate(builds):
                log(f"{folder.name}: build {'AB'[k]}")
                out = work / f"{folder.name}-{k}"
                tools.optimize(folder, [], out)
                mmes.append(tools.mme(folder, ["--poses", str(out / "pose.json"), "--format", "hba"]))
            rows.append((folder.name, "MME", *mmes))

    when = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="minutes")
    lines = [f"Measured {when}, `-j {args.jobs}`, one run per build and scene; "
             f"{args.label_a}: `{args.hba_a}`, {args.label_b}: `{args.hba_b}`.", "",
             f"| scene | metric | {args.label_a} | {args.label_b} |", "|---|---|---|---|"]
    for name, metric, a, b in rows:
        digits = 3 if metric.startswith("ATE") else 6
        lines.append(f"| `{name}` | {metric} | {a:.{digits}f} | {b:.{digits}f} |")
    table = "\n".join(lines) + "\n"
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(table, encoding="utf-8")
    print(table)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
