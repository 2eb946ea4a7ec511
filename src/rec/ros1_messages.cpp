#include "hba/rec/ros1_messages.hpp"

#include "byte_reader.hpp"
#include "hba/core/error.hpp"

namespace hba::rec {
namespace {

struct Header {
  double stamp = 0.0;
  std::string frame_id;
};

Header readHeader(ByteReader& reader) {
  Header header;
  reader.u32();  // seq
  header.stamp = reader.time();
  header.frame_id = reader.string();
  return header;
}

Pose readPose(ByteReader& reader) {
  Vec3 t;
  for (int k = 0; k < 3; ++k) t[k] = reader.f64();
  const double x = reader.f64(), y = reader.f64(), z = reader.f64(), w = reader.f64();
  Quat q(w, x, y, z);
  const double norm = q.norm();
  if (!(norm > 0.5 && norm < 1.5))
    reader.fail("a pose whose quaternion is not a rotation (norm " + std::to_string(norm) + ")");
  return Pose(q.normalized(), t);
}

void expectEnd(const ByteReader& reader, const std::string& type) {
  if (reader.remaining() != 0)
    reader.fail(std::to_string(reader.remaining()) + " bytes left after a " + type);
}

// A message that does not parse as its type says so: the recorder's
// definition does not match its data (or the bag is corrupt).
template <typename Decode>
auto decodeAs(const std::string& type, Decode decode) {
  try {
    return decode();
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + ": the message does not match the definition of " + type);
  }
}

PointCloud2View decodeCloud(const std::vector<std::uint8_t>& message, const std::string& what) {
  ByteReader reader(message.data(), message.size(), what);
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
  if (std::uint64_t{cloud.height} * cloud.row_step > cloud.data_size ||
      (points > 0 && cloud.point_step == 0) ||
      std::uint64_t{cloud.width} * cloud.point_step > cloud.row_step) {
    reader.fail("a PointCloud2 of " + std::to_string(cloud.height) + " x " + std::to_string(cloud.width) +
                " points of " + std::to_string(cloud.point_step) + " bytes (rows of " +
                std::to_string(cloud.row_step) + ") in " + std::to_string(cloud.data_size) +
                " bytes of data");
  }
  return cloud;
}

std::vector<StampedPose> decodeTrajectory(const std::string& type, const std::vector<std::uint8_t>& message,
                                          const std::string& what) {
  ByteReader reader(message.data(), message.size(), what);
  std::vector<StampedPose> poses;
  if (type == "nav_msgs/Path") {
    readHeader(reader);
    const std::uint32_t count = reader.count(16 + 56);
    for (std::uint32_t k = 0; k < count; ++k) {
      const Header header = readHeader(reader);
      poses.push_back({header.stamp, readPose(reader), header.frame_id, ""});
    }
  } else {
    const Header header = readHeader(reader);
    StampedPose pose{header.stamp, Pose(), header.frame_id, ""};
    if (type == "nav_msgs/Odometry") pose.child_frame_id = reader.string();
    pose.pose = readPose(reader);
    if (type == "nav_msgs/Odometry") {
      reader.skip(36 * 8);          // pose covariance
      reader.skip(6 * 8 + 36 * 8);  // twist and its covariance
    } else if (type == "geometry_msgs/PoseWithCovarianceStamped") {
      reader.skip(36 * 8);
    }
    poses.push_back(pose);
  }
  expectEnd(reader, type);
  return poses;
}

}  // namespace

PointCloud2View decodePointCloud2(const std::vector<std::uint8_t>& message, const std::string& what) {
  return decodeAs(kPointCloud2, [&] { return decodeCloud(message, what); });
}

std::vector<StampedPose> decodePoses(const std::string& type, const std::vector<std::uint8_t>& message,
                                     const std::string& what) {
  if (!isTrajectoryType(type)) throw Error(what + ": " + type + " is not a trajectory type hba reads");
  return decodeAs(type, [&] { return decodeTrajectory(type, message, what); });
}

bool isTrajectoryType(const std::string& type) {
  return type == "nav_msgs/Odometry" || type == "geometry_msgs/PoseStamped" ||
         type == "geometry_msgs/PoseWithCovarianceStamped" || type == "nav_msgs/Path";
}

}  // namespace hba::rec
