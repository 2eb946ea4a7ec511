// livox_ros_driver's CustomMsg (livox_ros_driver2's in ROS 2): the Livox
// driver's own point cloud, each point with its time after the message's
// first (offset_time, ns), reflectivity, tag and line.
#include "message_parts.hpp"

namespace hba::rec {
namespace detail {

LivoxCloud decodeLivox(const std::vector<std::uint8_t>& message, Serialization serialization,
                       const std::string& what, bool with_points) {
  return decodeAs(kLivoxCustom, [&] {
    ByteReader reader = messageReader(message, serialization, what);
    LivoxCloud cloud;
    const Header header = readHeader(reader);
    cloud.stamp = header.stamp;
    cloud.frame_id = header.frame_id;
    reader.u64();                                  // timebase: the first point's time, ns
    reader.u32();                                  // point_num
    for (int k = 0; k < 4; ++k) reader.u8();       // lidar_id, rsvd[3]
    const std::uint32_t count = reader.count(19);  // offset_time, x y z, reflectivity, tag, line
    if (!with_points) return cloud;
    cloud.points.reserve(count, true);
    cloud.points.time.reserve(count);
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t offset_time = reader.u32();
      const float x = reader.read<float>(), y = reader.read<float>(), z = reader.read<float>();
      const std::uint8_t reflectivity = reader.u8();
      reader.u8();  // tag
      reader.u8();  // line
      const Vec3f p(x, y, z);
      // The driver fills a sweep's missing returns with zeros.
      if (!p.allFinite() || p.isZero()) continue;
      cloud.points.add(p, static_cast<float>(reflectivity));
      cloud.points.time.push_back(static_cast<double>(offset_time));
    }
    expectEnd(reader, kLivoxCustom);
    return cloud;
  });
}

}  // namespace detail
}  // namespace hba::rec
