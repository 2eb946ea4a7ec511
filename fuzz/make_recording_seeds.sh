#!/usr/bin/env bash
# Writes the seeds of the recording fuzz targets with the tests' own writers
# (tests/rec: Debian's python3-rosbag, npm's @foxglove/rosmsg2-serialization,
# Python's sqlite3) from a scan folder as tests/rec/bag_fixture.hpp writes
# one, only smaller (3 scans of 24 points, binary PCD x y z intensity):
#   fuzz/corpus/fuzz_ros1_bag/*.bag        one bag per layout, compression and trajectory type
#   fuzz/corpus/fuzz_db3/*.db3             a ROS 2 sqlite3 bag
#   fuzz/corpus/fuzz_rosbag2_metadata/*    metadata.yaml naming run_0.db3
#   fuzz/fixtures/run_0.db3                the .db3 that metadata seeds are put beside
#   fuzz/corpus/fuzz_ros_message/*         each topic's first message, its kind byte first
# A writer that is missing (exit 77) leaves its seeds out.
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scans=$work/scans
python=/usr/bin/python3
[ -x "$python" ] || python=python3
"$python" - "$scans" <<'PY'
import math, os, random, struct, sys
folder = sys.argv[1]
os.makedirs(os.path.join(folder, "Scans"))
rng = random.Random(7)
with open(os.path.join(folder, "odom_poses.txt"), "w") as poses, \
     open(os.path.join(folder, "times.txt"), "w") as times:
    for k in range(3):
        points = [(rng.uniform(-30, 30), rng.uniform(-30, 30), rng.uniform(-30, 30), rng.randint(0, 255))
                  for _ in range(24)]
        header = ("VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                  "WIDTH %d\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS %d\nDATA binary\n" % (len(points), len(points)))
        with open(os.path.join(folder, "Scans", "%06d.pcd" % k), "wb") as f:
            f.write(header.encode() + b"".join(struct.pack("<4f", *p) for p in points))
        a = 0.07 * k  # turning about z, moving along y
        c, s = math.cos(a), math.sin(a)
        poses.write("%.17g %.17g 0 %.17g %.17g %.17g 0 %.17g 0 0 1 %.17g\n" % (c, -s, 2 * math.sin(a), s, c, 3 * a, 0.1 * a))
        times.write("%.17g\n" % (1600000000.0 + 0.1 * k))
PY
corpus=fuzz/corpus
mkdir -p "$corpus/fuzz_ros1_bag" "$corpus/fuzz_db3" "$corpus/fuzz_rosbag2_metadata" \
         "$corpus/fuzz_ros_message" fuzz/fixtures

bag() {
  local name=$1
  shift
  "$python" tests/rec/write_ros1_bag.py "$scans" "$work/$name.bag" "$@" >/dev/null || return 0
  cp "$work/$name.bag" "$corpus/fuzz_ros1_bag/"
}
bag fastlio_odometry
bag fastlio_lz4 --compression lz4
bag fastlio_bz2 --compression bz2
bag float64_big_endian_posestamped --layout float64 --big-endian --pose-type posestamped
bag ouster_posecov --layout ouster --pose-type posecov
bag livox_custom --layout livox
bag growing_path --pose-type path
bag tf_with_static --pose-type tf --tf-static "0.1 0 0.05 0 0 0 1"
bag two_cloud_topics --second-cloud-topic

if bash tests/rec/write_mcap.sh "$scans" "$work/messages.jsonl" cdr >/dev/null &&
   "$python" tests/rec/write_db3.py "$work/messages.jsonl" "$work/rosbag2"; then
  cp "$work/rosbag2/run_0.db3" "$corpus/fuzz_db3/fastlio.db3"
  cp "$work/rosbag2/run_0.db3" fuzz/fixtures/run_0.db3
  cp "$work/rosbag2/metadata.yaml" "$corpus/fuzz_rosbag2_metadata/written_by_tests.yaml"
fi
# As ROS 2 Humble's recorder writes it, every section present.
cat > "$corpus/fuzz_rosbag2_metadata/humble_recorder.yaml" <<'YAML'
rosbag2_bagfile_information:
  version: 5
  storage_identifier: sqlite3
  duration:
    nanoseconds: 200000000
  starting_time:
    nanoseconds_since_epoch: 1600000000000000000
  message_count: 6
  topics_with_message_count:
    - topic_metadata:
        name: /cloud_registered_body
        type: sensor_msgs/msg/PointCloud2
        serialization_format: cdr
        offered_qos_profiles: "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n  avoid_ros_namespace_conventions: false"
      message_count: 3
    - topic_metadata:
        name: /Odometry
        type: nav_msgs/msg/Odometry
        serialization_format: cdr
        offered_qos_profiles: ""
      message_count: 3
  compression_format: ""
  compression_mode: ""
  relative_file_paths:
    - run_0.db3
  files:
    - path: run_0.db3
      starting_time:
        nanoseconds_since_epoch: 1600000000000000000
      duration:
        nanoseconds: 200000000
      message_count: 6
  custom_data: ~
YAML

# Each topic's first message, prefixed by the byte feedRosMessage reads
# (fuzz/harness_recordings.cpp): 2 * type + (0 ROS 1, 1 CDR).
"$python" - "$corpus/fuzz_ros_message" "$corpus"/fuzz_ros1_bag/*.bag "$corpus"/fuzz_db3/*.db3 <<'PY'
import os, sqlite3, sys
TYPES = ["sensor_msgs/PointCloud2", "livox_ros_driver/CustomMsg", "livox_ros_driver2/CustomMsg",
         "nav_msgs/Odometry", "geometry_msgs/PoseStamped", "geometry_msgs/PoseWithCovarianceStamped",
         "nav_msgs/Path", "tf2_msgs/TFMessage"]
out = sys.argv[1]
written = set()
def save(source, topic, type_name, cdr, data):
    if type_name not in TYPES or data in written:
        return
    written.add(data)
    name = "%s_%s_%s" % (os.path.splitext(os.path.basename(source))[0], topic.strip("/").replace("/", "_"),
                         "cdr" if cdr else "ros1")
    with open(os.path.join(out, name), "wb") as f:
        f.write(bytes([2 * TYPES.index(type_name) + (1 if cdr else 0)]) + data)
for path in sys.argv[2:]:
    seen = set()
    if path.endswith(".bag"):
        import rosbag
        with rosbag.Bag(path) as bag:
            for topic, raw, _ in bag.read_messages(raw=True):
                if topic not in seen:
                    seen.add(topic)
                    save(path, topic, raw[0], False, raw[1])
    else:
        db = sqlite3.connect(path)
        for topic, type_name, data in db.execute(
                "SELECT t.name, t.type, m.data FROM messages m JOIN topics t ON t.id = m.topic_id ORDER BY m.id"):
            if topic not in seen:
                seen.add(topic)
                save(path, topic, type_name.replace("/msg/", "/"), True, data)
PY
ls -l "$corpus"/fuzz_ros1_bag "$corpus"/fuzz_db3 "$corpus"/fuzz_rosbag2_metadata "$corpus"/fuzz_ros_message
