#pragma once
// Private to the rec module: the pieces every message decoder shares.
#include <cstdint>
#include <string>
#include <vector>

#include "byte_reader.hpp"
#include "hba/core/error.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/rec/ros_messages.hpp"

namespace hba::rec::detail {

struct Header {
  double stamp = 0.0;
  std::string frame_id;
};

// A reader of one message: CDR after its 4-byte encapsulation header.
ByteReader messageReader(const std::vector<std::uint8_t>& message, Serialization serialization,
                         const std::string& what);
// std_msgs/Header (ROS 1's with its seq).
Header readHeader(ByteReader& reader);
// geometry_msgs/Pose (or Transform): a position and a unit quaternion.
Pose readPose(ByteReader& reader);
// Refuses bytes left after a message of `type` (CDR's zero padding aside).
void expectEnd(ByteReader& reader, const std::string& type);

// A livox_ros_driver CustomMsg: its header and (with_points) its points,
// each with its offset_time (ns after the stamp) as its time.
struct LivoxCloud {
  double stamp = 0.0;
  std::string frame_id;
  PointCloud points;
};
LivoxCloud decodeLivox(const std::vector<std::uint8_t>& message, Serialization serialization,
                       const std::string& what, bool with_points);

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

}  // namespace hba::rec::detail
