"""hba's file readers from Python: scans, trajectories and dataset folders."""
import os
import tempfile
import unittest

import numpy as np

import hba
from support import TEST_DATA, main

PCD = os.path.join(TEST_DATA, "pcd")


def rotation_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def some_poses(count):
    poses = np.tile(np.eye(4), (count, 1, 1))
    for k in range(count):
        poses[k, :3, :3] = rotation_z(0.1 * k)
        poses[k, :3, 3] = [k * 1.5, 0.25 * k, -0.125]
    return poses


class Scans(unittest.TestCase):
    def test_pcd_scan_is_float32_with_intensity(self):
        points = hba.read_scan(os.path.join(PCD, "hku1_cut_binary.pcd"))
        self.assertEqual(points.dtype, np.float32)
        self.assertEqual(points.ndim, 2)
        self.assertEqual(points.shape[1], 4)
        self.assertGreater(points.shape[0], 100)

    def test_every_encoding_reads_the_same_points(self):
        binary = hba.read_scan(os.path.join(PCD, "hku1_cut_binary.pcd"))
        compressed = hba.read_scan(os.path.join(PCD, "hku1_cut_binary_compressed.pcd"))
        np.testing.assert_array_equal(binary, compressed)

    def test_written_scan_reads_back(self):
        points = np.array([[1, 2, 3, 0.5], [-4, 5.25, 6, 7]], dtype=np.float32)
        with tempfile.TemporaryDirectory() as tmp:
            for name in ("a.pcd", "a.ply"):
                path = os.path.join(tmp, name)
                hba.write_scan(path, points)
                np.testing.assert_array_equal(hba.read_scan(path), points)
            hba.write_scan(os.path.join(tmp, "xyz.pcd"), points[:, :3])
            self.assertEqual(hba.read_scan(os.path.join(tmp, "xyz.pcd")).shape, (2, 3))

    def test_wrong_shape_names_the_argument(self):
        with self.assertRaisesRegex(hba.Error, r"points: expected an \(N, 3\) or \(N, 4\) array.*\(2, 5\)"):
            hba.write_scan("unused.pcd", np.zeros((2, 5)))

    def test_missing_file_names_it(self):
        with self.assertRaisesRegex(hba.Error, "no_such_scan.pcd"):
            hba.read_scan("/nonexistent/no_such_scan.pcd")


class Poses(unittest.TestCase):
    def test_written_poses_read_back_in_every_format(self):
        poses = some_poses(5)
        stamps = np.arange(5) * 0.1 + 100.0
        with tempfile.TemporaryDirectory() as tmp:
            for fmt in ("kitti", "tum", "hba"):
                path = os.path.join(tmp, "poses_" + fmt + ".txt")
                hba.write_poses(path, poses, format=fmt, stamps=stamps if fmt == "tum" else None)
                read = hba.read_poses(path, format=fmt)
                self.assertEqual(read.shape, (5, 4, 4))
                np.testing.assert_allclose(read, poses, atol=1e-12)
            read, read_stamps = hba.read_poses(os.path.join(tmp, "poses_tum.txt"), return_stamps=True)
            np.testing.assert_array_equal(read_stamps, stamps)
            _, no_stamps = hba.read_poses(os.path.join(tmp, "poses_kitti.txt"), return_stamps=True)
            self.assertIsNone(no_stamps)

    def test_a_scaled_matrix_is_not_a_pose(self):
        poses = some_poses(3)
        poses[2, :3, :3] *= 2.0
        with self.assertRaisesRegex(hba.Error, r"poses\[2\]: not a rigid transform"):
            hba.write_poses("unused.txt", poses)

    def test_wrong_format_name_says_did_you_mean(self):
        with self.assertRaisesRegex(hba.Error, "did you mean 'kitti'"):
            hba.write_poses("unused.txt", some_poses(1), format="kiti")


class Datasets(unittest.TestCase):
    def setUp(self):
        self.dataset = hba.open_dataset(os.path.join(TEST_DATA, "datasets", "hba_plain"))

    def test_scans_and_poses(self):
        n = len(self.dataset)
        self.assertGreater(n, 1)
        self.assertEqual(self.dataset.poses.shape, (n, 4, 4))
        self.assertEqual(self.dataset.layout, "hba")
        first = hba.read_scan(self.dataset.scan_path(0))
        np.testing.assert_array_equal(self.dataset[0], first)
        np.testing.assert_array_equal(self.dataset[-n], first)
        self.assertEqual(len(list(self.dataset)), n)  # iterates until IndexError

    def test_index_out_of_range(self):
        with self.assertRaises(IndexError):
            self.dataset[len(self.dataset)]

    def test_missing_folder_is_an_error(self):
        with self.assertRaisesRegex(hba.Error, "no_such_dataset"):
            hba.open_dataset("/nonexistent/no_such_dataset")


class Module(unittest.TestCase):
    def test_version(self):
        self.assertRegex(hba.__version__, r"^\d+\.\d+\.\d+")


if __name__ == "__main__":
    main()
