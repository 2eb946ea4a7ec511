#!/usr/bin/env python3
"""Writes a scan folder (binary PCD x y z intensity + KITTI poses + times.txt)
into a ROS 1 bag with Debian's python3-rosbag, the way FAST-LIO2 records it:
/cloud_registered_body (sensor_msgs/PointCloud2, PCL's PointXYZINormal
layout: padding, normals, curvature) and /Odometry (nav_msgs/Odometry), plus
a topic hba has no use for. Variants exercise other layouts and mistakes.
Exit 77 when python3-rosbag is missing (the tests then skip)."""
import argparse
import glob
import io
import os
import struct
import sys

try:
    import numpy as np
    import rosbag
    import rospy
    from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped
    from nav_msgs.msg import Path
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import PointCloud2, PointField
    from std_msgs.msg import String
    from geometry_msgs.msg import TransformStamped
except ImportError as error:  # skip, not fail
    print("skip: " + str(error))
    sys.exit(77)


def read_pcd(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"DATA binary\n") + len(b"DATA binary\n")
    header = data[:end].decode()
    fields = next(l for l in header.splitlines() if l.startswith("FIELDS")).split()[1:]
    assert fields == ["x", "y", "z", "intensity"], fields
    return np.frombuffer(data[end:], dtype="<f4").reshape(-1, 4)


def quaternion(r):
    # from a rotation matrix (w x y z), the largest-component branch
    t = np.trace(r)
    if t > 0:
        s = 2.0 * np.sqrt(t + 1.0)
        return (0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s)
    i = int(np.argmax(np.diag(r)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * np.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k])
    q = [0.0, 0.0, 0.0, 0.0]
    q[0] = (r[k, j] - r[j, k]) / s
    q[1 + i] = 0.25 * s
    q[1 + j] = (r[j, i] + r[i, j]) / s
    q[1 + k] = (r[k, i] + r[i, k]) / s
    return tuple(q)


LIVOX_DEFINITION = """std_msgs/Header header
uint64 timebase
uint32 point_num
uint8 lidar_id
uint8[3] rsvd
CustomPoint[] points
================================================================================
MSG: std_msgs/Header
uint32 seq
time stamp
string frame_id
================================================================================
MSG: livox_ros_driver/CustomPoint
uint32 offset_time
float32 x
float32 y
float32 z
uint8 reflectivity
uint8 tag
uint8 line
"""


def livox_message(points, stamp, frame):
    """livox_ros_driver/CustomMsg, as the Livox driver publishes it: offset_time in ns after
    the stamp, reflectivity, and one all-zero point (a missing return) at the end."""
    import genpy.dynamic
    classes = genpy.dynamic.generate_dynamic("livox_ros_driver/CustomMsg", LIVOX_DEFINITION)
    message, point = classes["livox_ros_driver/CustomMsg"], classes["livox_ros_driver/CustomPoint"]
    msg = message()
    msg.header.stamp, msg.header.frame_id = stamp, frame
    msg.timebase = stamp.to_nsec()
    msg.lidar_id, msg.rsvd = 0, [0, 0, 0]
    msg.points = [point(offset_time=n * 100000000 // len(points), x=float(p[0]), y=float(p[1]), z=float(p[2]),
                        reflectivity=int(min(255, max(0, p[3]))), tag=16, line=n % 6)
                  for n, p in enumerate(points)]
    msg.points.append(point(offset_time=100000000, x=0.0, y=0.0, z=0.0, reflectivity=0, tag=0, line=0))
    msg.point_num = len(msg.points)
    return msg


def cloud_message(points, stamp, layout, big_endian, frame="body"):
    if layout == "livox":
        return livox_message(points, stamp, frame)
    msg = PointCloud2()
    msg.header.stamp = stamp
    msg.header.frame_id = frame
    msg.height, msg.width = 1, len(points)
    order = ">" if big_endian else "<"
    if layout == "fastlio":  # PointXYZINormal: x y z pad, nx ny nz pad, intensity curvature pad pad
        names = [("x", 0), ("y", 4), ("z", 8), ("normal_x", 16), ("normal_y", 20), ("normal_z", 24),
                 ("intensity", 32), ("curvature", 36)]
        msg.fields = [PointField(n, o, PointField.FLOAT32, 1) for n, o in names]
        step, kind = 48, "f4"
        table = np.zeros((len(points), 12), dtype=order + "f4")
        table[:, 0:3] = points[:, 0:3]
        table[:, 8] = points[:, 3]
    elif layout == "float64":  # x y z as float64, a uint16 ring, intensity as uint8
        msg.fields = [PointField("x", 0, PointField.FLOAT64, 1), PointField("y", 8, PointField.FLOAT64, 1),
                      PointField("z", 16, PointField.FLOAT64, 1), PointField("ring", 24, PointField.UINT16, 1),
                      PointField("intensity", 26, PointField.UINT8, 1)]
        step = 32
        buf = bytearray(step * len(points))
        for n, p in enumerate(points):
            struct.pack_into(order + "dddHB", buf, n * step, float(p[0]), float(p[1]), float(p[2]), n % 32,
                             int(min(255, max(0, p[3]))))
        msg.is_bigendian, msg.point_step, msg.row_step = big_endian, step, step * len(points)
        msg.data = bytes(buf)
        msg.is_dense = True
        return msg
    elif layout == "ouster":  # x y z pad intensity, t (uint32 ns since the stamp), reflectivity, ring
        msg.fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("y", 4, PointField.FLOAT32, 1),
                      PointField("z", 8, PointField.FLOAT32, 1), PointField("intensity", 16, PointField.FLOAT32, 1),
                      PointField("t", 20, PointField.UINT32, 1), PointField("reflectivity", 24, PointField.UINT16, 1),
                      PointField("ring", 26, PointField.UINT8, 1)]
        step = 32
        buf = bytearray(step * len(points))
        for n, p in enumerate(points):
            # The points spread evenly over a 0.1 s sweep, in order.
            struct.pack_into(order + "fff4xfIHB", buf, n * step, float(p[0]), float(p[1]), float(p[2]), float(p[3]),
                             n * 100000000 // len(points), 7, n % 64)
        msg.is_bigendian, msg.point_step, msg.row_step = big_endian, step, step * len(points)
        msg.data = bytes(buf)
        msg.is_dense = True
        return msg
    else:
        raise ValueError(layout)
    msg.is_bigendian, msg.point_step, msg.row_step = big_endian, step, step * len(points)
    msg.data = table.tobytes()
    msg.is_dense = True
    return msg


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("folder")
    parser.add_argument("bag")
    parser.add_argument("--compression", default="none", choices=["none", "lz4", "bz2"])
    parser.add_argument("--layout", default="fastlio", choices=["fastlio", "float64", "ouster", "livox"])
    parser.add_argument("--big-endian", action="store_true")
    parser.add_argument("--scans", type=int, default=0, help="only the first N")
    parser.add_argument("--second-cloud-topic", action="store_true")
    parser.add_argument("--pose-type", default="odometry", choices=["odometry", "posestamped", "posecov", "path", "tf", "none"],
                        help="path: every pose in nav_msgs/Path messages that grow (as a SLAM system republishes it)")
    parser.add_argument("--pose-shift", type=float, default=0.0, help="seconds added to the poses' stamps")
    parser.add_argument("--repeat", type=int, default=1,
                        help="the sequence N times, each later by its duration (large bags for benchmarks)")
    parser.add_argument("--repeat-shift", type=float, default=0.0,
                        help="metres each repetition is moved along x (apart, so they never meet)")
    parser.add_argument("--tf-static", default="",
                        help="'x y z qx qy qz qw': the clouds in frame lidar, placed in body by /tf_static")
    parser.add_argument("--world-frame", action="store_true",
                        help="clouds moved into the world by their pose (FAST-LIO2's /cloud_registered)")
    parser.add_argument("--mismatch", action="store_true",
                        help="/Odometry messages that hold a PoseStamped's bytes (a definition that does not match)")
    # Faults in one message (issue #57), K counting the scans from 0:
    parser.add_argument("--bad-position", default="",
                        help="'K VALUE': the odometry's position.y in message K is VALUE (nan, inf)")
    parser.add_argument("--quaternion-scale", type=float, default=1.0,
                        help="every odometry quaternion multiplied by this (3: not unit length; 0: none)")
    parser.add_argument("--same-stamp", type=int, default=-1,
                        help="odometry message K stamped as message K-1 (two poses at one stamp)")
    parser.add_argument("--republish", type=int, default=-1,
                        help="odometry message K written twice, stamp and pose alike")
    parser.add_argument("--reverse-stamps", default="", choices=["", "cloud", "odometry"],
                        help="that topic's stamps in reverse order (they run backwards)")
    parser.add_argument("--long-cloud", type=int, default=-1,
                        help="cloud message K's data twice as long as width x point_step says")
    parser.add_argument("--tf-static-back", default="",
                        help="'x y z qx qy qz qw': /tf_static also places body in lidar (a cycle)")
    args = parser.parse_args()
    if args.layout == "livox":
        try:
            import genpy.dynamic  # noqa: F401  (Livox's message type is made at run time)
        except ImportError as error:
            print("skip: " + str(error))
            return 77

    scans = sorted(glob.glob(os.path.join(args.folder, "Scans", "*.pcd")))
    poses = np.loadtxt(os.path.join(args.folder, "odom_poses.txt")).reshape(-1, 3, 4)
    times = np.loadtxt(os.path.join(args.folder, "times.txt"))
    if args.scans:
        scans, poses, times = scans[: args.scans], poses[: args.scans], times[: args.scans]
    cloud_times = times[::-1] if args.reverse_stamps == "cloud" else times
    odometry_times = times[::-1] if args.reverse_stamps == "odometry" else times.copy()
    if args.same_stamp > 0:
        odometry_times[args.same_stamp] = odometry_times[args.same_stamp - 1]
    span = float(times[-1] - times[0]) + 1.0
    clouds = {}
    path_so_far = []
    with rosbag.Bag(args.bag, "w", compression=args.compression) as bag:
        for n, (scan, pose, t) in enumerate(
                (s, p + np.array([[0, 0, 0, r * args.repeat_shift], [0, 0, 0, 0], [0, 0, 0, 0]]), t + r * span)
                for r in range(args.repeat) for s, p, t in zip(scans, poses, times)):
            stamp = rospy.Time.from_sec(float(t))
            if scan not in clouds:
                clouds[scan] = read_pcd(scan)
            if n == 0 and args.tf_static:
                try:
                    from tf2_msgs.msg import TFMessage
                except ImportError as error:
                    print("skip: " + str(error))
                    return 77
                # As robot_state_publisher latches it: once, before the data.
                v = [float(x) for x in args.tf_static.split()]
                t_static = TransformStamped()
                t_static.header.stamp = stamp
                t_static.header.frame_id, t_static.child_frame_id = "body", "lidar"
                t_static.transform.translation.x, t_static.transform.translation.y, t_static.transform.translation.z = v[:3]
                r = t_static.transform.rotation
                r.x, r.y, r.z, r.w = v[3:]
                transforms = [t_static]
                if args.tf_static_back:
                    v = [float(x) for x in args.tf_static_back.split()]
                    back = TransformStamped()
                    back.header.stamp = stamp
                    back.header.frame_id, back.child_frame_id = "lidar", "body"
                    back.transform.translation.x, back.transform.translation.y, back.transform.translation.z = v[:3]
                    r = back.transform.rotation
                    r.x, r.y, r.z, r.w = v[3:]
                    transforms.append(back)
                bag.write("/tf_static", TFMessage(transforms=transforms), stamp)
            points = clouds[scan]
            if args.world_frame:
                points = points.copy()
                points[:, 0:3] = points[:, 0:3] @ pose[:, :3].T + pose[:, 3]
            shift = t - times[n % len(times)]  # of the repetition
            cloud = cloud_message(points, rospy.Time.from_sec(float(cloud_times[n % len(times)] + shift)),
                                  args.layout, args.big_endian, "lidar" if args.tf_static else "body")
            if n == args.long_cloud:
                cloud.data = bytes(cloud.data) * 2
            bag.write("/cloud_registered_body", cloud, stamp)
            if args.second_cloud_topic:
                bag.write("/cloud_registered", cloud, stamp)
            if args.pose_type == "tf":
                # odom -> body at each scan (with ROS 1's leading slash), and a wheel every other scan.
                from tf2_msgs.msg import TFMessage
                w, x, y, z = quaternion(pose[:, :3])
                body = TransformStamped()
                body.header.stamp, body.header.frame_id, body.child_frame_id = stamp, "/odom", "body"
                body.transform.translation.x, body.transform.translation.y, body.transform.translation.z = pose[:, 3]
                r = body.transform.rotation
                r.x, r.y, r.z, r.w = x, y, z, w
                transforms = [body]
                if n % 2 == 0:
                    wheel = TransformStamped()
                    wheel.header.stamp, wheel.header.frame_id, wheel.child_frame_id = stamp, "body", "wheel"
                    wheel.transform.rotation.w = 1.0
                    transforms.append(wheel)
                bag.write("/tf", TFMessage(transforms=transforms), stamp)
            elif args.pose_type != "none":
                kinds = {"odometry": Odometry, "posestamped": PoseStamped, "posecov": PoseWithCovarianceStamped,
                         "path": PoseStamped}
                odo = kinds[args.pose_type]()
                odo.header.stamp = rospy.Time.from_sec(float(odometry_times[n % len(times)] + shift) + args.pose_shift)
                odo.header.frame_id = "camera_init"
                target = odo.pose if args.pose_type in ("posestamped", "path") else odo.pose.pose
                if args.pose_type == "odometry":
                    odo.child_frame_id = "body"
                w, x, y, z = quaternion(pose[:, :3])
                target.position.x, target.position.y, target.position.z = pose[:, 3]
                s = args.quaternion_scale
                target.orientation.x, target.orientation.y, target.orientation.z, target.orientation.w = s * x, s * y, s * z, s * w
                if args.bad_position and int(args.bad_position.split()[0]) == n:
                    target.position.y = float(args.bad_position.split()[1])
                if args.mismatch:
                    wrong = PoseStamped(header=odo.header, pose=odo.pose.pose)
                    buffer = io.BytesIO()
                    wrong.serialize(buffer)
                    raw = ("nav_msgs/Odometry", buffer.getvalue(), Odometry._md5sum, Odometry)
                    bag.write("/Odometry", raw, stamp, raw=True)
                elif args.pose_type == "path":
                    # The whole path so far, every scan: only the last message counts.
                    path_so_far.append(odo)
                    bag.write("/path", Path(header=odo.header, poses=list(path_so_far)), stamp)
                else:
                    for _ in range(2 if n == args.republish else 1):
                        bag.write("/Odometry" if args.pose_type == "odometry" else "/pose", odo, stamp)
            if n % 50 == 0:
                bag.write("/rosout_agg", String(data="scan %d" % n), stamp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
