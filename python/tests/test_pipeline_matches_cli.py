"""The tool's other steps from Python, by the same library calls: raw sweeps
deskewed again between passes, recordings with keyframes and every scan's
pose, and a session placed in a map that stays put. Each gives the poses
`hba optimize` writes, bit for bit."""
import filecmp
import json
import os
import shutil
import subprocess
import tempfile
import unittest

import numpy as np

import hba
from support import HBA_CLI, main, run_cli

BAG_WRITER = os.environ.get("HBA_ROS1_BAG_WRITER", "")


def cli_output(folder):
    """An output folder's optimized poses and report."""
    with open(os.path.join(folder, "report.json")) as f:
        return hba.read_poses(os.path.join(folder, "pose.json")), json.load(f)


class TempCase(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    @classmethod
    def path(cls, *names):
        return os.path.join(cls.tmp.name, *names)


class PlanMatchesCli(TempCase):
    """The run's plan, worked out before it (windows, final voxel, layers, threads, memory)."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.data = cls.path("sim")
        run_cli("simulate", "--frames", 40, "--seed", 3, "-o", cls.data)

    def cli_plan(self, *flags):
        out = subprocess.run([HBA_CLI, "-j", "1", "optimize", self.data, "--print-plan", *map(str, flags)], check=True,
                             stdout=subprocess.PIPE, text=True).stdout
        return json.loads(out)

    def test_the_plan_is_the_clis(self):
        plan = hba.plan(hba.open_dataset(self.data), threads=1)
        self.assertEqual(plan, self.cli_plan())
        self.assertEqual(plan["frames"], 40)
        self.assertEqual(plan["threads"], 1)
        self.assertTrue(plan["windows"]["automatic"])
        # The run does what the plan said.
        report = hba.optimize(hba.open_dataset(self.data), threads=1).report
        self.assertEqual(report["windows"], plan["windows"])
        self.assertEqual(report["final_voxel"], plan["final_voxel"])
        self.assertEqual(report["layers"], plan["layers"])

    def test_settings_change_the_plan_alike(self):
        plan = hba.plan(hba.open_dataset(self.data), threads=1, window=12, layers=2)
        self.assertEqual(plan, self.cli_plan("--window", 12, "--layers", 2))
        self.assertEqual(plan["windows"]["window"], 12)
        self.assertEqual(plan["layers"], 2)
        with self.assertRaisesRegex(hba.Error, "stride"):
            hba.plan(hba.open_dataset(self.data), window=10, stride=10)


class DeskewPassesMatchCli(TempCase):
    """Raw sweeps (points with times): two passes, the second deskewed by the first's poses."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.data = cls.path("sweeps")
        run_cli("simulate", "--frames", 40, "--seed", 3, "--sweep", "-o", cls.data)
        run_cli("-j", "1", "optimize", cls.data, "-o", cls.path("out"), "--no-render", "--no-report-page")
        cls.cli_poses, cls.cli_report = cli_output(cls.path("out"))

    def test_passes_give_the_cli_poses(self):
        dataset = hba.open_dataset(self.data)
        first_scan = dataset[5]
        result = hba.optimize(dataset, threads=1)
        self.assertTrue(np.array_equal(result.poses, self.cli_poses))
        self.assertEqual(result.report["deskew"]["passes"], 2)
        self.assertEqual(result.report["deskew"]["point_times"], self.cli_report["deskew"]["point_times"])
        # The caller's dataset still reads the sweeps as before the run.
        self.assertTrue(np.array_equal(dataset[5], first_scan))

    def test_one_pass_is_not_two(self):
        one = hba.optimize(hba.open_dataset(self.data), threads=1, deskew_passes=1)
        self.assertEqual(one.report["deskew"]["passes"], 1)
        self.assertGreater(np.abs(one.poses - self.cli_poses).max(), 1e-6)
        with self.assertRaisesRegex(hba.Error, "deskew_passes: 0"):
            hba.optimize(hba.open_dataset(self.data), deskew_passes=0)

    def test_deskew_off_is_the_clis_too(self):
        run_cli("-j", "1", "optimize", self.data, "--deskew", "off", "-o", self.path("off"), "--no-render",
                "--no-report-page")
        cli_poses, cli_report = cli_output(self.path("off"))
        self.assertNotIn("deskew", cli_report)
        result = hba.optimize(hba.open_dataset(self.data, deskew="off"), threads=1)
        self.assertTrue(np.array_equal(result.poses, cli_poses))
        self.assertNotIn("deskew", result.report)
        with self.assertRaisesRegex(hba.Error, "sometimes"):
            hba.open_dataset(self.data, deskew="sometimes")

    def test_arrays_need_poses(self):
        with self.assertRaisesRegex(hba.Error, "poses: required with arrays"):
            hba.optimize([hba.read_scan(hba.open_dataset(self.data).scan_path(0))])


class RecordingMatchesCli(TempCase):
    """A ROS 1 bag (written by Debian's python3-rosbag), keyframed, with every scan's pose."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.skip = ""
        python = shutil.which("python3", path="/usr/bin") or "python3"
        if not BAG_WRITER:
            cls.skip = "HBA_ROS1_BAG_WRITER is not set"
            return
        sim = cls.path("sim")
        run_cli("simulate", "--frames", 40, "--seed", 5, "-o", sim)
        # The scan folder the bag writer takes: Scans/ of x y z intensity PCDs,
        # KITTI odometry, times.txt in Unix time.
        folder = cls.path("folder")
        os.makedirs(os.path.join(folder, "Scans"))
        dataset = hba.open_dataset(sim)
        for k in range(len(dataset)):
            points = dataset[k]
            if points.shape[1] == 3:
                points = np.hstack([points, np.ones((len(points), 1), np.float32)])
            hba.write_scan(os.path.join(folder, "Scans", "%06d.pcd" % k), points[:, :4])
        hba.write_poses(os.path.join(folder, "odom_poses.txt"), dataset.poses, "kitti")
        with open(os.path.join(folder, "times.txt"), "w") as f:
            f.writelines("%.3f\n" % (1600000000.0 + 0.1 * k) for k in range(len(dataset)))
        cls.bag = cls.path("run.bag")
        written = subprocess.run([python, BAG_WRITER, folder, cls.bag], stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, text=True)
        if written.returncode == 77:
            cls.skip = "python3-rosbag is not installed"
            return
        if written.returncode != 0:
            raise RuntimeError("the bag writer failed: " + written.stdout)
        # Keyframes: about one in three clouds.
        steps = np.linalg.norm(np.diff(dataset.poses[:, :3, 3], axis=0), axis=1)
        # A Python float: numpy 2 (Debian 13) gives repr(np.float64) as "np.float64(...)".
        cls.keyframe_distance = float(3.0 * steps.mean())
        run_cli("-j", "1", "optimize", cls.bag, "--keyframe-distance", repr(cls.keyframe_distance), "-o",
                cls.path("out"), "--every-scan", "--no-render", "--no-report-page")
        cls.cli_poses, cls.cli_report = cli_output(cls.path("out"))

    def setUp(self):
        if self.skip:
            self.skipTest(self.skip)

    def test_keyframes_and_every_scan_give_the_cli_poses(self):
        dataset = hba.open_dataset(self.bag, keyframe_distance=self.keyframe_distance)
        self.assertEqual(dataset.layout, "ros1-bag")
        self.assertEqual(len(dataset), len(self.cli_poses))
        self.assertLess(len(dataset), 20)  # keyframes, not all 40 clouds
        result = hba.optimize(dataset, threads=1)
        self.assertTrue(np.array_equal(result.poses, self.cli_poses))
        stamps, every = dataset.every_scan(result.poses)
        self.assertEqual(every.shape, (40, 4, 4))
        cli_every, cli_stamps = hba.read_poses(self.path("out", "every_scan_poses_tum.txt"), return_stamps=True)
        self.assertLess(np.abs(stamps - cli_stamps).max(), 1e-6)
        self.assertLess(np.abs(every - cli_every).max(), 1e-9)
        # Between keyframes the scans moved with them, not stayed at the odometry.
        self.assertGreater(np.abs(every[1:, :3, 3] - hba.open_dataset(self.bag).poses[1:, :3, 3]).max(), 1e-3)

    def test_topics_are_chosen_by_name(self):
        every = hba.open_dataset(self.bag, cloud_topic="/cloud_registered_body", pose_topic="/Odometry")
        self.assertEqual(len(every), 40)
        with self.assertRaisesRegex(hba.Error, "/nothing"):
            hba.open_dataset(self.bag, cloud_topic="/nothing")
        with self.assertRaisesRegex(hba.Error, "tf_frames: 'odom' must be PARENT:CHILD"):
            hba.open_dataset(self.bag, tf_frames="odom")


class PriorMapMatchesCli(TempCase):
    """A second session placed in the first (a dataset at its poses, or its merged cloud) and refined against it."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        data = cls.path("sessions")
        run_cli("simulate", "--sessions", 2, "--frames", 60, "--seed", 5, "-o", data)
        cls.first, cls.second = (os.path.join(data, "session-%d" % k) for k in range(2))
        cls.cloud = cls.path("map.pcd")
        # The cloud: the first session's scans at their true poses (its
        # odometry's drift would leave too few places agreeing).
        run_cli("map", cls.first, "--poses", os.path.join(cls.first, "gt_world.txt"), "--format", "tum", "-o",
                cls.cloud)
        for name, flag, value in (("fixed", "--fixed", cls.first), ("cloud", "--map", cls.cloud)):
            run_cli("-j", "1", "optimize", cls.second, flag, value, "-o", cls.path(name), "--no-render",
                    "--no-report-page")
        cls.fixed_poses, cls.fixed_report = cli_output(cls.path("fixed"))
        cls.cloud_poses, cls.cloud_report = cli_output(cls.path("cloud"))

    def test_a_dataset_as_the_map_gives_the_cli_poses(self):
        session = hba.open_dataset(self.second)
        result = hba.optimize_in_map(session, map=hba.open_dataset(self.first), threads=1)
        self.assertTrue(np.array_equal(result.poses, self.fixed_poses))
        ours, theirs = result.report["map"], self.fixed_report["map"]
        self.assertTrue(ours["found"])
        self.assertEqual(ours["points"], theirs["points"])
        self.assertEqual(ours["refinement"], theirs["refinement"])
        # Placed in the first session's frame: far from the second's own.
        self.assertGreater(np.abs(result.poses[:, :3, 3] - session.poses[:, :3, 3]).max(), 1.0)

    def test_a_cloud_as_the_map_gives_the_cli_poses(self):
        result = hba.optimize_in_map(hba.open_dataset(self.second), map=self.cloud, threads=1)
        self.assertTrue(np.array_equal(result.poses, self.cloud_poses))
        self.assertEqual(result.report["map"]["tiles"], self.cloud_report["map"]["tiles"])

    def test_bad_maps_are_refused(self):
        session = hba.open_dataset(self.second)
        with self.assertRaisesRegex(hba.Error, "the session being optimized"):
            hba.optimize_in_map(session, map=hba.open_dataset(self.second))
        with self.assertRaisesRegex(hba.Error, "map_poses: only for a map given as an hba.Dataset"):
            hba.optimize_in_map(session, map=self.cloud, map_poses=session.poses)
        with self.assertRaisesRegex(hba.Error, "nowhere.pcd"):
            hba.optimize_in_map(session, map=self.path("nowhere.pcd"))


class ReportPageMatchesCli(TempCase):
    """The page `hba view OUT` writes for an output folder, written from Python by the same call."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.data = cls.path("plain")
        run_cli("simulate", "--frames", 40, "--seed", 3, "-o", cls.data)
        cls.out = cls.path("out")
        run_cli("-j", "1", "optimize", cls.data, "-o", cls.out, "--no-report-page")
        run_cli("view", cls.out)

    def test_the_page_is_the_tools_byte_for_byte(self):
        dataset = hba.open_dataset(self.data)
        with open(os.path.join(self.out, "report.json")) as f:
            report = json.load(f)
        page = self.path("page.html")
        figures = hba.write_report_page(page, dataset, dataset.poses,
                                        hba.read_poses(os.path.join(self.out, "pose.json")), report=report,
                                        title="plain", ground_truth=hba.read_poses(os.path.join(self.data, "gt.txt")),
                                        picture=os.path.join(self.out, "before_after.png"))
        self.assertGreater(figures["points"], 1000)
        self.assertEqual(figures["bytes"], os.path.getsize(page))
        self.assertTrue(filecmp.cmp(page, os.path.join(self.out, "report.html"), shallow=False))
        # Written again over its own page; another title is another page.
        hba.write_report_page(page, dataset, dataset.poses, dataset.poses, title="other")
        self.assertFalse(filecmp.cmp(page, os.path.join(self.out, "report.html"), shallow=False))

    def test_bad_pages_are_refused(self):
        dataset = hba.open_dataset(self.data)
        with self.assertRaisesRegex(hba.Error, "must be an .html file"):
            hba.write_report_page(self.path("page.txt"), dataset, dataset.poses, dataset.poses)
        notes = self.path("notes.html")
        with open(notes, "w") as f:
            f.write("<p>mine</p>")
        with self.assertRaisesRegex(hba.Error, "not a page hba wrote; pass force=True"):
            hba.write_report_page(notes, dataset, dataset.poses, dataset.poses)
        with open(notes) as f:
            self.assertEqual(f.read(), "<p>mine</p>")
        with self.assertRaisesRegex(hba.Error, "report: expected a dict"):
            hba.write_report_page(self.path("p.html"), dataset, dataset.poses, dataset.poses, report=[1])
        with self.assertRaisesRegex(hba.Error, "pose"):
            hba.write_report_page(self.path("p.html"), dataset, dataset.poses[:3], dataset.poses[:3])
        hba.write_report_page(notes, dataset, dataset.poses, dataset.poses, force=True)


if __name__ == "__main__":
    main()
