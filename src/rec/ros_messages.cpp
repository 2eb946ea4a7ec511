#include "hba/rec/ros_messages.hpp"

#include <fmt/format.h>

#include <cmath>

#include "hba/core/error.hpp"
#include "message_parts.hpp"

namespace hba::rec {

namespace detail {

// A reader of one message: CDR after its 4-byte encapsulation header.
ByteReader messageReader(const std::vector<std::uint8_t>& message, Serialization serialization,
                         const std::string& what) {
  ByteReader reader(message.data(), message.size(), what);
  if (serialization == Serialization::Cdr) {
    const std::uint8_t zero = reader.u8(), kind = reader.u8();
    reader.skip(2);  // options
    if (zero != 0 || kind != 1) {
      reader.fail("not little-endian CDR (encapsulation " + std::to_string(zero) + " " +
                  std::to_string(kind) + ")");
    }
    reader.startCdr();
  }
  return reader;
}

Header readHeader(ByteReader& reader) {
  Header header;
  if (!reader.cdr()) reader.u32();  // ROS 1's seq
  header.stamp = reader.time();
  header.frame_id = reader.string();
  return header;
}

PoseFields readPoseFields(ByteReader& reader, const std::string& field, bool transform) {
  PoseFields fields;
  fields.field = field;
  fields.transform = transform;
  for (int k = 0; k < 3; ++k) fields.position[k] = reader.f64();
  fields.x = reader.f64();
  fields.y = reader.f64();
  fields.z = reader.f64();
  fields.w = reader.f64();
  return fields;
}

Pose toPose(const PoseFields& fields, const std::string& what) {
  // As pose files: a shorter quaternion is noise, not a rotation to renormalize.
  constexpr double kMinQuaternionNorm = 1e-3;
  const std::string position = fields.field + (fields.transform ? ".translation" : ".position");
  const std::string orientation = fields.field + (fields.transform ? ".rotation" : ".orientation");
  for (int k = 0; k < 3; ++k) {
    const double value = fields.position[k];
    if (std::isfinite(value)) continue;
    throw BadFieldValue(fmt::format("{}: {}.{} is {}: a pose needs a finite position", what, position,
                                    "xyz"[k], std::isnan(value) ? "NaN" : "infinite"));
  }
  Quat q(fields.w, fields.x, fields.y, fields.z);
  if (!q.coeffs().allFinite()) {
    throw BadFieldValue(fmt::format("{}: {} is not finite (x y z w = {} {} {} {}): a pose needs a rotation",
                                    what, orientation, fields.x, fields.y, fields.z, fields.w));
  }
  const double norm = q.norm();
  if (norm < kMinQuaternionNorm) {
    throw BadFieldValue(
        fmt::format("{}: {} has (near) zero length ({:g}): it is no rotation", what, orientation, norm));
  }
  q.coeffs() /= norm;
  return Pose(q, fields.position);
}

void expectEnd(ByteReader& reader, const std::string& type) {
  // CDR writers may pad a message to a multiple of 4 or 8 bytes.
  if (reader.cdr() && reader.remaining() < 8) {
    bool zeros = true;
    for (std::size_t k = 0; k < reader.remaining(); ++k) zeros = zeros && reader.here()[k] == 0;
    if (zeros) return;
  }
  if (reader.remaining() != 0)
    reader.fail(std::to_string(reader.remaining()) + " bytes left after a " + type);
}

}  // namespace detail

namespace {
using namespace detail;

PointCloud2View decodePointCloud2Message(const std::vector<std::uint8_t>& message,
                                         Serialization serialization, const std::string& what) {
  ByteReader reader = messageReader(message, serialization, what);
  PointCloud2View cloud;
  const Header header = readHeader(reader);
  cloud.stamp = header.stamp;
  cloud.frame_id = header.frame_id;
  cloud.height = reader.u32();
  cloud.width = reader.u32();
  const std::uint32_t fields = reader.count(13);
  for (std::uint32_t k = 0; k < fields; ++k) {
    PointField field;
    field.name = reader.string();
    field.offset = reader.u32();
    field.datatype = reader.u8();
    field.count = reader.u32();
    cloud.fields.push_back(field);
  }
  cloud.big_endian = reader.u8() != 0;
  cloud.point_step = reader.u32();
  cloud.row_step = reader.u32();
  const auto data = reader.bytes();
  cloud.data = data.first;
  cloud.data_size = data.second;
  reader.u8();  // is_dense
  expectEnd(reader, kPointCloud2);
  const std::uint64_t points = std::uint64_t{cloud.height} * cloud.width;
  // The data is height rows of row_step bytes, exactly: a block that is
  // longer is as corrupt as a shorter one (its points would be read in part).
  const std::uint64_t expected = std::uint64_t{cloud.height} * cloud.row_step;
  if (expected != cloud.data_size || (points > 0 && cloud.point_step == 0) ||
      std::uint64_t{cloud.width} * cloud.point_step > cloud.row_step) {
    reader.fail("a PointCloud2 of " + std::to_string(cloud.height) + " x " + std::to_string(cloud.width) +
                " points of " + std::to_string(cloud.point_step) + " bytes (rows of " +
                std::to_string(cloud.row_step) + ") in " + std::to_string(cloud.data_size) +
                " bytes of data (height x row_step is " + std::to_string(expected) + ")");
  }
  return cloud;
}

std::vector<StampedPose> decodeTrajectory(const std::string& type, const std::vector<std::uint8_t>& message,
                                          Serialization serialization, const std::string& what) {
  ByteReader reader = messageReader(message, serialization, what);
  std::vector<StampedPose> poses;
  std::vector<PoseFields> fields;
  if (type == "nav_msgs/Path") {
    readHeader(reader);
    const std::uint32_t count = reader.count(16 + 56);
    for (std::uint32_t k = 0; k < count; ++k) {
      const Header header = readHeader(reader);
      poses.push_back({header.stamp, Pose(), header.frame_id, ""});
      fields.push_back(readPoseFields(reader, "poses[" + std::to_string(k) + "].pose"));
    }
  } else {
    const Header header = readHeader(reader);
    StampedPose pose{header.stamp, Pose(), header.frame_id, ""};
    if (type == "nav_msgs/Odometry") pose.child_frame_id = reader.string();
    fields.push_back(readPoseFields(reader, type == "geometry_msgs/PoseStamped" ? "pose" : "pose.pose"));
    if (type == "nav_msgs/Odometry") {
      reader.skip(36 * 8);          // pose covariance
      reader.skip(6 * 8 + 36 * 8);  // twist and its covariance
    } else if (type == "geometry_msgs/PoseWithCovarianceStamped") {
      reader.skip(36 * 8);
    }
    poses.push_back(pose);
  }
  expectEnd(reader, type);
  for (std::size_t k = 0; k < poses.size(); ++k) poses[k].pose = toPose(fields[k], what);
  return poses;
}

}  // namespace

std::string rosTypeName(const std::string& type) {
  const std::size_t at = type.find("/msg/");
  return at == std::string::npos ? type : type.substr(0, at) + "/" + type.substr(at + 5);
}

PointCloud2View decodePointCloud2(const std::vector<std::uint8_t>& message, Serialization serialization,
                                  const std::string& what) {
  return decodeAs(kPointCloud2, [&] { return decodePointCloud2Message(message, serialization, what); });
}

std::vector<StampedPose> decodePoses(const std::string& type, const std::vector<std::uint8_t>& message,
                                     Serialization serialization, const std::string& what) {
  if (!isTrajectoryType(type)) throw Error(what + ": " + type + " is not a trajectory type hba reads");
  return decodeAs(type, [&] { return decodeTrajectory(type, message, serialization, what); });
}

std::vector<StampedPose> decodeTransforms(const std::vector<std::uint8_t>& message,
                                          Serialization serialization, const std::string& what) {
  return decodeAs(kTfMessage, [&] {
    ByteReader reader = messageReader(message, serialization, what);
    std::vector<StampedPose> transforms;
    std::vector<PoseFields> fields;
    const std::uint32_t count = reader.count(16 + 4 + 56);
    for (std::uint32_t k = 0; k < count; ++k) {
      const Header header = readHeader(reader);
      transforms.push_back({header.stamp, Pose(), header.frame_id, reader.string()});
      // A Transform is laid out as a Pose.
      fields.push_back(readPoseFields(reader, "transforms[" + std::to_string(k) + "].transform", true));
    }
    expectEnd(reader, kTfMessage);
    for (std::size_t k = 0; k < transforms.size(); ++k) transforms[k].pose = toPose(fields[k], what);
    return transforms;
  });
}

namespace {
bool isLivoxType(const std::string& type) {
  return type == kLivoxCustom || type == "livox_ros_driver2/CustomMsg";
}
}  // namespace

bool isCloudType(const std::string& type) { return type == kPointCloud2 || isLivoxType(type); }

CloudHeader decodeCloudHeader(const std::string& type, const std::vector<std::uint8_t>& message,
                              Serialization serialization, const std::string& what) {
  if (isLivoxType(type)) {
    const LivoxCloud livox = decodeLivox(message, serialization, what, false);
    return {livox.stamp, livox.frame_id, {"offset_time", "x", "y", "z", "reflectivity", "tag", "line"}};
  }
  const PointCloud2View view = decodePointCloud2(message, serialization, what);
  CloudHeader header{view.stamp, view.frame_id, {}};
  for (const PointField& field : view.fields) header.fields.push_back(field.name);
  return header;
}

PointCloud decodeCloud(const std::string& type, const std::vector<std::uint8_t>& message,
                       Serialization serialization, const std::string& what) {
  if (isLivoxType(type)) return decodeLivox(message, serialization, what, true).points;
  return toPointCloud(decodePointCloud2(message, serialization, what), what);
}

bool isTrajectoryType(const std::string& type) {
  return type == "nav_msgs/Odometry" || type == "geometry_msgs/PoseStamped" ||
         type == "geometry_msgs/PoseWithCovarianceStamped" || type == "nav_msgs/Path";
}

}  // namespace hba::rec
