"""hba.optimize's keywords are the YAML settings, read and checked as `hba optimize --config` reads them."""
import unittest

import numpy as np

import hba
from support import main

NO_SCANS = ([], np.zeros((0, 4, 4)))


class SettingsKwargs(unittest.TestCase):
    def test_defaults_without_keywords(self):
        settings = hba.settings()
        self.assertEqual(settings["threads"], 0)
        self.assertIn("window", settings)
        self.assertIsInstance(settings["local"], dict)

    def test_keywords_reach_the_settings(self):
        settings = hba.settings(window=12, stride=4, refine=False, scan_voxel=0.25,
                                local={"voxel_size": 2.5}, threads=2)
        self.assertEqual(settings["window"], 12)
        self.assertEqual(settings["stride"], 4)
        self.assertIs(settings["refine"], False)
        self.assertEqual(settings["downsample_scans"], 0.25)  # scan_voxel is its other name
        self.assertEqual(settings["local"]["voxel_size"], 2.5)
        self.assertEqual(settings["global"]["voxel_size"], hba.settings()["global"]["voxel_size"])
        self.assertEqual(settings["threads"], 2)

    def test_numpy_numbers_are_numbers(self):
        settings = hba.settings(window=np.int64(12), scan_voxel=np.float32(0.5))
        self.assertEqual(settings["window"], 12)
        self.assertEqual(settings["downsample_scans"], 0.5)

    def test_unknown_name_says_did_you_mean(self):
        with self.assertRaisesRegex(hba.Error, r"unknown setting 'windw' \(did you mean 'window'\?\)"):
            hba.optimize(*NO_SCANS, windw=10)

    def test_unknown_name_in_a_section_says_did_you_mean(self):
        with self.assertRaisesRegex(hba.Error, r"'local.voxel_sise' \(did you mean 'voxel_size'\?\)"):
            hba.settings(local={"voxel_sise": 2.0})

    def test_errors_are_value_errors(self):
        with self.assertRaises(ValueError):
            hba.settings(windw=10)

    def test_out_of_range_value_is_refused(self):
        with self.assertRaisesRegex(hba.Error, "window must be"):
            hba.optimize(*NO_SCANS, window=1)
        with self.assertRaisesRegex(hba.Error, "scan"):
            hba.settings(scan_voxel=-1.0)

    def test_stride_must_stay_below_window(self):
        with self.assertRaisesRegex(hba.Error, "stride must be below window"):
            hba.settings(window=5, stride=5)

    def test_wrong_types_are_refused(self):
        with self.assertRaisesRegex(hba.Error, "'window' has a value of the wrong type"):
            hba.settings(window=10.5)
        with self.assertRaisesRegex(hba.Error, "'window' has a value of type list"):
            hba.settings(window=[10])
        with self.assertRaisesRegex(hba.Error, "threads must be an integer >= 0"):
            hba.settings(threads=-1)

    def test_integers_too_large_are_refused_naming_the_setting(self):
        with self.assertRaisesRegex(hba.Error, r"setting 'window' is 1180591620717411303424, out of range; "
                                               r"it takes"):
            hba.settings(window=2**70)
        with self.assertRaisesRegex(hba.Error, r"setting 'local.max_iterations' is -1180591620717411303424"):
            hba.settings(local={"max_iterations": -2**70})
        with self.assertRaisesRegex(hba.Error, "threads must be an integer >= 0.*got 1180591620717411303424"):
            hba.settings(threads=2**70)
        with self.assertRaisesRegex(hba.Error, "threads must be an integer >= 0.*got True"):
            hba.settings(threads=True)

    def test_threads_have_the_limit_of_hba_j(self):
        """hba -j 100000 is refused (at most 4096): so is threads=100000, before any work."""
        self.assertEqual(hba.settings(threads=4096)["threads"], 4096)
        for value in (4097, 100000, 2**31 - 1):
            with self.subTest(threads=value), \
                    self.assertRaisesRegex(hba.Error, f"threads must be .*at most 4096 .*got {value}"):
                hba.settings(threads=value)
        with self.assertRaisesRegex(ValueError, "at most 4096"):
            hba.optimize(*NO_SCANS, threads=100000)

    def test_strings_are_not_numbers(self):
        """YAML would read the text "10" as 10: a string is refused where a number or bool is due."""
        with self.assertRaisesRegex(hba.Error, r"setting 'window' is the string '10', not a number; it takes"):
            hba.optimize(*NO_SCANS, window="10")
        with self.assertRaisesRegex(hba.Error, r"setting 'scan_voxel' is the string '0.5', not a number"):
            hba.settings(scan_voxel="0.5")
        with self.assertRaisesRegex(hba.Error, r"setting 'local.voxel_size' is the string '2'"):
            hba.settings(local={"voxel_size": "2"})
        with self.assertRaisesRegex(hba.Error, r"setting 'refine' is the string 'false', not a bool"):
            hba.settings(refine="false")
        with self.assertRaisesRegex(hba.Error, "threads must be an integer"):
            hba.settings(threads="2")

    def test_nan_and_infinity_are_refused_naming_the_setting(self):
        for value in (float("nan"), float("inf"), np.float64("-inf")):
            with self.subTest(value=value), self.assertRaisesRegex(hba.Error,
                                                                   "setting 'scan_voxel' is .*, not a finite number"):
                hba.settings(scan_voxel=value)

    def test_a_choice_takes_its_names(self):
        self.assertEqual(hba.settings(top_down="direct_assign")["top_down"], "direct_assign")
        with self.assertRaisesRegex(hba.Error, "top_down"):
            hba.settings(top_down="direct")


if __name__ == "__main__":
    main()
