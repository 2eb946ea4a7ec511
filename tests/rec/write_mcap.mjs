// Writes a scan folder (binary PCD x y z intensity, KITTI poses, times.txt)
// into an MCAP file as ROS 2 records it, with the npm packages @mcap/core
// (the container) and @foxglove/rosmsg2-serialization (CDR), not with hba:
// /cloud_registered_body (sensor_msgs/msg/PointCloud2, PCL's PointXYZINormal
// layout) and /Odometry (nav_msgs/msg/Odometry).
// usage: node write_mcap.mjs FOLDER OUT.mcap [zstd|lz4|none|cdr] [N] [LAYOUT]
// "cdr" writes no MCAP but the CDR messages themselves, as JSON lines
// (topic, type, time in ns, base64 data) for write_db3.py to store.
// LAYOUT: "indexed" (the writer's defaults: a summary with chunk indexes and
// statistics, message indexes after each chunk, CRCs), "no-summary" (the
// same data section, no summary), "no-message-index" (chunk indexes but no
// message indexes) or "unfinished" (the writer never ended: the chunks
// written so far, no summary, no footer, as a recorder that was killed
// leaves it).
import fs from "node:fs";
import path from "node:path";
import { McapWriter } from "@mcap/core";
import { parse } from "@foxglove/rosmsg";
import { MessageWriter } from "@foxglove/rosmsg2-serialization";
import zstd from "@foxglove/wasm-zstd";
import lz4 from "lz4js";

const [folder, out, compression = "zstd", limit = "0", layout = "indexed"] = process.argv.slice(2);
if (!["indexed", "no-summary", "no-message-index", "unfinished"].includes(layout)) throw new Error(`layout ${layout}`);

const header = `
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec`;
const cloudDefinition = `std_msgs/Header header
uint32 height
uint32 width
sensor_msgs/PointField[] fields
bool is_bigendian
uint32 point_step
uint32 row_step
uint8[] data
bool is_dense${header}
================================================================================
MSG: sensor_msgs/PointField
string name
uint32 offset
uint8 datatype
uint32 count`;
const odometryDefinition = `std_msgs/Header header
string child_frame_id
geometry_msgs/PoseWithCovariance pose
geometry_msgs/TwistWithCovariance twist${header}
================================================================================
MSG: geometry_msgs/PoseWithCovariance
geometry_msgs/Pose pose
float64[36] covariance
================================================================================
MSG: geometry_msgs/Pose
geometry_msgs/Point position
geometry_msgs/Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
================================================================================
MSG: geometry_msgs/TwistWithCovariance
geometry_msgs/Twist twist
float64[36] covariance
================================================================================
MSG: geometry_msgs/Twist
geometry_msgs/Vector3 linear
geometry_msgs/Vector3 angular
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z`;

function readPcd(file) {
  const bytes = fs.readFileSync(file);
  const marker = Buffer.from("DATA binary\n");
  const start = bytes.indexOf(marker) + marker.length;
  const fields = bytes.subarray(0, start).toString().split("\n").find((l) => l.startsWith("FIELDS"));
  if (fields.trim() !== "FIELDS x y z intensity") throw new Error(`${file}: ${fields}`);
  const data = bytes.subarray(start);
  return new Float32Array(data.buffer.slice(data.byteOffset, data.byteOffset + data.length));
}

function quaternion(r) {  // r: 3x3 row-major; returns [x, y, z, w]
  const t = r[0] + r[4] + r[8];
  if (t > 0) {
    const s = 2 * Math.sqrt(t + 1);
    return [(r[7] - r[5]) / s, (r[2] - r[6]) / s, (r[3] - r[1]) / s, 0.25 * s];
  }
  const i = r[0] > r[4] ? (r[0] > r[8] ? 0 : 2) : (r[4] > r[8] ? 1 : 2);
  const j = (i + 1) % 3, k = (i + 2) % 3;
  const at = (a, b) => r[3 * a + b];
  const s = 2 * Math.sqrt(1 + at(i, i) - at(j, j) - at(k, k));
  const q = [0, 0, 0, 0];
  q[3] = (at(k, j) - at(j, k)) / s;
  q[i] = 0.25 * s;
  q[j] = (at(j, i) + at(i, j)) / s;
  q[k] = (at(k, i) + at(i, k)) / s;
  return q;
}

function stampOf(seconds) {
  const sec = Math.floor(seconds);
  return { sec, nanosec: Math.round((seconds - sec) * 1e9) };
}

await zstd.isLoaded;
const scans = fs.readdirSync(path.join(folder, "Scans")).filter((f) => f.endsWith(".pcd")).sort();
const poses = fs.readFileSync(path.join(folder, "odom_poses.txt"), "utf8").trim().split("\n").map((l) => l.trim().split(/\s+/).map(Number));
const times = fs.readFileSync(path.join(folder, "times.txt"), "utf8").trim().split("\n").map(Number);
const count = Number(limit) > 0 ? Number(limit) : scans.length;

const fd = fs.openSync(out, "w");
const cdrLines = compression === "cdr";
let position = 0n;
const writable = {
  position: () => position,
  write: async (buffer) => {
    fs.writeSync(fd, buffer);
    position += BigInt(buffer.byteLength);
  },
};
const compressors = {
  zstd: (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) }),
  lz4: (data) => ({ compression: "lz4", compressedData: lz4.compress(data) }),
};
const noSummary = layout === "no-summary";
const writer = new McapWriter({
  writable,
  useChunks: true,
  // Small chunks, so that even the tests' small folders span several
  // (MCAP_CHUNK_BYTES sets another size: the benchmark takes the writer's 1 MiB).
  chunkSize: Number(process.env.MCAP_CHUNK_BYTES || 32 * 1024),
  compressChunk: compressors[compression],
  useMessageIndex: layout !== "no-message-index",
  useStatistics: !noSummary,
  useSummaryOffsets: !noSummary,
  repeatSchemas: !noSummary,
  repeatChannels: !noSummary,
  useAttachmentIndex: !noSummary,
  useMetadataIndex: !noSummary,
  useChunkIndex: !noSummary,
});
if (!cdrLines) await writer.start({ profile: "ros2", library: "hba tests (@mcap/core)" });
const cloudSchema = cdrLines ? 0 : await writer.registerSchema({ name: "sensor_msgs/msg/PointCloud2", encoding: "ros2msg", data: new TextEncoder().encode(cloudDefinition) });
const odometrySchema = cdrLines ? 0 : await writer.registerSchema({ name: "nav_msgs/msg/Odometry", encoding: "ros2msg", data: new TextEncoder().encode(odometryDefinition) });
const cloudChannel = cdrLines ? 0 : await writer.registerChannel({ topic: "/cloud_registered_body", schemaId: cloudSchema, messageEncoding: "cdr", metadata: new Map() });
const odometryChannel = cdrLines ? 0 : await writer.registerChannel({ topic: "/Odometry", schemaId: odometrySchema, messageEncoding: "cdr", metadata: new Map() });
const cloudWriter = new MessageWriter(parse(cloudDefinition, { ros2: true }));
const odometryWriter = new MessageWriter(parse(odometryDefinition, { ros2: true }));

const names = [["x", 0], ["y", 4], ["z", 8], ["normal_x", 16], ["normal_y", 20], ["normal_z", 24], ["intensity", 32], ["curvature", 36]];
for (let n = 0; n < count; n++) {
  const xyzi = readPcd(path.join(folder, "Scans", scans[n]));
  const points = xyzi.length / 4;
  const table = new Float32Array(points * 12);
  for (let p = 0; p < points; p++) {
    table[12 * p] = xyzi[4 * p];
    table[12 * p + 1] = xyzi[4 * p + 1];
    table[12 * p + 2] = xyzi[4 * p + 2];
    table[12 * p + 8] = xyzi[4 * p + 3];
  }
  const stamp = stampOf(times[n]);
  const time = BigInt(stamp.sec) * 1000000000n + BigInt(stamp.nanosec);
  const cloud = {
    header: { stamp, frame_id: "body" },
    height: 1,
    width: points,
    fields: names.map(([name, offset]) => ({ name, offset, datatype: 7, count: 1 })),
    is_bigendian: false,
    point_step: 48,
    row_step: 48 * points,
    data: new Uint8Array(table.buffer),
    is_dense: true,
  };
  const cloudBytes = cloudWriter.writeMessage(cloud);
  if (cdrLines) {
    fs.writeSync(fd, JSON.stringify({ topic: "/cloud_registered_body", type: "sensor_msgs/msg/PointCloud2", time: time.toString(), data: Buffer.from(cloudBytes).toString("base64") }) + "\n");
  } else {
    await writer.addMessage({ channelId: cloudChannel, sequence: n, logTime: time, publishTime: time, data: cloudBytes });
  }
  const m = poses[n];
  const [x, y, z, w] = quaternion([m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]]);
  const odometry = {
    header: { stamp, frame_id: "camera_init" },
    child_frame_id: "body",
    pose: { pose: { position: { x: m[3], y: m[7], z: m[11] }, orientation: { x, y, z, w } }, covariance: new Array(36).fill(0) },
    twist: { twist: { linear: { x: 0, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } }, covariance: new Array(36).fill(0) },
  };
  const odometryBytes = odometryWriter.writeMessage(odometry);
  if (cdrLines) {
    fs.writeSync(fd, JSON.stringify({ topic: "/Odometry", type: "nav_msgs/msg/Odometry", time: time.toString(), data: Buffer.from(odometryBytes).toString("base64") }) + "\n");
  } else {
    await writer.addMessage({ channelId: odometryChannel, sequence: n, logTime: time, publishTime: time, data: odometryBytes });
  }
}
if (!cdrLines && layout !== "unfinished") await writer.end();
fs.closeSync(fd);
