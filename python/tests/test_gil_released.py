"""hba.optimize releases the GIL: a Python thread keeps running while it works."""
import os
import tempfile
import threading
import time
import unittest

import hba
from support import main, scan_paths, simulate


class GilReleased(unittest.TestCase):
    def test_a_python_thread_runs_during_optimize(self):
        with tempfile.TemporaryDirectory() as tmp:
            data = simulate(tmp, frames=40, seed=3)
            scans = [hba.read_scan(path) for path in scan_paths(data)]
            poses = hba.read_poses(os.path.join(data, "pose.json"))

        ticks = []
        stop = threading.Event()

        def tick():
            while not stop.is_set():
                ticks.append(time.monotonic())
                time.sleep(0.001)

        ticker = threading.Thread(target=tick)
        ticker.start()
        try:
            start = time.monotonic()
            hba.optimize(scans, poses, threads=1)
            end = time.monotonic()
        finally:
            stop.set()
            ticker.join()
        # Holding the GIL, hba would stop the ticker for the whole call; the
        # margins leave out the conversions before and after the work.
        self.assertGreater(end - start, 0.3, "the run is too short to tell")
        margin = 0.25 * (end - start)
        during = [t for t in ticks if start + margin < t < end - margin]
        self.assertGreater(len(during), 10)


if __name__ == "__main__":
    main()
