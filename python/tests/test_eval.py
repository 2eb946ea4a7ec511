"""hba.ate and hba.mme: zero for the truth, worse for drifted poses."""
import os
import subprocess
import tempfile
import unittest

import numpy as np

import hba
from support import HBA_CLI, main, scan_paths, simulate


def moved(poses, rotation_angle, translation):
    """The whole trajectory in another world frame."""
    c, s = np.cos(rotation_angle), np.sin(rotation_angle)
    frame = np.eye(4)
    frame[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    frame[:3, 3] = translation
    return frame @ poses


class Evaluation(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        data = simulate(cls.tmp.name, frames=30, seed=5)
        cls.gt = hba.read_poses(os.path.join(data, "gt.txt"))
        cls.drifted = hba.read_poses(os.path.join(data, "pose.json"))
        cls.scans = [hba.read_scan(path) for path in scan_paths(data)]

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_ate_of_the_truth_is_zero(self):
        ate = hba.ate(self.gt, self.gt)
        self.assertEqual(ate["matched"], len(self.gt))
        self.assertLess(ate["translation_m"]["rmse"], 1e-12)
        self.assertLess(ate["rotation_deg"]["max"], 1e-6)

    def test_alignment_removes_a_change_of_world_frame(self):
        other_frame = moved(self.gt, 0.7, [10.0, -3.0, 2.0])
        self.assertLess(hba.ate(self.gt, other_frame, align="se3")["translation_m"]["rmse"], 1e-9)
        self.assertGreater(hba.ate(self.gt, other_frame, align="none")["translation_m"]["rmse"], 1.0)
        aligned = hba.ate(self.gt, other_frame)["alignment"]
        self.assertEqual(aligned["rotation"].shape, (3, 3))
        self.assertAlmostEqual(aligned["scale"], 1.0)

    def test_drifted_poses_have_a_larger_ate(self):
        drift = hba.ate(self.gt, self.drifted)["translation_m"]
        self.assertGreater(drift["rmse"], 1e-3)
        self.assertGreaterEqual(drift["max"], drift["rmse"])

    def test_unknown_alignment_says_did_you_mean(self):
        with self.assertRaisesRegex(hba.Error, "did you mean 'sim3'"):
            hba.ate(self.gt, self.gt, align="sim3x")

    def test_truth_makes_the_crisper_map(self):
        truth = hba.mme(self.scans, self.gt)
        drifted = hba.mme(self.scans, self.drifted)
        self.assertTrue(np.isfinite(truth))
        self.assertLess(truth, drifted)

    def world_points(self):
        """The scans moved into the world by the truth: float64, as a georeferenced map holds them."""
        return [scan[:, :3] @ pose[:3, :3].T + pose[:3, 3] for scan, pose in zip(self.scans, self.gt)]

    def test_mme_of_world_points_is_the_same_at_every_offset(self):
        """Issue 57: world points were rounded to float32 (-3.653 at 0, -3.474 at 5e5 m, undefined at 5e6 m)."""
        world = self.world_points()
        identity = np.repeat(np.eye(4)[None], len(world), axis=0)
        at_origin = hba.mme(world, identity)
        for offset in (1e5, 5e5, 5e6):
            shift = np.array([offset, offset, 0.0])
            with self.subTest(offset=offset):
                self.assertAlmostEqual(hba.mme([points + shift for points in world], identity), at_origin,
                                       delta=1e-3)
                # One cloud, as a map: the same figure.
                self.assertAlmostEqual(hba.mme([np.vstack(world) + shift], identity[:1]), at_origin,
                                       delta=1e-3)

    def test_mme_of_far_world_points_matches_hba_mme(self):
        """The same float64 map far out (UTM): hba.mme and `hba mme --map` agree."""
        cloud = np.vstack(self.world_points()) + np.array([4.5e5, 5.4e6, 120.0])
        path = os.path.join(self.tmp.name, "utm_map.pcd")
        hba.write_scan(path, cloud)
        printed = subprocess.run([HBA_CLI, "-q", "mme", "--map", path], check=True, capture_output=True,
                                 text=True).stdout
        cli = float(next(line.split()[1] for line in printed.splitlines() if line.startswith("MME")))
        self.assertAlmostEqual(hba.mme([cloud], np.eye(4)[None]), cli, delta=1e-3)

    def test_far_poses_of_sensor_frame_scans_keep_the_figure(self):
        """Scans in their sensor frame with poses in UTM: the map is kept near its first pose."""
        shifted = self.gt.copy()
        shifted[:, :3, 3] += [5e6, 5e6, 0.0]
        self.assertAlmostEqual(hba.mme(self.scans, shifted), hba.mme(self.scans, self.gt), delta=1e-3)

    def test_mme_needs_a_pose_per_scan(self):
        with self.assertRaises(hba.Error):
            hba.mme(self.scans, self.gt[:-1])

    def test_mme_refuses_what_hba_mme_refuses(self):
        """--voxel >= 0, --radius > 0, --min-neighbors >= 0, as the CLI's checks."""
        for keywords, message in ((dict(voxel=-1), r"voxel must be >= 0 .*got -1\.0"),
                                  (dict(voxel=float("nan")), "voxel must be >= 0"),
                                  (dict(radius=0), "radius must be > 0"),
                                  (dict(min_neighbors=-1), "min_neighbors must be >= 0")):
            with self.subTest(**keywords), self.assertRaisesRegex(hba.Error, message):
                hba.mme(self.scans, self.gt, **keywords)
        with self.assertRaises(TypeError):
            hba.mme(self.scans, self.gt, voxel="0.5")


if __name__ == "__main__":
    main()
