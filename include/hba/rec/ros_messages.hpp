#pragma once
// The few ROS message types hba reads, decoded from ROS 1's serialization
// or ROS 2's (CDR): point clouds (sensor_msgs/PointCloud2) and trajectories
// (nav_msgs/Odometry, geometry_msgs/PoseStamped and
// PoseWithCovarianceStamped, nav_msgs/Path). Types are named as ROS 1 does
// ("sensor_msgs/PointCloud2"; rosTypeName turns ROS 2's names into these).
// A message shorter or longer than its type says throws hba::Error naming
// `what`.
#include <cstdint>
#include <string>
#include <vector>

#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

namespace hba::rec {

enum class Serialization { Ros1, Cdr };

// "sensor_msgs/msg/PointCloud2" -> "sensor_msgs/PointCloud2"; others as they are.
std::string rosTypeName(const std::string& type);

struct PointField {
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;  // 1 int8 .. 6 uint32, 7 float32, 8 float64
  std::uint32_t count = 1;
};

// A PointCloud2's layout and a view of its data (inside the message bytes).
struct PointCloud2View {
  double stamp = 0.0;  // the header's, s
  std::string frame_id;
  std::uint32_t height = 0, width = 0;
  std::vector<PointField> fields;
  bool big_endian = false;
  std::uint32_t point_step = 0, row_step = 0;
  const std::uint8_t* data = nullptr;
  std::size_t data_size = 0;
};

inline constexpr const char* kPointCloud2 = "sensor_msgs/PointCloud2";

PointCloud2View decodePointCloud2(const std::vector<std::uint8_t>& message, Serialization serialization,
                                  const std::string& what);

// The points of a PointCloud2 in its own frame: x, y, z (float32 or
// float64, either byte order, any padding), intensity (or reflectivity)
// and each point's time as stored (a field of kPointTimeFields) when
// present; points with a non-finite coordinate are left out.
PointCloud toPointCloud(const PointCloud2View& cloud, const std::string& what);

// Livox's own cloud: livox_ros_driver/CustomMsg (livox_ros_driver2's in ROS 2).
inline constexpr const char* kLivoxCustom = "livox_ros_driver/CustomMsg";
// True for the point cloud types hba reads: PointCloud2 and Livox's CustomMsg.
bool isCloudType(const std::string& type);

// A cloud message of either type without its points: stamp, frame and the
// names of its point fields.
struct CloudHeader {
  double stamp = 0.0;
  std::string frame_id;
  std::vector<std::string> fields;
};
CloudHeader decodeCloudHeader(const std::string& type, const std::vector<std::uint8_t>& message,
                              Serialization serialization, const std::string& what);
// The points of a cloud message of either type, as toPointCloud reads them
// (a CustomMsg: reflectivity as intensity, offset_time as the time; the
// driver's all-zero points for missing returns left out).
PointCloud decodeCloud(const std::string& type, const std::vector<std::uint8_t>& message,
                       Serialization serialization, const std::string& what);

struct StampedPose {
  double stamp = 0.0;
  Pose pose;
  std::string frame_id;        // the frame the pose is in
  std::string child_frame_id;  // the body it places (Odometry only)
};

// tf2_msgs/TFMessage: each transform places child_frame_id in frame_id.
inline constexpr const char* kTfMessage = "tf2_msgs/TFMessage";
std::vector<StampedPose> decodeTransforms(const std::vector<std::uint8_t>& message,
                                          Serialization serialization, const std::string& what);

// True for the trajectory types decodePoses reads.
bool isTrajectoryType(const std::string& type);
// The poses of one trajectory message: one, or a Path's all.
std::vector<StampedPose> decodePoses(const std::string& type, const std::vector<std::uint8_t>& message,
                                     Serialization serialization, const std::string& what);

}  // namespace hba::rec
