"""BENCHMARKS.md's generated section: rendering, and splicing it between its markers."""
import os
from pathlib import Path

import analysis
import measure

BEGIN = "<!-- benchmark-harness:begin -->"
END = "<!-- benchmark-harness:end -->"
# Stage keys of report.json's "seconds" in pipeline order; unknown keys follow, sorted.
STAGE_ORDER = ("read", "downsample", "load_and_downsample", "voxelize", "solve",
               "bundle_adjustment", "keyframes", "pose_graph", "total")
PASS, FAIL = "✅", "❌"


def seconds(value):
    return f"{value:.2f}" if value < 10 else f"{value:.1f}" if value < 1000 else f"{value:.0f}"


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines)


def _before_after(before, after, digits):
    return f"{before:.{digits}f} → {after:.{digits}f}"


def _machine(context):
    m = context["machine"]
    rows = [("CPU", f"{m['cpu']} ({m['cores']} cores)"), ("memory", m["memory"]),
            ("OS, kernel", f"{m['os']}, Linux {m['kernel']}"), ("compiler", m["compiler"]),
            ("build type", m["build_type"]), ("commit", f"`{m['commit']}`"),
            ("generated", m["date"]), ("threads", f"`-j {context['jobs']}` for every command")]
    return "### Machine\n\n" + table(("", ""), rows)


def _scenarios(context):
    rows = []
    for name, record in context["records"].items():
        poses = {"drift": "drift (simulated odometry)", "loop": "loop-closed (simulated)",
                 "real": "FAST-LIO2 odometry",
                 "sparse": "good odometry, sparse scans (simulated, nclt's twin)"}[record["variant"]]
        rows.append((f"`{name}`", record["sensor"], record["frames"],
                     f"{record['duration_s']:.0f} s", poses,
                     "yes" if "accuracy_before" in record else "no (MME only)"))
    commands = []
    for name, record in context["records"].items():
        commands.append(f"# {name}")
        commands += [context["shorten"](line) for line in record["commands"]]
    return ("### Scenarios\n\n"
            + table(("scenario", "sensor", "frames", "duration at 10 Hz", "initial poses",
                     "ground truth"), rows)
            + "\n\nThe exact commands, as run (`$DATA`: the data folder; the loop-closed variant"
              " reuses the drift variant's scans with `--poses-only` initial poses):\n\n"
              "<details><summary>commands</summary>\n\n```sh\n" + "\n".join(commands)
            + "\n```\n\n</details>")


def _time_and_memory(context):
    rows = []
    for name, record in context["records"].items():
        s = context["summaries"][name]
        rows.append((f"`{name}`", record["frames"], len(record["runs"]), seconds(s["wall_s"]),
                     seconds(s["cpu_s"]), f"{s['cpu_s'] / s['wall_s']:.2f}",
                     f"{s['peak_rss_mib']:.0f}", f"{s['per_frame_ms']:.1f}",
                     seconds(s["floor_s"]), f"{s['floor_ratio']:.1f}x",
                     f"{record['load_average_1min']:.1f}", record["measured_at"]))
    return ("### Time and memory of `hba optimize`\n\n"
            "Medians over the runs counted in `runs`; wall, CPU (user + system) and peak RSS of the"
            " optimize process (`wait4`). I/O floor: `io_floor`, reading and downsampling every"
            " scan once (0.1 m, as optimize) with the same threads. Load: the 1-minute load average"
            " as the scenario started (the harness's previous step included); figures taken at a"
            " load above the core count are pessimistic.\n\n"
            + table(("scenario", "frames", "runs", "wall (s)", "CPU (s)", "CPU / wall",
                     "peak RSS (MiB)", "ms / frame", "I/O floor (s)", "total / floor", "load",
                     "measured"), rows))


def _stage_keys(summaries):
    keys = {key for s in summaries.values() for key in s["stage_seconds"]}
    known = [key for key in STAGE_ORDER if key in keys]
    return known + sorted(keys - set(known))


def _stages(context):
    keys = _stage_keys(context["summaries"])
    rows = [(f"`{name}`", *(seconds(s["stage_seconds"][key]) if key in s["stage_seconds"] else "—"
                            for key in keys))
            for name, s in context["summaries"].items()]
    return ("### Time by stage (s, medians, from optimize's `report.json`)\n\n"
            + table(("scenario", *keys), rows))


def _accuracy_row(name, record, summary, regressed):
    if record["frames"] <= measure.MME_MAX_FRAMES:
        mme = _before_after(record["mme_before"], record["mme_after"], 3)
    else:
        mme = f"skipped (N > {measure.MME_MAX_FRAMES})"
    if "accuracy_before" not in record:
        return (f"`{name}`", "—", "—", "—", mme, "no ground truth")
    before, after = record["accuracy_before"], summary["accuracy_after"]
    gate = f"**{FAIL} ACCURACY REGRESSION**" if name in regressed else f"{PASS} better"
    return (f"`{name}`",
            _before_after(before["ate_translation_m"], after["ate_translation_m"], 4),
            _before_after(before["ate_rotation_deg"], after["ate_rotation_deg"], 3),
            _before_after(before["rpe_translation_m"], after["rpe_translation_m"], 4), mme, gate)


def _accuracy(context):
    rows = [_accuracy_row(name, record, context["summaries"][name], context["regressed"])
            for name, record in context["records"].items()]
    return ("### Accuracy before → after\n\n"
            "ATE and RPE: RMSE after SE(3) alignment (`hba eval`, RPE between consecutive"
            " frames), median over the runs. MME: `hba mme` (0.1 m map, lower = crisper); after ="
            " the last run's poses. The harness exits non-zero when any run's ATE after is worse"
            " than before.\n\n"
            + table(("scenario", "ATE (m)", "ATE rotation (deg)", "RPE (m)", "MME", "gate"), rows))


def _scaling(context):
    rows = []
    for variant in ("drift", "loop"):
        series = sorted((record["frames"], context["summaries"][name]["wall_s"])
                        for name, record in context["records"].items()
                        if record["sensor"] == "hdl32" and record["variant"] == variant)
        fit = analysis.scaling(series)
        per_frame = ", ".join(f"{n}: {1000 * t / n:.1f}" for n, t in series)
        if fit is None:
            rows.append((f"HDL-32, {variant}", per_frame or "—", "—", "—", "needs two sizes"))
            continue
        verdict = "linear" if fit["linear"] else "grows faster than N"
        rows.append((f"HDL-32, {variant}", per_frame, f"{fit['slope_s_per_1000_frames']:.1f}",
                     f"{fit['per_frame_growth']:.2f}x", verdict))
    return ("### Scaling with N\n\n"
            f"Per-frame time at the largest N over that at the smallest: within"
            f" {analysis.LINEAR_GROWTH_TOLERANCE:.2f}x counts as linear.\n\n"
            + table(("series", "ms / frame at N", "slope (s per 1000 frames)",
                     "per-frame growth", "verdict"), rows))


def _mark(passed):
    return PASS if passed else FAIL


def _targets(context):
    rows = []
    for name, record in context["records"].items():
        checks = analysis.target_checks(record, context["summaries"][name])
        time_s, budget_s, time_ok = checks["time"]
        rss, rss_limit, rss_ok = checks["memory"]
        ratio, ratio_limit, ratio_ok = checks["floor"]
        rows.append((f"`{name}`", f"{seconds(time_s)} s", f"{seconds(budget_s)} s", _mark(time_ok),
                     f"{rss / 1024:.2f} GiB", _mark(rss_ok), f"{ratio:.1f}x", _mark(ratio_ok)))
    return ("### Targets\n\n"
            "Time: below 5 % of the sequence's duration at 10 Hz on this machine. Memory: peak RSS"
            " below 4 GiB (the target is set for N = 20000; checked for every size). Floor: total"
            " within 3x the I/O floor.\n\n"
            + table(("scenario", "total", "5 % of duration", "time", "peak RSS", "< 4 GiB",
                     "total / I/O floor", "≤ 3x"), rows))


def _plot(context):
    if context["plot"] is None:
        return ("_No plot: gnuplot is not installed (`bash scripts/install_deps.sh --bench`"
                " installs it)._")
    return f"![Time and peak memory of hba optimize against N]({context['plot']})"


def _problems(context):
    parts = []
    if context["failures"]:
        parts.append("### Failed\n\n```\n" + "\n\n".join(
            f"{name}: {message}" for name, message in context["failures"].items()) + "\n```")
    if context["missing"]:
        parts.append("Not measured yet: " + ", ".join(f"`{name}`" for name in context["missing"]))
    return parts


def render(context):
    """The whole generated section, markers included."""
    header = ("## The whole method at scale (generated by `scripts/benchmark.sh`)\n\n"
              "Written by the benchmark harness between the `benchmark-harness` markers: edits"
              " here are lost at the next run. Regenerate with:\n\n```sh\n"
              "bash scripts/install_deps.sh --bench   # once: gnuplot-nox (the plot) and python3\n"
              f"bash scripts/benchmark.sh{' --quick' if context['quick'] else ''}\n```")
    if context["quick"]:
        header += ("\n\n**Quick run (`--quick`): tiny scenarios to try the harness, not the"
                   " N = 1000 / 5000 / 20000 set (`bash scripts/benchmark.sh`).**")
    parts = [header, _machine(context)]
    if context["records"]:
        parts += [_scenarios(context), _time_and_memory(context), _stages(context),
                  _accuracy(context), _scaling(context), _targets(context), _plot(context)]
    parts += _problems(context)
    return BEGIN + "\n" + "\n\n".join(parts) + "\n" + END


def splice(document, section):
    """document with its generated section replaced by section.

    The first time, the section goes after the introduction (before the first
    '## ' heading); the hand-written text around it is kept as it is.
    """
    if BEGIN in document and END in document:
        head, rest = document.split(BEGIN, 1)
        return head + section + rest.split(END, 1)[1]
    position = document.find("\n## ")
    if position < 0:
        return (document.rstrip("\n") + "\n\n" if document.strip() else "") + section + "\n"
    return document[:position + 1] + section + "\n\n" + document[position + 1:]


def write_atomically(path, text):
    path = Path(path)
    partial = path.with_name(f".{path.name}.partial-{os.getpid()}")
    partial.write_text(text, encoding="utf-8")
    os.replace(partial, path)
