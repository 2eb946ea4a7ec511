"""python/examples/optimize_numpy.py runs on a simulated sequence and writes its poses."""
import os
import subprocess
import sys
import tempfile
import unittest

import hba
from support import main, simulate

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "examples", "optimize_numpy.py")


class Example(unittest.TestCase):
    def test_example_writes_the_optimized_poses(self):
        with tempfile.TemporaryDirectory() as tmp:
            data = simulate(tmp, frames=30, seed=2)
            output = os.path.join(tmp, "poses_kitti.txt")
            run = subprocess.run([sys.executable, EXAMPLE, data, "--output", output],
                                 check=True, capture_output=True, text=True)
            self.assertIn("mean map entropy", run.stdout)
            self.assertIn("ATE optimized", run.stdout)
            self.assertEqual(hba.read_poses(output).shape, (30, 4, 4))


if __name__ == "__main__":
    main()
