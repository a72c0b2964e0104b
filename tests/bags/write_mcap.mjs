#!/usr/bin/env node
// Writes an MCAP file of ROS 2 messages from the neutral JSON records of carmen_to_records.py,
// with the MCAP project's own TypeScript writer (@mcap/core) and Foxglove's CDR serializer
// (@foxglove/rosmsg2-serialization): an independent writer, so floorgrid's MCAP reader is tested
// against files it had no hand in.
//
// Usage: node write_mcap.mjs RECORDS.jsonl OUT.mcap [--compression none|lz4|zstd]
//          [--no-summary] [--no-odom] [--no-chunks] [--chunk-size BYTES]
//          [--manifest OUT.json] [--dump-dir DIR]
//
// Topics: /scan (sensor_msgs/msg/LaserScan), /odom (nav_msgs/msg/Odometry), /tf and /tf_static
// (tf2_msgs/msg/TFMessage). The manifest tells, per topic, its type, message count, log times
// and each message's size; DIR/<topic with / as _>.bin holds the topic's serialized messages
// (CDR with its 4-byte header) one after the other, for byte-identity checks.
import fs from "node:fs";
import path from "node:path";
import { McapWriter } from "@mcap/core";
import { parse } from "@foxglove/rosmsg";
import { MessageWriter } from "@foxglove/rosmsg2-serialization";
import lz4 from "lz4js";
import * as zstd from "@foxglove/wasm-zstd";

const SEP = "\n================================================================================\n";

// ROS 2 message definitions as rosbag2 stores them: the message, then each dependency after a
// line of '=' and "MSG: package/Name".
const TIME = "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec";
const HEADER = "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id";
const VECTOR3 = "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z";
const POINT = "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z";
const QUATERNION =
  "MSG: geometry_msgs/Quaternion\nfloat64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1";

const DEFINITIONS = {
  "sensor_msgs/msg/LaserScan": [
    "std_msgs/Header header\n" +
      "float32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n" +
      "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n" +
      "float32[] ranges\nfloat32[] intensities",
    HEADER,
    TIME,
  ].join(SEP),
  "nav_msgs/msg/Odometry": [
    "std_msgs/Header header\nstring child_frame_id\n" +
      "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist",
    HEADER,
    TIME,
    "MSG: geometry_msgs/PoseWithCovariance\ngeometry_msgs/Pose pose\nfloat64[36] covariance",
    "MSG: geometry_msgs/Pose\ngeometry_msgs/Point position\ngeometry_msgs/Quaternion orientation",
    POINT,
    QUATERNION,
    "MSG: geometry_msgs/TwistWithCovariance\ngeometry_msgs/Twist twist\nfloat64[36] covariance",
    "MSG: geometry_msgs/Twist\ngeometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular",
    VECTOR3,
  ].join(SEP),
  "tf2_msgs/msg/TFMessage": [
    "geometry_msgs/TransformStamped[] transforms",
    "MSG: geometry_msgs/TransformStamped\nstd_msgs/Header header\nstring child_frame_id\n" +
      "geometry_msgs/Transform transform",
    HEADER,
    TIME,
    "MSG: geometry_msgs/Transform\ngeometry_msgs/Vector3 translation\n" +
      "geometry_msgs/Quaternion rotation",
    VECTOR3,
    QUATERNION,
  ].join(SEP),
};

function parseArgs(argv) {
  const options = { compression: "lz4", summary: true, odom: true, chunks: true, chunkSize: 65536 };
  const positional = [];
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === "--compression") options.compression = argv[++i];
    else if (a === "--no-summary") options.summary = false;
    else if (a === "--no-odom") options.odom = false;
    else if (a === "--no-chunks") options.chunks = false;
    else if (a === "--chunk-size") options.chunkSize = Number(argv[++i]);
    else if (a === "--manifest") options.manifest = argv[++i];
    else if (a === "--dump-dir") options.dumpDir = argv[++i];
    else positional.push(a);
  }
  if (positional.length !== 2 || !["none", "lz4", "zstd"].includes(options.compression)) {
    console.error("usage: write_mcap.mjs RECORDS.jsonl OUT.mcap [--compression none|lz4|zstd] ...");
    process.exit(2);
  }
  [options.records, options.out] = positional;
  return options;
}

// Seconds as a float -> ROS 2 time; rounding half up as write_rosbag2_db3.py does.
function rosTime(stamp) {
  let sec = Math.floor(stamp);
  let nanosec = Math.floor((stamp - sec) * 1e9 + 0.5);
  if (nanosec >= 1e9) {
    sec += 1;
    nanosec -= 1e9;
  }
  return { sec, nanosec };
}

const nanoseconds = (t) => BigInt(t.sec) * 1000000000n + BigInt(t.nanosec);

function quaternion(yaw) {
  return { x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) };
}

function transform(stamp, parent, child, x, y, yaw) {
  return {
    header: { stamp, frame_id: parent },
    child_frame_id: child,
    transform: { translation: { x, y, z: 0 }, rotation: quaternion(yaw) },
  };
}

class FileWritable {
  constructor(file) {
    this.fd = fs.openSync(file, "w");
    this.offset = 0n;
  }
  async write(buffer) {
    fs.writeSync(this.fd, buffer);
    this.offset += BigInt(buffer.byteLength);
  }
  position() {
    return this.offset;
  }
  close() {
    fs.closeSync(this.fd);
  }
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  await zstd.isLoaded;
  const compressChunk = {
    none: undefined,
    lz4: (data) => ({ compression: "lz4", compressedData: lz4.compress(data) }),
    zstd: (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) }),
  }[options.compression];

  const file = new FileWritable(options.out);
  const s = options.summary;
  const writer = new McapWriter({
    writable: file,
    useChunks: options.chunks,
    chunkSize: options.chunkSize,
    compressChunk,
    useStatistics: s,
    useSummaryOffsets: s,
    repeatSchemas: s,
    repeatChannels: s,
    useChunkIndex: s,
    useMessageIndex: s,
    useAttachmentIndex: s,
    useMetadataIndex: s,
  });
  await writer.start({ profile: "ros2", library: "floorgrid tests/bags/write_mcap.mjs" });

  const topics = {};
  async function addTopic(topic, type) {
    const text = DEFINITIONS[type];
    const schemaId = await writer.registerSchema({
      name: type,
      encoding: "ros2msg",
      data: new TextEncoder().encode(text),
    });
    const channelId = await writer.registerChannel({
      topic,
      schemaId,
      messageEncoding: "cdr",
      metadata: new Map([["offered_qos_profiles", ""]]),
    });
    topics[topic] = {
      type,
      channelId,
      writer: new MessageWriter(parse(text, { ros2: true })),
      count: 0,
      sizes: [],
      chunks: [],
      sequence: 0,
      first_ns: null,
      last_ns: null,
    };
  }
  await addTopic("/tf_static", "tf2_msgs/msg/TFMessage");
  await addTopic("/scan", "sensor_msgs/msg/LaserScan");
  if (options.odom) await addTopic("/odom", "nav_msgs/msg/Odometry");
  await addTopic("/tf", "tf2_msgs/msg/TFMessage");

  async function put(topic, time, message) {
    const t = topics[topic];
    const data = t.writer.writeMessage(message);
    const logTime = nanoseconds(time);
    await writer.addMessage({
      channelId: t.channelId,
      sequence: t.sequence++,
      logTime,
      publishTime: logTime,
      data,
    });
    t.count += 1;
    t.sizes.push(data.byteLength);
    t.chunks.push(Buffer.from(data));
    if (t.first_ns === null) t.first_ns = logTime;
    t.last_ns = logTime;
  }

  const lines = fs.readFileSync(options.records, "utf8").split("\n").filter((l) => l.trim());
  const records = lines.map((l) => JSON.parse(l));
  const firstStamp = records.find((r) => r.stamp !== undefined)?.stamp ?? 0;
  for (const r of records) {
    if (r.kind === "mount") {
      const time = rosTime(firstStamp);
      await put("/tf_static", time, {
        transforms: [transform(time, "base_link", "laser", r.x, r.y, r.yaw)],
      });
    } else if (r.kind === "pose") {
      const time = rosTime(r.stamp);
      if (options.odom) {
        const zeros = new Array(36).fill(0);
        await put("/odom", time, {
          header: { stamp: time, frame_id: "odom" },
          child_frame_id: "base_link",
          pose: {
            pose: { position: { x: r.x, y: r.y, z: 0 }, orientation: quaternion(r.yaw) },
            covariance: zeros,
          },
          twist: {
            twist: { linear: { x: r.tv, y: 0, z: 0 }, angular: { x: 0, y: 0, z: r.rv } },
            covariance: zeros,
          },
        });
      }
      await put("/tf", time, {
        transforms: [transform(time, "odom", "base_link", r.x, r.y, r.yaw)],
      });
    } else if (r.kind === "scan") {
      const time = rosTime(r.stamp);
      const n = r.ranges.length;
      await put("/scan", time, {
        header: { stamp: time, frame_id: "laser" },
        angle_min: r.angle_min,
        angle_max: r.angle_min + (n - 1) * r.angle_increment,
        angle_increment: r.angle_increment,
        time_increment: 0,
        scan_time: 0,
        range_min: r.range_min,
        range_max: r.range_max,
        ranges: Float32Array.from(r.ranges),
        intensities: new Float32Array(0),
      });
    }
  }
  await writer.end();
  file.close();

  const manifest = { file: path.basename(options.out), compression: options.compression,
                     summary: options.summary, chunks: options.chunks, topics: {} };
  for (const [topic, t] of Object.entries(topics)) {
    manifest.topics[topic] = {
      type: t.type,
      count: t.count,
      first_ns: String(t.first_ns ?? 0),
      last_ns: String(t.last_ns ?? 0),
      sizes: t.sizes,
    };
    if (options.dumpDir) {
      fs.mkdirSync(options.dumpDir, { recursive: true });
      fs.writeFileSync(path.join(options.dumpDir, topic.replaceAll("/", "_") + ".bin"),
                       Buffer.concat(t.chunks));
    }
  }
  if (options.manifest) fs.writeFileSync(options.manifest, JSON.stringify(manifest, null, 1));
}

await main();
