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
// A message that parses but holds a value no pose can have (a NaN position,
// a zero quaternion): said as it is, not as a definition that does not match.
class BadFieldValue : public Error {
 public:
  using Error::Error;
};

// geometry_msgs/Pose (or, with `transform`, a Transform: translation and
// rotation) as stored; `field` names it in messages ("pose.pose" of an
// Odometry).
struct PoseFields {
  std::string field;
  bool transform = false;
  Vec3 position = Vec3::Zero();
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
};
PoseFields readPoseFields(ByteReader& reader, const std::string& field, bool transform = false);
// The pose, once the whole message has parsed (a message of another layout
// is said to be one, not a NaN): a finite position and the quaternion
// renormalized, as pose files' are. Throws BadFieldValue naming `what` and
// the field for a non-finite number or a quaternion of (near) zero length.
Pose toPose(const PoseFields& fields, const std::string& what);
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
  } catch (const BadFieldValue&) {
    throw;
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + ": the message does not match the definition of " + type);
  }
}

}  // namespace hba::rec::detail
