#pragma once
// Plain values and arrays of them packed into bytes and read back, for
// exchanges between processes of one machine type (no byte swapping: the
// members of a group run the same build).
#include <cstddef>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "hba/core/error.hpp"
#include "hba/core/pose.hpp"
#include "hba/dist/group.hpp"

namespace hba::dist {

// Values copied byte by byte: trivially copyable ones, and fixed-size Eigen
// vectors and matrices (plain arrays of scalars, though their copy
// constructors are user-declared).
template <typename T>
inline constexpr bool kPlainLayout =
    std::conjunction_v<std::is_standard_layout<T>, std::is_trivially_destructible<T>>;
template <typename T>
inline constexpr bool kPackable = std::is_trivially_copyable_v<T> || kPlainLayout<T>;

class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(kPackable<T>, "only plain values are packed");
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <typename T>
  void putVector(const std::vector<T>& values) {
    static_assert(kPackable<T>, "only plain values are packed");
    put<std::uint64_t>(values.size());
    const auto* p = reinterpret_cast<const std::uint8_t*>(values.data());
    bytes_.insert(bytes_.end(), p, p + values.size() * sizeof(T));
  }
  Bytes take() { return std::move(bytes_); }

 private:
  Bytes bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const Bytes& bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    static_assert(kPackable<T>, "only plain values are packed");
    T value;
    std::memcpy(static_cast<void*>(&value), take(sizeof(T)), sizeof(T));
    return value;
  }
  template <typename T>
  std::vector<T> getVector() {
    static_assert(kPackable<T>, "only plain values are packed");
    const auto count = get<std::uint64_t>();
    if (count > (bytes_.size() - at_) / sizeof(T)) throw Error(overrun());
    std::vector<T> values(count);
    if (count > 0) std::memcpy(static_cast<void*>(values.data()), take(count * sizeof(T)), count * sizeof(T));
    return values;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  const std::uint8_t* take(std::size_t n) {
    if (n > bytes_.size() - at_) throw Error(overrun());
    const std::uint8_t* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  std::string overrun() const {
    return "exchange between processes: a message of " + std::to_string(bytes_.size()) +
           " bytes ends early (at byte " + std::to_string(at_) + ")";
  }
  const Bytes& bytes_;
  std::size_t at_ = 0;
};

inline void putPose(ByteWriter& out, const Pose& pose) {
  out.put(pose.q.coeffs());
  out.put(pose.t);
}

inline Pose getPose(ByteReader& in) {
  Pose pose;
  pose.q.coeffs() = in.get<Eigen::Vector4d>();
  pose.t = in.get<Vec3>();
  return pose;
}

inline void putPoses(ByteWriter& out, const std::vector<Pose>& poses) {
  out.put<std::uint64_t>(poses.size());
  for (const Pose& pose : poses) putPose(out, pose);
}

inline std::vector<Pose> getPoses(ByteReader& in) {
  std::vector<Pose> poses(in.get<std::uint64_t>());
  for (Pose& pose : poses) pose = getPose(in);
  return poses;
}

}  // namespace hba::dist
