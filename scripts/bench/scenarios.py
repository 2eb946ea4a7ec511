"""The benchmark's scenarios and the datasets they run on.

Simulated datasets are cached in the data folder, each keyed by the simulate
flags that made it (a .stamp file beside the folder holds them): a folder is
reused while its flags are unchanged and simulated again otherwise. The
loop-closed variant reuses the drift variant's scans and only simulates its
initial poses (`simulate --poses-only --loop-closed`).
"""
import os
import shlex
from dataclasses import dataclass, field
from pathlib import Path

FRAME_RATE_HZ = 10.0
SEED = 1
FULL_HDL32_FRAMES = (1000, 5000, 20000)
QUICK_HDL32_FRAMES = (100, 200)
HKU1_FRAMES = 314


def add_data_arguments(parser, repo):
    """--data-dir (where simulated datasets are cached), --hku1 and --nclt (the real sequences beside
    the repository)."""
    parser.add_argument("--data-dir", type=Path,
                        default=Path(os.environ.get("HBA_BENCH_DATA", "/work/hba-bench-data")))
    parser.add_argument("--hku1", type=Path, default=repo.parent / "shared/data/hku1")
    parser.add_argument("--nclt", type=Path, default=repo.parent / "shared/data/nclt")


@dataclass(frozen=True)
class Scenario:
    name: str
    sensor: str  # hdl32 | livox | real
    frames: int
    variant: str  # drift | loop | real

    def describe(self):
        return {"sensor": self.sensor, "frames": self.frames, "variant": self.variant,
                "duration_s": self.frames / FRAME_RATE_HZ}


def simulated(sensor, frames, variant):
    return Scenario(f"sim-{sensor}-{frames}-{variant}", sensor, frames, variant)


HKU1 = Scenario("hku1", "real", HKU1_FRAMES, "real")
NCLT = Scenario("nclt", "real", 1141, "real")
# nclt's twin with ground truth (issue #36): sparse VLP-16 scans along 1.1 km
# of KITTI 00's path, a good odometry; ten-scan windows do worse than it.
SPARSE_TWIN = Scenario("sim-vlp16-1500-sparse", "vlp16", 1500, "sparse")
SPARSE_TWIN_FLAGS = ["--downsample", "0.5", "--drift-translation", "0.002", "--drift-rotation", "0.002",
                     "--jitter-rotation", "0.02", "--jitter-translation", "0.005", "--noise", "0.03",
                     "--scene", "open"]


def scenario_set(quick):
    hdl32_frames, livox_frames = (QUICK_HDL32_FRAMES, 100) if quick else (FULL_HDL32_FRAMES, 1000)
    hdl32 = [simulated("hdl32", n, variant) for n in hdl32_frames for variant in ("drift", "loop")]
    sparse = [] if quick else [SPARSE_TWIN]
    return hdl32 + [simulated("livox", livox_frames, "drift"), HKU1] + sparse


@dataclass
class Inputs:
    """What optimize, eval and mme read for one scenario."""

    dataset: Path
    initial_poses: Path  # what the optimizer starts from
    pose_override: bool  # initial_poses is not the dataset's own trajectory
    ground_truth: Path = None
    commands: list = field(default_factory=list)  # what made the data

    def pose_args(self):
        return ["--poses", str(self.initial_poses), "--format", "hba"] if self.pose_override else []


class DataStore:
    def __init__(self, root, tools, hku1_dir, log, real_dirs=None):
        self.root = Path(root)
        self.tools = tools
        # Real sequences by scenario name (hku1's folder unless given).
        self.real_dirs = {"hku1": Path(hku1_dir), **{k: Path(v) for k, v in (real_dirs or {}).items()}}
        self.log = log

    def inputs(self, scenario):
        if scenario.variant == "real":
            folder = self.real_dirs[scenario.name]
            return Inputs(folder, folder / "odom_poses.txt", False)
        if scenario.variant == "sparse":
            # KITTI 00's path from the shared data beside hku1's folder.
            path = Path(self.real_dirs["hku1"]).parent / "trajectories" / "kitti00_gt.txt"
            twin = self._simulated(scenario.name,
                                   self._flags(scenario, ["--trajectory", str(path), *SPARSE_TWIN_FLAGS]))
            return Inputs(twin.folder, twin.folder / "pose.json", False, twin.folder / "gt.txt", [twin.command])
        scans = self._simulated(f"sim-{scenario.sensor}-{scenario.frames}",
                                self._flags(scenario, []))
        if scenario.variant == "drift":
            return Inputs(scans.folder, scans.folder / "pose.json", False,
                          scans.folder / "gt.txt", [scans.command])
        poses = self._simulated(f"sim-{scenario.sensor}-{scenario.frames}-loop-poses",
                                self._flags(scenario, ["--loop-closed", "--poses-only"]))
        return Inputs(scans.folder, poses.folder / "pose.json", True,
                      poses.folder / "gt.txt", [scans.command, poses.command])

    @staticmethod
    def _flags(scenario, extra):
        return ["--sensor", scenario.sensor, "--frames", str(scenario.frames), "--seed", str(SEED),
                *extra]

    def _simulated(self, name, flags):
        folder = self.root / name
        stamp = self.root / f"{name}.stamp"
        wanted = " ".join(flags) + "\n"
        argv = self.tools.simulate_argv(flags, folder)
        if not (folder.is_dir() and stamp.is_file() and stamp.read_text() == wanted):
            self.log(f"simulating {name} ({' '.join(flags)})")
            stamp.unlink(missing_ok=True)  # a half-made folder must never look current
            self.root.mkdir(parents=True, exist_ok=True)
            self.tools.simulate(flags, folder)
            stamp.write_text(wanted)
        return _Simulated(folder, shlex.join(argv))


@dataclass
class _Simulated:
    folder: Path
    command: str
