#pragma once
// Scans and poses between numpy arrays and hba's types. Every conversion
// checks shapes and throws hba::Error naming the argument (`what`), so a
// Python user sees which array is wrong.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/io/wide_cloud.hpp"

namespace hba::python {

// An array of T in C order, converted (and copied) from whatever numpy holds.
template <typename T>
using DenseArray = pybind11::array_t<T, pybind11::array::c_style | pybind11::array::forcecast>;

// What becomes of points far from the world origin (their median more than
// 10 km out: world points in UTM or ECEF), where floats are decimetres apart.
enum class FarPoints {
  // Kept to a float step of the cloud's extent, relative to an origin
  // (PointCloud::origin, io::farCloudOrigin), as the float64 readers keep a
  // map: for calls that merge points into the world (hba.mme).
  KeepOrigin,
  // Rounded to floats, as Dataset::loadScan gives a dataset's scans: for
  // scans in their sensor frame (hba.optimize), which lie near it.
  Narrow,
};

// An (N, 3) array (x y z) or (N, 4) array (x y z intensity), any real dtype,
// read in float64.
PointCloud cloudFromArray(const pybind11::handle& array, const std::string& what,
                          FarPoints far = FarPoints::Narrow);
// (N, 4) float32 with intensity, (N, 3) without.
pybind11::array_t<float> arrayFromCloud(const PointCloud& cloud);

// The same arrays with every coordinate kept: any real or integer dtype
// whose values a float64 holds exactly (int64 beyond 2^53 and long doubles
// that are not doubles are refused, as are strings, complex numbers and
// objects). Intensities become float32, as every scan format stores them.
io::WideCloud wideCloudFromArray(const pybind11::handle& array, const std::string& what);
// (N, 4) float64 with intensity, (N, 3) without.
pybind11::array_t<double> arrayFromWideCloud(const io::WideCloud& cloud);

// A (K, 4, 4) array, or anything numpy turns into one (a list of 4x4);
// every matrix must be a rigid transform.
std::vector<Pose> posesFromArray(const pybind11::handle& poses, const std::string& what);
pybind11::array_t<double> arrayFromPoses(const std::vector<Pose>& poses);

// One 4x4 rigid transform.
Pose poseFromMatrix(const pybind11::handle& matrix, const std::string& what);

// Where hba reads the scans of `scans` from: an hba.Dataset is read from
// disk as needed (it must outlive the source: the caller's argument keeps it
// alive); a sequence of arrays is copied into memory (far points as `far`
// says). Needs the GIL.
std::unique_ptr<io::ScanSource> scanSourceFrom(const pybind11::handle& scans,
                                               FarPoints far = FarPoints::Narrow);

}  // namespace hba::python
