"""What the Python tests share: the hba CLI (argv[1], from ctest) and simulated sequences."""
import os
import subprocess
import sys

HBA_CLI = sys.argv[1] if len(sys.argv) > 1 else os.environ.get("HBA_CLI", "hba")
TEST_DATA = os.environ.get("HBA_TEST_DATA_DIR",
                           os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data"))
# ../shared/data beside the repository (third-party files, real sequences); may be absent.
SHARED_DATA = os.environ.get("HBA_SHARED_DATA_DIR",
                             os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data"))


def run_cli(*args):
    subprocess.run([HBA_CLI, *map(str, args)], check=True, stdout=subprocess.DEVNULL)


def simulate(parent, frames=40, seed=3):
    """A simulated sequence in parent/sim: pcd/, pose.json (drifting), gt.txt."""
    folder = os.path.join(parent, "sim")
    run_cli("simulate", "--frames", frames, "--seed", seed, "-o", folder)
    return folder


def scan_paths(folder):
    """The scans of a simulated sequence, in frame order."""
    pcd = os.path.join(folder, "pcd")
    names = sorted(os.listdir(pcd), key=lambda name: int(os.path.splitext(name)[0]))
    return [os.path.join(pcd, name) for name in names]


def main():
    """unittest's main, without the CLI path ctest passes."""
    import unittest
    unittest.main(argv=sys.argv[:1])
