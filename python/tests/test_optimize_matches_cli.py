"""hba.optimize on numpy arrays gives the poses `hba optimize` writes for the same files."""
import json
import os
import pathlib
import tempfile
import unittest

import numpy as np

import hba
from support import main, run_cli, scan_paths, simulate


class CliRunCase(unittest.TestCase):
    """40 simulated frames in a temporary folder, and `hba -j 1 optimize` of them with cli_args."""
    cli_args = ()

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.data = simulate(cls.tmp.name, frames=40, seed=3)
        cls.write_inputs()
        cls.out = os.path.join(cls.tmp.name, "out")
        run_cli("-j", "1", "optimize", cls.data, "-o", cls.out, "--no-render", *cls.cli_args)
        cls.cli_poses = hba.read_poses(os.path.join(cls.out, "pose.json"))
        with open(os.path.join(cls.out, "report.json")) as f:
            cls.cli_report = json.load(f)

    @classmethod
    def write_inputs(cls):
        pass

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()


class OptimizeMatchesCli(CliRunCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.scans = [hba.read_scan(path) for path in scan_paths(cls.data)]
        cls.initial = hba.read_poses(os.path.join(cls.data, "pose.json"))

    def test_arrays_give_the_cli_poses(self):
        result = hba.optimize(self.scans, self.initial, threads=1)
        self.assertEqual(result.poses.shape, (40, 4, 4))
        self.assertEqual(result.poses.dtype, np.float64)
        # The optimization moved the poses: returning the input would not pass.
        self.assertGreater(np.abs(result.poses - self.initial).max(), 1e-3)
        self.assertLess(np.abs(result.poses - self.cli_poses).max(), 1e-9)
        self.assertEqual(result.report["settings"], self.cli_report["settings"])
        self.assertEqual(result.report["layers"], self.cli_report["layers"])
        self.assertEqual(result.report["threads"], 1)

    def test_the_hierarchys_own_poses_are_given(self):
        result = hba.optimize(self.scans, self.initial, threads=1, refine=False)
        self.assertEqual(result.hierarchy_poses.shape, (40, 4, 4))
        # Without the refinement the run's poses are the hierarchy's, kept
        # by the self-check (the simulation drifts: the hierarchy moved it).
        self.assertFalse(result.report["consistency"]["hierarchy_rejected"])
        self.assertTrue(np.array_equal(result.hierarchy_poses, result.poses))
        self.assertGreater(np.abs(result.hierarchy_poses - self.initial).max(), 1e-3)
        refined = hba.optimize(self.scans, self.initial, threads=1)
        self.assertTrue(np.array_equal(refined.hierarchy_poses, result.hierarchy_poses))
        self.assertGreater(np.abs(refined.poses - refined.hierarchy_poses).max(), 1e-6)

    def test_dataset_gives_the_cli_poses(self):
        dataset = hba.open_dataset(self.data)
        result = hba.optimize(dataset, dataset.poses, threads=1)
        self.assertLess(np.abs(result.poses - self.cli_poses).max(), 1e-9)

    def test_a_list_of_matrices_is_taken_too(self):
        result = hba.optimize(self.scans[:20], list(self.initial[:20]), threads=1, refine=False)
        self.assertEqual(result.poses.shape, (20, 4, 4))
        self.assertFalse(result.report["refinement"]["ran"])

    def test_a_folder_name_is_not_scans(self):
        with self.assertRaisesRegex(hba.Error, "pass hba.open_dataset"):
            hba.optimize(self.data, self.initial)
        with self.assertRaisesRegex(hba.Error, r"scans\[1\]: expected an \(N, 3\) or \(N, 4\) array"):
            hba.optimize([self.scans[0], self.scans[1][:, :2]], self.initial[:2])

    def test_pose_count_must_match_scan_count(self):
        with self.assertRaisesRegex(hba.Error, "pose"):
            hba.optimize(self.scans, self.initial[:-1], threads=1)


class LoopsAndPriorsMatchCli(CliRunCase):
    """Loop pairs and position priors read by the tool's own call."""

    @classmethod
    def write_inputs(cls):
        cls.loops = os.path.join(cls.tmp.name, "loops.txt")
        with open(cls.loops, "w") as f:
            f.write("# i j\n2 14\n")
        # The true position of every tenth frame, 0.5 m sigma.
        cls.priors = os.path.join(cls.tmp.name, "priors.txt")
        with open(os.path.join(cls.data, "gt.txt")) as gt, open(cls.priors, "w") as out:
            for i, line in enumerate(l for l in gt if not l.startswith("#")):
                if i % 10 == 0:
                    out.write(" ".join(line.split()[:4]) + " 0.5\n")
        cls.cli_args = ("--loops", cls.loops, "--priors", cls.priors)

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.cli_closure = cls.cli_report["closure"]

    def test_files_give_the_cli_poses_and_closures(self):
        self.assertEqual(self.cli_closure["loops_used"], 1)  # a loop the planes verify
        self.assertEqual(self.cli_closure["priors_used"], 4)
        dataset = hba.open_dataset(self.data)
        result = hba.optimize(dataset, dataset.poses, loops=self.loops, priors=pathlib.Path(self.priors),
                              threads=1)
        self.assertLess(np.abs(result.poses - self.cli_poses).max(), 1e-9)
        for key in ("loops_given", "loops_used", "priors_given", "priors_used", "verified"):
            self.assertEqual(result.report["closure"][key], self.cli_closure[key], key)

    def test_without_files_none_is_given(self):
        dataset = hba.open_dataset(self.data)
        result = hba.optimize(dataset, dataset.poses, threads=1)
        self.assertEqual(result.report["closure"]["priors_given"], 0)
        self.assertEqual(result.report["closure"]["loops_given"], 0)

    def test_priors_need_stamps_and_bad_files_are_named(self):
        scans = [hba.read_scan(path) for path in scan_paths(self.data)]
        initial = hba.read_poses(os.path.join(self.data, "pose.json"))
        with self.assertRaisesRegex(hba.Error, "priors: .*no stamps.*hba.open_dataset"):
            hba.optimize(scans, initial, priors=self.priors)
        result = hba.optimize(scans, initial, loops=self.loops, threads=1, refine=False)
        self.assertEqual(result.report["closure"]["loops_given"], 1)
        bad = os.path.join(self.tmp.name, "bad_loops.txt")
        with open(bad, "w") as f:
            f.write("2 400\n")
        with self.assertRaisesRegex(hba.Error, "bad_loops.txt"):
            hba.optimize(scans, initial, loops=bad)
        with self.assertRaisesRegex(hba.Error, "loops: expected a file name"):
            hba.optimize(scans, initial, loops=3)


class SessionsMatchCli(unittest.TestCase):
    """Two sessions in their own frames: placed and optimized by the tool's own calls."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.data = os.path.join(cls.tmp.name, "sessions")
        run_cli("simulate", "--sessions", 2, "--frames", 60, "--seed", 5, "-o", cls.data)
        cls.dirs = [os.path.join(cls.data, "session-%d" % k) for k in range(2)]
        cls.out = os.path.join(cls.tmp.name, "out")
        run_cli("-j", "1", "optimize", *cls.dirs, "-o", cls.out, "--no-render")
        cls.cli_poses = np.concatenate(
            [hba.read_poses(os.path.join(cls.out, "session-%d" % k, "pose.json")) for k in range(2)])
        with open(os.path.join(cls.out, "report.json")) as f:
            cls.cli_report = json.load(f)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_registered_sessions_give_the_cli_poses(self):
        datasets = [hba.open_dataset(d) for d in self.dirs]
        result = hba.optimize_sessions(datasets, threads=1)
        self.assertEqual(result.poses.shape, (120, 4, 4))
        self.assertLess(np.abs(result.poses - self.cli_poses).max(), 1e-9)
        self.assertEqual([s["first_frame"] for s in result.report["sessions"]],
                         [s["first_frame"] for s in self.cli_report["sessions"]])
        ours, theirs = result.report["alignment"], self.cli_report["alignment"]
        self.assertEqual(ours["method"], "register")
        self.assertTrue(ours["registered"][0]["found"])
        self.assertEqual(ours["registered"][0]["agreeing"], theirs["registered"][0]["agreeing"])
        # The second session really was moved into the first one's frame.
        second = datasets[1].poses
        self.assertGreater(np.abs(result.poses[60:, :3, 3] - second[:, :3, 3]).max(), 1.0)

    def test_placement_given_or_refused(self):
        datasets = [hba.open_dataset(d) for d in self.dirs]
        identity = hba.optimize_sessions(datasets, align="identity", refine=False, threads=1)
        self.assertEqual(identity.report["alignment"]["method"], "identity")
        given = hba.optimize_sessions(datasets, align=[np.eye(4)], refine=False, threads=1)
        self.assertLess(np.abs(given.poses - identity.poses).max(), 1e-12)
        self.assertEqual(given.report["alignment"]["method"], "given")
        with self.assertRaisesRegex(hba.Error, "align: 2 transforms for 1 later sessions"):
            hba.optimize_sessions(datasets, align=[np.eye(4), np.eye(4)])
        with self.assertRaisesRegex(hba.Error, "align: 'nearest' is none of"):
            hba.optimize_sessions(datasets, align="nearest")
        with self.assertRaisesRegex(hba.Error, "two sessions or more"):
            hba.optimize_sessions(datasets[:1])
        with self.assertRaisesRegex(hba.Error, r"datasets\[1\]: expected an hba.Dataset"):
            hba.optimize_sessions([datasets[0], self.dirs[1]])


if __name__ == "__main__":
    main()
