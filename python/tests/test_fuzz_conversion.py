"""Seeded random arrays and files through hba.write_scan and hba.read_scan.

Random dtypes (every numpy number kind, long double, strings, objects),
shapes, memory layouts (Fortran order, strides, negative strides, swapped
bytes, read-only) and values (NaN, infinities, huge, subnormal, UTM with
sub-millimetre fractions, integers past 2^53). Every call must return or
raise hba.Error, TypeError or ValueError, never crash; what comes back must
be what went in, as the docstrings promise: .pcd/.ply every finite point to
the last bit, .las to half a millimetre, .bin only what float32 holds. Then
random byte damage to the written files: read_scan returns or raises hba.Error.

HBA_FUZZ_CASES (default 300, what ctest runs) and HBA_FUZZ_SEED pick the
run; a failure prints the case's seed so it can be replayed alone.
"""
import os
import sys
import tempfile
import time
import unittest

import numpy as np

import hba
from support import main

CASES = int(os.environ.get("HBA_FUZZ_CASES", "300"))
SEED = int(os.environ.get("HBA_FUZZ_SEED", "35"))
EXTENSIONS = (".pcd", ".ply", ".las", ".bin")
EXPECTED_ERRORS = (hba.Error, TypeError, ValueError)
HALF_MM = 0.0005


def random_values(rng, count):
    """float64 values of one random flavour, with a few specials mixed in."""
    flavour = rng.integers(0, 7)
    if flavour == 0:
        values = rng.uniform(-100, 100, count)
    elif flavour == 1:  # UTM with sub-millimetre fractions
        values = rng.choice([494428.61, 4877455.58, 768323.751, 2028765.291]) + rng.uniform(-500, 500, count)
    elif flavour == 2:  # float32 values held in float64
        values = rng.uniform(-1e4, 1e4, count).astype(np.float32).astype(np.float64)
    elif flavour == 3:  # huge and tiny magnitudes
        values = rng.choice([-1, 1], count) * 10.0 ** rng.uniform(-320, 308, count)
    elif flavour == 4:  # integers around float32's and float64's limits
        values = rng.choice([2.0**24 + 1, 2.0**53, 2.0**53 + 2, -(2.0**31), 65535.5, 0.0], count)
    elif flavour == 5:  # one point repeated
        values = np.full(count, rng.uniform(-1e6, 1e6))
    else:
        values = rng.normal(0, 1e7, count)
    specials = np.array([np.nan, np.inf, -np.inf, -0.0, 5e-324, 3.5e38, 1e300])
    for i in np.flatnonzero(rng.random(count) < 0.03):
        values[i] = rng.choice(specials)
    return values


def random_dtype(rng):
    """Mostly float64 and float32; every other kind now and then."""
    roll = rng.random()
    if roll < 0.4:
        return np.float64
    if roll < 0.6:
        return np.float32
    return rng.choice([np.float16, np.longdouble, np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16,
                       np.uint32, np.uint64, np.bool_, np.complex128, np.str_, object, "datetime64[s]"])


def cast(values, dtype):
    with np.errstate(all="ignore"):
        if dtype in (np.str_, object):
            return values.astype(dtype)
        if dtype == "datetime64[s]":
            return np.zeros(values.shape, dtype=dtype)
        if np.issubdtype(dtype, np.integer):
            info = np.iinfo(dtype)
            clean = np.nan_to_num(values, nan=0, posinf=info.max, neginf=info.min)
            return np.clip(np.round(clean), info.min, info.max).astype(dtype)
        array = values.astype(dtype)
        if dtype == np.longdouble and array.size and np.finfo(np.longdouble).eps < np.finfo(np.float64).eps:
            array.flat[0] += np.longdouble(2.0) ** -70 * (1 + abs(array.flat[0]))  # not a float64 now
        return array


def random_layout(rng, array):
    """The same values in another memory layout."""
    layout = rng.integers(0, 6)
    if layout == 1 and array.ndim == 2:
        return np.asfortranarray(array)
    if layout == 2:  # every other row of a larger array
        wide = np.repeat(array, 2, axis=0) if array.ndim else array
        return wide[::2]
    if layout == 3 and array.ndim == 2:  # negative strides
        return array[::-1][::-1]
    if layout == 4 and array.dtype.kind in "iuf" and array.dtype.itemsize > 1:
        return array.astype(array.dtype.newbyteorder())
    if layout == 5:
        array = array.copy()
        array.flags.writeable = False
    return array


def random_points(rng):
    """Mostly well-formed points (2-D, 3 or 4 columns, numbers); a third of the time anything."""
    hostile = rng.random() < 0.35
    count = int(rng.choice([0, 1, 2, rng.integers(3, 200), rng.integers(3, 200)]))
    columns = int(rng.choice([3, 4, 2, 5, 1])) if hostile else int(rng.choice([3, 4]))
    shape = str(rng.choice(["2d", "1d", "3d", "transposed", "scalar", "list"])) if hostile else "2d"
    dtype = random_dtype(rng) if hostile else rng.choice([np.float64, np.float64, np.float32, np.int32,
                                                           np.float16, np.uint16])
    values = np.stack([random_values(rng, count) for _ in range(columns)], axis=1) if count else \
        np.zeros((0, columns))
    if columns == 4 and rng.random() < 0.8:  # intensities mostly small, non-negative
        values[:, 3] = np.abs(values[:, 3]) % 70000
    array = random_layout(rng, cast(values, dtype))
    if shape == "1d":
        array = array.reshape(-1)
    elif shape == "3d":
        array = array.reshape(array.shape + (1,))
    elif shape == "transposed":
        array = array.T
    elif shape == "scalar":
        array = array.flat[0] if array.size else 0.0
    elif shape == "list":
        array = array.tolist()
    return array


def as_float64(points):
    """What hba should hold: the values in float64, or None where it must refuse them."""
    try:
        array = np.asarray(points)
    except Exception:  # ragged lists and the like
        return None
    if array.dtype.kind not in "biuf" or array.ndim != 2 or array.shape[1] not in (3, 4):
        return None
    with np.errstate(all="ignore"):
        wide = array.astype(np.float64)
        if array.dtype.kind in "iu" and any(int(w) != int(a) for w, a in zip(wide.flat, array.flat)):
            return None  # Python's integers compare exactly
        if array.dtype.kind == "f" and not np.array_equal(wide.astype(array.dtype), array, equal_nan=True):
            return None
    return wide


def float32_of(values):
    with np.errstate(all="ignore"):
        return values.astype(np.float32).astype(np.float64)


def is_float32(values):
    return np.all(np.isnan(values) | (float32_of(values) == values))


def expected_outcome(wide, extension):
    """(xyz, intensity) hba must read back, or None where write_scan must refuse."""
    finite = np.all(np.isfinite(wide[:, :3]), axis=1)
    intensity = float32_of(wide[:, 3]) if wide.shape[1] == 4 else None
    if extension == ".las":
        if not np.all(finite):
            return None
        if len(wide):
            low, high = wide[:, :3].min(axis=0), wide[:, :3].max(axis=0)
            middle = (low + high) / 2
            offset = np.sign(middle) * np.floor(np.abs(middle) + 0.5)  # std::round: halves away from 0
            with np.errstate(all="ignore"):
                reach = max(np.abs(high - offset).max(), np.abs(low - offset).max())
            if not reach < 2147483647 * 0.001:
                return None
        if intensity is None:
            stored = np.zeros(len(wide))
        else:
            positive = np.where(intensity > 0, np.minimum(intensity, 65535), 0)
            stored = np.floor(positive + 0.5)
        return wide[:, :3], stored
    if extension == ".bin":
        if not is_float32(wide[finite, :3]):  # a point with a NaN is stored as it is, then dropped
            return None
        return wide[finite, :3], (intensity[finite] if intensity is not None else np.zeros(finite.sum()))
    return wide[finite, :3], (intensity[finite] if intensity is not None else None)


class ConversionFuzz(unittest.TestCase):
    def check_case(self, seed, folder):
        with np.errstate(all="ignore"):
            return self.run_case(np.random.default_rng(seed), folder)

    def run_case(self, rng, folder):
        points = random_points(rng)
        extension = str(rng.choice(EXTENSIONS))
        path = os.path.join(folder, "case" + extension)
        if os.path.exists(path):
            os.remove(path)
        wide = as_float64(points)
        expected = None if wide is None else expected_outcome(wide, extension)
        try:
            hba.write_scan(path, points)
        except EXPECTED_ERRORS as error:
            self.assertIsNone(expected, f"write_scan refused what it should write: {error}")
            self.assertFalse(os.path.exists(path), "a refused write left a file")
            return "refused"
        self.assertIsNotNone(expected, f"write_scan wrote what it should refuse ({type(points).__name__} "
                             f"{getattr(points, 'dtype', '')} {getattr(points, 'shape', '')})")
        back = hba.read_scan(path)
        xyz, intensity = expected
        self.assertEqual(back.dtype, np.float64)
        self.assertEqual(back.shape[0], len(xyz))
        if len(xyz) == 0:
            return "written"
        if extension == ".las":
            tolerance = HALF_MM + 1e-12 * np.maximum(1.0, np.abs(xyz))
            self.assertTrue(np.all(np.abs(back[:, :3] - xyz) <= tolerance), "LAS lost more than half a mm")
        else:
            np.testing.assert_array_equal(back[:, :3], xyz)
        if intensity is None:
            self.assertEqual(back.shape[1], 3)
        else:
            np.testing.assert_array_equal(back[:, 3], intensity)
        self.damage_and_read(rng, path)
        return "written"

    def damage_and_read(self, rng, path):
        """Random bytes of the file changed, cut or grown: read_scan returns or raises hba.Error."""
        with open(path, "rb") as file:
            data = bytearray(file.read())
        for _ in range(int(rng.integers(1, 8))):
            action = rng.integers(0, 3)
            if action == 0 and data:
                data[int(rng.integers(0, len(data)))] = int(rng.integers(0, 256))
            elif action == 1:
                del data[int(rng.integers(0, len(data) + 1)):]
            else:
                data += bytes(rng.integers(0, 256, int(rng.integers(1, 64)), dtype=np.uint8))
        damaged = path + ".damaged" + os.path.splitext(path)[1]
        with open(damaged, "wb") as file:
            file.write(data)
        try:
            points = hba.read_scan(damaged)
            self.assertEqual(points.dtype, np.float64)
            self.assertTrue(np.all(np.isfinite(points[:, :3])))
        except hba.Error:
            pass

    def test_random_arrays_round_trip_or_are_refused(self):
        outcomes = {"written": 0, "refused": 0}
        start = time.monotonic()
        with tempfile.TemporaryDirectory() as folder:
            for case in range(CASES):
                seed = SEED * 1_000_003 + case
                with self.subTest(seed=seed):
                    outcomes[self.check_case(seed, folder)] += 1
        print(f"conversion fuzz: {CASES} cases (seed {SEED}) in {time.monotonic() - start:.1f} s: "
              f"{outcomes['written']} written and read back, {outcomes['refused']} refused", file=sys.stderr)
        self.assertGreater(outcomes["written"], CASES // 5)
        self.assertGreater(outcomes["refused"], CASES // 20)


if __name__ == "__main__":
    main()
