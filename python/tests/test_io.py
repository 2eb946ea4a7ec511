"""hba's file readers from Python: scans, trajectories and dataset folders."""
import json
import os
import tempfile
import unittest

import numpy as np

import hba
from support import SHARED_DATA, TEST_DATA, main

PCD = os.path.join(TEST_DATA, "pcd")
LAS = os.path.join(SHARED_DATA, "las")


def rotation_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def some_poses(count):
    poses = np.tile(np.eye(4), (count, 1, 1))
    for k in range(count):
        poses[k, :3, :3] = rotation_z(0.1 * k)
        poses[k, :3, 3] = [k * 1.5, 0.25 * k, -0.125]
    return poses


def utm_points(count, seed=11):
    """Survey points in UTM with sub-millimetre fractions: no float32 holds them."""
    rng = np.random.default_rng(seed)
    points = np.empty((count, 4))
    points[:, 0] = 494428.61 + rng.uniform(-500, 500, count)
    points[:, 1] = 4877455.58 + rng.uniform(-500, 500, count)
    points[:, 2] = 130 + rng.uniform(-10, 10, count)
    points[:, 3] = rng.integers(0, 256, count)
    return points


class Scans(unittest.TestCase):
    def test_pcd_scan_is_float64_with_intensity(self):
        points = hba.read_scan(os.path.join(PCD, "hku1_cut_binary.pcd"))
        self.assertEqual(points.dtype, np.float64)
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

    def test_float64_coordinates_are_kept(self):
        """UTM points came back 0.25 m off when scans went through float32."""
        points = utm_points(300)
        with tempfile.TemporaryDirectory() as tmp:
            for name in ("map.pcd", "map.ply"):
                path = os.path.join(tmp, name)
                hba.write_scan(path, points)
                np.testing.assert_array_equal(hba.read_scan(path), points)
            with open(os.path.join(tmp, "map.pcd"), "rb") as pcd:
                self.assertIn(b"SIZE 8 8 8 4\n", pcd.read(400))
            path = os.path.join(tmp, "map.las")
            hba.write_scan(path, points)
            back = hba.read_scan(path)
            self.assertLessEqual(np.abs(back[:, :3] - points[:, :3]).max(), 0.0005 + 1e-9)  # millimetres
            np.testing.assert_array_equal(back[:, 3], points[:, 3])
            with self.assertRaisesRegex(hba.Error, r"map.bin: cannot write point 0 .*a .bin stores float32"):
                hba.write_scan(os.path.join(tmp, "map.bin"), points)
            self.assertFalse(os.path.exists(os.path.join(tmp, "map.bin")))

    def test_float32_points_are_written_as_float32(self):
        points = np.array([[1, 2, 3, 0.5], [-4, 5.25, 6, 7]], dtype=np.float32)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "a.pcd")
            hba.write_scan(path, points.astype(np.float64))  # float64 holding float32 values
            with open(path, "rb") as pcd:
                self.assertIn(b"SIZE 4 4 4 4\n", pcd.read(400))
            np.testing.assert_array_equal(hba.read_scan(path), points)

    def test_numbers_only_and_exact_in_float64(self):
        with self.assertRaisesRegex(hba.Error, r"points: expected numbers, got an array of dtype <U1"):
            hba.write_scan("unused.pcd", np.array([["1", "2", "3"]]))
        with self.assertRaisesRegex(hba.Error, r"points: expected numbers, got an array of dtype complex128"):
            hba.write_scan("unused.pcd", np.zeros((2, 3), dtype=complex))
        with self.assertRaisesRegex(hba.Error, r"points: expected a numpy array of points .*got NoneType"):
            hba.write_scan("unused.pcd", None)
        with self.assertRaisesRegex(hba.Error, r"points: value 0 \(9007199254740993, dtype int64\) is not exactly "
                                               r"a float64"):
            hba.write_scan("unused.pcd", np.array([[2**53 + 1, 0, 0]], dtype=np.int64))
        with tempfile.TemporaryDirectory() as tmp:  # 2**53 + 2 is a float64
            hba.write_scan(os.path.join(tmp, "a.pcd"), np.array([[2**53 + 2, 0, 0]], dtype=np.int64))
            self.assertEqual(hba.read_scan(os.path.join(tmp, "a.pcd"))[0, 0], 2**53 + 2)

    def test_wrong_shape_names_the_argument(self):
        with self.assertRaisesRegex(hba.Error, r"points: expected an \(N, 3\) or \(N, 4\) array.*\(2, 5\)"):
            hba.write_scan("unused.pcd", np.zeros((2, 5)))

    def test_missing_file_names_it(self):
        with self.assertRaisesRegex(hba.Error, "no_such_scan.pcd"):
            hba.read_scan("/nonexistent/no_such_scan.pcd")


@unittest.skipUnless(os.path.isfile(os.path.join(LAS, "expected.json")), "no ../shared/data/las")
class ThirdPartyLas(unittest.TestCase):
    """LAS files by PDAL, laspy and laz-perf against the facts expected.json lists."""

    def test_counts_first_points_bounds_and_intensities(self):
        with open(os.path.join(LAS, "expected.json")) as facts:
            files = json.load(facts)
        self.assertEqual(len(files), 6)
        for fact in files:
            with self.subTest(file=fact["file"]):
                points = hba.read_scan(os.path.join(LAS, fact["file"]))
                half_scale = np.array(fact["scale"]) / 2
                self.assertEqual(points.dtype, np.float64)
                self.assertEqual(points.shape, (fact["point_count"], 4))
                first = np.array(fact["first_points"])
                self.assertTrue(np.all(np.abs(points[:len(first), :3] - first) <= half_scale))
                self.assertTrue(np.all(np.abs(points[:, :3].min(axis=0) - fact["bounds"]["min"]) <= half_scale))
                self.assertTrue(np.all(np.abs(points[:, :3].max(axis=0) - fact["bounds"]["max"]) <= half_scale))
                np.testing.assert_array_equal(points[:3, 3], fact["first_intensities"])

    def test_terrascan_utm_point_is_not_rounded(self):
        """494428.61 4877455.58 came back as 494428.625 4877455.5 through float32."""
        first = hba.read_scan(os.path.join(LAS, "point-color.las"))[0]
        self.assertAlmostEqual(first[0], 494428.61, delta=0.005)
        self.assertAlmostEqual(first[1], 4877455.58, delta=0.005)


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
        n = len(self.dataset)
        with self.assertRaisesRegex(IndexError, f"scan index {n} is out of range for {n} scans \\(-{n} to {n - 1}\\)"):
            self.dataset[n]
        with self.assertRaisesRegex(IndexError, f"scan index -{n + 1} is out of range for {n} scans"):
            self.dataset[-n - 1]
        with self.assertRaisesRegex(IndexError, f"scan index -{n + 1} is out of range"):
            self.dataset.scan_path(-n - 1)

    def test_dataset_scans_are_float32_as_hba_optimizes_them(self):
        self.assertEqual(self.dataset[0].dtype, np.float32)

    def test_missing_folder_is_an_error(self):
        with self.assertRaisesRegex(hba.Error, "no_such_dataset"):
            hba.open_dataset("/nonexistent/no_such_dataset")


class Module(unittest.TestCase):
    def test_version(self):
        self.assertRegex(hba.__version__, r"^\d+\.\d+\.\d+")


if __name__ == "__main__":
    main()
