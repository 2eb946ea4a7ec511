#include "numpy_convert.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"

namespace py = pybind11;

namespace hba::python {
namespace {

std::string shapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    text += (d > 0 ? ", " : "") + std::to_string(array.shape(d));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

// Tolerant enough for matrices written with 6 to 9 digits (KITTI files),
// strict enough to refuse a scaled or sheared matrix.
constexpr double kRigidTolerance = 1e-5;

bool isRigid(const Mat4& m) {
  const Mat3 r = m.topLeftCorner<3, 3>();
  const bool orthonormal = (r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff() < kRigidTolerance;
  const bool last_row = m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1));
  return orthonormal && r.determinant() > 0 && last_row && m.allFinite();
}

std::string dtypeName(const py::array& array) { return py::str(array.dtype()); }

// An array of numbers (bool, integer or real dtype), whatever its layout.
py::array numericArray(const py::handle& object, const std::string& what) {
  py::array array = py::array::ensure(object);
  if (!array || (array.dtype().kind() == 'O' && !py::isinstance<py::array>(object))) {
    throw Error(what + ": expected a numpy array of points (N, 3) or (N, 4), got " +
                std::string(py::str(object.get_type().attr("__name__"))));
  }
  const char kind = array.dtype().kind();
  if (kind != 'b' && kind != 'i' && kind != 'u' && kind != 'f') {
    throw Error(what + ": expected numbers, got an array of dtype " + dtypeName(array));
  }
  return array;
}

// A value that a float64 holds exactly: as one, it converts back to itself
// (the bound keeps the conversion back defined).
template <typename Integer>
bool isExactInDouble(Integer v) {
  const auto d = static_cast<double>(v);
  return d < static_cast<double>(std::numeric_limits<Integer>::max()) && static_cast<Integer>(d) == v;
}

template <typename Number>
void requireEachExactInDouble(const py::array& array, const std::string& what) {
  const auto values = DenseArray<Number>::ensure(array);
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    const Number v = values.data()[i];
    bool exact = true;
    if constexpr (std::is_integral_v<Number>) {
      exact = isExactInDouble(v);
    } else {
      exact = std::isnan(v) || static_cast<Number>(static_cast<double>(v)) == v;
    }
    if (!exact) {
      throw Error(what + ": value " + std::to_string(i) + " (" +
                  std::string(py::str(array.attr("flat")[py::int_(i)])) + ", dtype " + dtypeName(array) +
                  ") is not exactly a float64, which hba keeps coordinates in");
    }
  }
}

// 64-bit integers past 2^53 and long doubles that are not doubles would
// change on the way to float64: refused rather than rounded. Every other
// dtype of numbers fits.
void requireExactInDouble(const py::array& array, const std::string& what) {
  const char kind = array.dtype().kind();
  if (kind == 'i' && array.itemsize() == 8) requireEachExactInDouble<std::int64_t>(array, what);
  if (kind == 'u' && array.itemsize() == 8) requireEachExactInDouble<std::uint64_t>(array, what);
  if (kind == 'f' && array.itemsize() > 8) requireEachExactInDouble<long double>(array, what);
}

void requirePointShape(const py::array& points, const std::string& what) {
  if (points.ndim() != 2 || (points.shape(1) != 3 && points.shape(1) != 4)) {
    throw Error(what + ": expected an (N, 3) or (N, 4) array (x y z [intensity]), got shape " +
                shapeText(points));
  }
}

}  // namespace

io::WideCloud wideCloudFromArray(const py::handle& array, const std::string& what) {
  const py::array numbers = numericArray(array, what);
  requirePointShape(numbers, what);
  requireExactInDouble(numbers, what);
  const auto points = DenseArray<double>::ensure(numbers);
  if (!points) throw Error(what + ": cannot be read as float64 numbers");
  const auto n = static_cast<std::size_t>(points.shape(0));
  const bool with_intensity = points.shape(1) == 4;
  const auto view = points.unchecked<2>();
  io::WideCloud cloud;
  cloud.reserve(n, with_intensity);
  for (std::size_t i = 0; i < n; ++i) {
    const auto row = static_cast<py::ssize_t>(i);
    const Vec3 p(view(row, 0), view(row, 1), view(row, 2));
    if (with_intensity) {
      cloud.add(p, static_cast<float>(view(row, 3)));
    } else {
      cloud.add(p);
    }
  }
  return cloud;
}

py::array_t<double> arrayFromWideCloud(const io::WideCloud& cloud) {
  const py::ssize_t columns = cloud.hasIntensity() ? 4 : 3;
  py::array_t<double> array({static_cast<py::ssize_t>(cloud.size()), columns});
  auto view = array.mutable_unchecked<2>();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto row = static_cast<py::ssize_t>(i);
    for (py::ssize_t c = 0; c < 3; ++c) view(row, c) = cloud.points[i][c];
    if (cloud.hasIntensity()) view(row, 3) = cloud.intensity[i];
  }
  return array;
}

PointCloud cloudFromArray(const py::handle& array, const std::string& what, FarPoints far) {
  const py::array numbers = numericArray(array, what);
  requirePointShape(numbers, what);
  const auto points = DenseArray<double>::ensure(numbers);
  if (!points) throw Error(what + ": cannot be read as float64 numbers");
  const auto n = static_cast<std::size_t>(points.shape(0));
  const bool with_intensity = points.shape(1) == 4;
  const auto view = points.unchecked<2>();
  const auto point = [&](std::size_t i) {
    const auto row = static_cast<py::ssize_t>(i);
    return Vec3(view(row, 0), view(row, 1), view(row, 2));
  };
  PointCloud cloud;
  if (far == FarPoints::KeepOrigin) {
    std::vector<Vec3> wide(n);
    for (std::size_t i = 0; i < n; ++i) wide[i] = point(i);
    cloud.origin = io::farCloudOrigin(wide);
  }
  cloud.reserve(n, with_intensity);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3f p = (point(i) - cloud.origin).cast<float>();
    if (with_intensity) {
      cloud.add(p, static_cast<float>(view(static_cast<py::ssize_t>(i), 3)));
    } else {
      cloud.add(p);
    }
  }
  return cloud;
}

py::array_t<float> arrayFromCloud(const PointCloud& cloud) {
  const py::ssize_t columns = cloud.hasIntensity() ? 4 : 3;
  py::array_t<float> array({static_cast<py::ssize_t>(cloud.size()), columns});
  auto view = array.mutable_unchecked<2>();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto row = static_cast<py::ssize_t>(i);
    // Scans have a zero origin; a map's points are moved back to the world.
    const Vec3f p = cloud.origin.isZero() ? cloud.points[i] : cloud.world(i).cast<float>();
    for (py::ssize_t c = 0; c < 3; ++c) view(row, c) = p[c];
    if (cloud.hasIntensity()) view(row, 3) = cloud.intensity[i];
  }
  return array;
}

std::vector<Pose> posesFromArray(const py::handle& poses, const std::string& what) {
  const auto matrices = DenseArray<double>::ensure(poses);
  if (!matrices) throw Error(what + ": expected a (K, 4, 4) array of poses");
  if (matrices.ndim() != 3 || matrices.shape(1) != 4 || matrices.shape(2) != 4) {
    throw Error(what + ": expected a (K, 4, 4) array of sensor-to-world poses, got shape " +
                shapeText(matrices));
  }
  const auto view = matrices.unchecked<3>();
  std::vector<Pose> out;
  out.reserve(static_cast<std::size_t>(matrices.shape(0)));
  for (py::ssize_t k = 0; k < matrices.shape(0); ++k) {
    Mat4 m;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) m(r, c) = view(k, r, c);
    }
    if (!isRigid(m)) {
      throw Error(what + "[" + std::to_string(k) +
                  "]: not a rigid transform (rotation not orthonormal, or last row not 0 0 0 1)");
    }
    out.push_back(Pose::fromMatrix(m));
  }
  return out;
}

Pose poseFromMatrix(const py::handle& matrix, const std::string& what) {
  auto m = DenseArray<double>::ensure(matrix);
  if (!m || m.ndim() != 2 || m.shape(0) != 4 || m.shape(1) != 4)
    throw Error(what + ": expected a 4x4 matrix");
  return posesFromArray(m.reshape({1, 4, 4}), what).front();
}

py::array_t<double> arrayFromPoses(const std::vector<Pose>& poses) {
  py::array_t<double> array({static_cast<py::ssize_t>(poses.size()), py::ssize_t{4}, py::ssize_t{4}});
  auto view = array.mutable_unchecked<3>();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const Mat4 m = poses[k].matrix();
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) view(static_cast<py::ssize_t>(k), r, c) = m(r, c);
    }
  }
  return array;
}

std::unique_ptr<io::ScanSource> scanSourceFrom(const py::handle& scans, FarPoints far) {
  if (py::isinstance<io::Dataset>(scans)) {
    return std::make_unique<io::DatasetScanSource>(scans.cast<const io::Dataset&>());
  }
  if (py::isinstance<py::str>(scans)) {
    throw Error("scans: '" + scans.cast<std::string>() +
                "' is a name, not scans; pass hba.open_dataset(name) for a folder");
  }
  if (py::isinstance<py::array>(scans) || !py::isinstance<py::sequence>(scans)) {
    throw Error("scans: expected a list of (N, 3) or (N, 4) arrays, or an hba.Dataset");
  }
  std::vector<PointCloud> clouds;
  const auto sequence = py::reinterpret_borrow<py::sequence>(scans);
  clouds.reserve(sequence.size());
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    clouds.push_back(cloudFromArray(sequence[i], "scans[" + std::to_string(i) + "]", far));
  }
  return std::make_unique<io::MemoryScanSource>(std::move(clouds));
}

}  // namespace hba::python
