"""The commands the benchmark runs: hba (simulate, optimize, eval, mme) and io_floor."""
import json
import re
import shlex
import subprocess
from pathlib import Path

import process

MME_LINE = re.compile(r"^MME (\S+)", re.MULTILINE)


def add_build_arguments(parser):
    """--hba-a and --hba-b (two builds' hba, the baseline first) and their labels."""
    parser.add_argument("--hba-a", type=Path, required=True, help="the baseline build's hba")
    parser.add_argument("--hba-b", type=Path, required=True, help="the candidate build's hba")
    parser.add_argument("--label-a", default="A")
    parser.add_argument("--label-b", default="B")


class Tools:
    """Builds and runs the command lines; remembers each distinct one it ran, in order."""

    def __init__(self, hba, io_floor, jobs):
        self.hba = str(hba)
        self.io_floor_path = str(io_floor)
        self.jobs = jobs
        self.history = []

    def _hba(self, *args):
        return [self.hba, "-q", "-j", str(self.jobs), *map(str, args)]

    def _run(self, argv):
        line = shlex.join(argv)
        if line not in self.history:
            self.history.append(line)
        return process.run(argv)

    def simulate_argv(self, flags, output):
        return self._hba("simulate", *flags, "-o", output, "--force")

    def simulate(self, flags, output):
        self._run(self.simulate_argv(flags, output))

    def writes_report_page(self):
        """Whether this build writes report.html by default (it then has --no-report-page)."""
        if not hasattr(self, "_page_flag"):
            # Whatever the exit code (a wrapper may differ): the help text tells.
            help_text = subprocess.run([self.hba, "optimize", "--help"], capture_output=True, text=True,
                                       check=False, stdin=subprocess.DEVNULL)
            self._page_flag = "--no-report-page" in help_text.stdout + help_text.stderr
        return self._page_flag

    def optimize(self, dataset, pose_args, output, render=False):
        """Returns (Usage of the optimize process, its report.json). Without `render`, neither the
        picture nor the report page: the optimization alone, comparable with builds before either."""
        picture = [] if render else ["--no-render"] + (["--no-report-page"] if self.writes_report_page() else [])
        _, usage = self._run(self._hba("optimize", dataset, *pose_args, "-o", output, *picture, "--force"))
        with open(output / "report.json", encoding="utf-8") as report:
            return usage, json.load(report)

    def eval(self, ground_truth, estimate, json_path):
        """ATE and RPE (RMSE) of estimate against ground_truth."""
        self._run(self._hba("eval", "--gt", ground_truth, "--est", estimate, "--json", json_path, "--force"))
        with open(json_path, encoding="utf-8") as file:
            result = json.load(file)
        return {
            "ate_translation_m": result["ate"]["translation_m"]["rmse"],
            "ate_rotation_deg": result["ate"]["rotation_deg"]["rmse"],
            "rpe_translation_m": result["rpe"]["translation_m"]["rmse"],
            "rpe_rotation_deg": result["rpe"]["rotation_deg"]["rmse"],
        }

    def mme(self, dataset, pose_args):
        """Mean map entropy of the dataset's map with the given poses (lower = crisper)."""
        stdout, _ = self._run(self._hba("mme", dataset, *pose_args))
        match = MME_LINE.search(stdout)
        if not match:
            raise process.CommandFailed([self.hba, "mme", str(dataset)], "no 'MME <value>' line", stdout)
        return float(match.group(1))

    def io_floor(self, dataset, voxel):
        argv = [self.io_floor_path, str(dataset), "--voxel", str(voxel), "-j", str(self.jobs)]
        stdout, _ = self._run(argv)
        return json.loads(stdout)
