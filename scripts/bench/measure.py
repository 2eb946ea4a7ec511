"""Measures one scenario: the I/O floor, accuracy before, K optimize runs, accuracy after."""
import datetime
import os
import shutil

SCAN_VOXEL_M = 0.1  # optimize's default --downsample-scans: the floor reads what optimize reads
# The merged map's entropy grows costly with the sequence; above this many
# frames it is skipped and the report says so.
MME_MAX_FRAMES = 5000


def measure_scenario(scenario, inputs, tools, runs, work_dir, log):
    """Returns the raw record of one scenario (every number the report uses)."""
    tools.history.clear()
    record = {**scenario.describe(), "runs": [],
              "measured_at": datetime.datetime.now().astimezone().isoformat(timespec="minutes"),
              # Other work on the machine slows every figure: the report shows it.
              "load_average_1min": os.getloadavg()[0]}
    log("I/O floor")
    record["io_floor"] = tools.io_floor(inputs.dataset, SCAN_VOXEL_M)
    out = work_dir / scenario.name
    out.mkdir(parents=True, exist_ok=True)
    if inputs.ground_truth:
        record["accuracy_before"] = tools.eval(inputs.ground_truth, inputs.initial_poses,
                                               out / "eval_before.json")
    measure_mme = scenario.frames <= MME_MAX_FRAMES
    if measure_mme:
        log("MME before")
        record["mme_before"] = tools.mme(inputs.dataset, inputs.pose_args())
    optimized = out / "optimized"
    for k in range(1, runs + 1):
        log(f"optimize, run {k}/{runs}")
        record["runs"].append(_optimize_once(inputs, tools, optimized, out))
    if measure_mme:
        log("MME after")
        record["mme_after"] = tools.mme(inputs.dataset,
                                        ["--poses", str(optimized / "pose.json"), "--format", "hba"])
    record["commands"] = inputs.commands + tools.history
    return record


def _optimize_once(inputs, tools, optimized, out):
    shutil.rmtree(optimized, ignore_errors=True)  # each run starts from an absent folder
    usage, report = tools.optimize(inputs.dataset, inputs.pose_args(), optimized)
    run = {"wall_s": usage.wall_s, "cpu_s": usage.cpu_s, "peak_rss_mib": usage.peak_rss_mib,
           "stage_seconds": report.get("seconds", {}), "layers": report.get("layers")}
    if inputs.ground_truth:
        run["accuracy_after"] = tools.eval(inputs.ground_truth, optimized / "pose.json",
                                           out / "eval_after.json")
    return run
