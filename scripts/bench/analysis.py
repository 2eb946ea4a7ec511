"""Figures derived from the raw records: medians, targets, scaling, the accuracy gate."""
import statistics

TIME_BUDGET_FRACTION = 0.05  # of the sequence's duration
MEMORY_TARGET_MIB = 4 * 1024
FLOOR_RATIO_TARGET = 3.0
# Per-frame time at the largest N over that at the smallest: above this, cost grows faster than N.
LINEAR_GROWTH_TOLERANCE = 1.25


def median_of(runs, key):
    return statistics.median(run[key] for run in runs)


def summarize(record):
    """Medians over the runs of one scenario's record."""
    runs = record["runs"]
    wall_s = median_of(runs, "wall_s")
    stage_keys = {key for run in runs for key in run["stage_seconds"]}
    summary = {
        "wall_s": wall_s,
        "cpu_s": median_of(runs, "cpu_s"),
        "peak_rss_mib": median_of(runs, "peak_rss_mib"),
        "per_frame_ms": 1000.0 * wall_s / record["frames"],
        "floor_s": record["io_floor"]["seconds_wall"],
        "floor_ratio": wall_s / record["io_floor"]["seconds_wall"],
        "stage_seconds": {key: statistics.median(run["stage_seconds"][key] for run in runs
                                                 if key in run["stage_seconds"])
                          for key in stage_keys},
    }
    if "accuracy_before" in record:
        summary["accuracy_after"] = {
            metric: statistics.median(run["accuracy_after"][metric] for run in runs)
            for metric in record["accuracy_before"]}
    return summary


def target_checks(record, summary):
    """(measured, limit, passed) for each target, by name."""
    budget_s = TIME_BUDGET_FRACTION * record["duration_s"]
    floor_limit_s = FLOOR_RATIO_TARGET * summary["floor_s"]
    return {
        "time": (summary["wall_s"], budget_s, summary["wall_s"] < budget_s),
        "memory": (summary["peak_rss_mib"], MEMORY_TARGET_MIB,
                   summary["peak_rss_mib"] < MEMORY_TARGET_MIB),
        "floor": (summary["floor_ratio"], FLOOR_RATIO_TARGET, summary["wall_s"] <= floor_limit_s),
    }


def accuracy_regressions(name, record):
    """One message per run whose ATE after optimization is worse than before."""
    if "accuracy_before" not in record:
        return []
    before = record["accuracy_before"]["ate_translation_m"]
    return [f"ACCURACY REGRESSION: {name} ATE {before:.6g} -> {after:.6g} m (run {k})"
            for k, run in enumerate(record["runs"], start=1)
            if (after := run["accuracy_after"]["ate_translation_m"]) > before]


def scaling(points):
    """Least-squares slope of time against N, and how per-frame time changes with N.

    points: [(frames, seconds)] of one series, any order. Returns None for
    fewer than two sizes.
    """
    points = sorted(points)
    if len({frames for frames, _ in points}) < 2:
        return None
    slope_s_per_frame = statistics.linear_regression(*zip(*points)).slope
    (n_small, t_small), (n_large, t_large) = points[0], points[-1]
    growth = (t_large / n_large) / (t_small / n_small)
    return {"slope_s_per_1000_frames": 1000.0 * slope_s_per_frame,
            "per_frame_growth": growth,
            "linear": growth <= LINEAR_GROWTH_TOLERANCE}

