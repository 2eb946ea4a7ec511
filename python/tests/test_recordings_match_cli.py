"""Recordings from Python by the tool's library calls: an MCAP file (written
by npm's @mcap/core) and a rosbag2 folder of sqlite3 files (Python's sqlite3,
messages by npm's @foxglove/rosmsg2-serialization), made from hku1's first
scans in ../shared. Each gives the poses `hba optimize` writes, bit for bit.
(The ROS 1 bag is in test_pipeline_matches_cli.py.)"""
import os
import shutil
import subprocess
import tempfile
import unittest

import numpy as np

import hba
from support import main, run_cli

SHARED = os.environ.get("HBA_SHARED_DATA_DIR", "")
MCAP_WRITER = os.environ.get("HBA_MCAP_WRITER", "")
DB3_WRITER = os.environ.get("HBA_DB3_WRITER", "")
SCANS = 60  # of hku1's 314: enough for two layers, quick on one thread


def write_or_skip(command):
    """Runs a writer; the test skips where its tools are missing (exit 77)."""
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode == 77:
        raise unittest.SkipTest("the recording writer's tools are missing: " + done.stdout.strip()[-200:])
    if done.returncode != 0:
        raise AssertionError("writer failed: " + done.stdout)


class RecordingFormatsMatchCli(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.hku1 = os.path.join(SHARED, "hku1")
        if not os.path.exists(os.path.join(cls.hku1, "odom_poses.txt")):
            raise unittest.SkipTest("../shared/data/hku1 is absent")
        if not MCAP_WRITER or not DB3_WRITER:
            raise unittest.SkipTest("HBA_MCAP_WRITER or HBA_DB3_WRITER is not set")
        cls.tmp = tempfile.TemporaryDirectory()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def path(self, *names):
        return os.path.join(self.tmp.name, *names)

    def expect_the_clis_poses(self, recording, name):
        out = self.path(name + "-out")
        run_cli("-j", "1", "optimize", recording, "-o", out, "--no-render", "--no-report-page")
        cli = hba.read_poses(os.path.join(out, "pose.json"))
        dataset = hba.open_dataset(recording)
        self.assertEqual(len(dataset), SCANS)
        result = hba.optimize(dataset, threads=1)
        self.assertTrue(np.array_equal(result.poses, cli))
        # Not the input handed back: the run moved the poses.
        self.assertGreater(np.abs(result.poses[:, :3, 3] - dataset.poses[:, :3, 3]).max(), 1e-4)

    def test_mcap_gives_the_cli_poses(self):
        mcap = self.path("hku1.mcap")
        write_or_skip(["bash", MCAP_WRITER, self.hku1, mcap, "zstd", str(SCANS)])
        self.expect_the_clis_poses(mcap, "mcap")

    def test_rosbag2_sqlite3_gives_the_cli_poses(self):
        lines = self.path("hku1.jsonl")
        write_or_skip(["bash", MCAP_WRITER, self.hku1, lines, "cdr", str(SCANS)])
        python = shutil.which("python3", path="/usr/bin") or "python3"
        bag = self.path("bag")
        subprocess.run([python, DB3_WRITER, lines, bag, "--split", "2"], check=True)
        self.expect_the_clis_poses(bag, "db3")


if __name__ == "__main__":
    main()
