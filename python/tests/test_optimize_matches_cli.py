"""hba.optimize on numpy arrays gives the poses `hba optimize` writes for the same files."""
import json
import os
import tempfile
import unittest

import numpy as np

import hba
from support import main, run_cli, scan_paths, simulate


class OptimizeMatchesCli(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.data = simulate(cls.tmp.name, frames=40, seed=3)
        cls.out = os.path.join(cls.tmp.name, "out")
        run_cli("-j", "1", "optimize", cls.data, "-o", cls.out, "--no-render")
        cls.cli_poses = hba.read_poses(os.path.join(cls.out, "pose.json"))
        with open(os.path.join(cls.out, "report.json")) as f:
            cls.cli_report = json.load(f)
        cls.scans = [hba.read_scan(path) for path in scan_paths(cls.data)]
        cls.initial = hba.read_poses(os.path.join(cls.data, "pose.json"))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

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


if __name__ == "__main__":
    main()
