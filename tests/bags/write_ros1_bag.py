#!/usr/bin/python3
"""Writes a ROS 1 bag (format 2.0) from the neutral JSON lines of carmen_to_records.py, with
Debian's python3-rosbag and its message packages: a writer independent of floorgrid's reader, so
that the reader's tests check it against the format as ROS itself writes it.

Run it with /usr/bin/python3 (the ROS packages live in Debian's dist-packages).

Topics written:
  /scan        sensor_msgs/LaserScan     one per scan record (frame "laser"; intensities empty)
  /odom        nav_msgs/Odometry         one per pose record (odom -> base_link), unless --no-odom
  /tf          tf2_msgs/TFMessage        one per pose record (odom -> base_link)
  /tf_static   tf2_msgs/TFMessage        once, base_link -> laser from the mount record (latched)
Every message's log time is its record's stamp; /tf_static's is the first record's stamp.

Beside OUT.bag it writes OUT.bag.json, a manifest of what it wrote:
  {"compression":, "chunk_threshold":, "messages": N, "start_ns":, "end_ns":,
   "topics": {"/scan": {"type":, "messages":, "sha256":, "bytes":, "first_ns":, "last_ns":,
                        "dump":}}}
where sha256 is over the concatenation of each message's bytes as rosbag serializes them
(msg.serialize), and, with --dump, "dump" names a file OUT.bag.<topic>.bin holding exactly that
concatenation.

Usage: write_ros1_bag.py RECORDS.jsonl OUT.bag [--compression none|bz2|lz4]
                         [--chunk-threshold BYTES] [--no-odom] [--dump]
                         [--mount x,y,yaw[,roll]] [--no-scan] [--extra-scan-topic TOPIC]
                         [--odom-every N] [--mount-chain N]

With --mount-chain N, /tf_static holds the mount as a chain of N links base_link -> link1 ->
... -> laser: each link turns by the mount's yaw / N and moves by its translation / N along the
way turned so far (so the chain ends where the mount is).
"""
import argparse
import hashlib
import io
import json
import math
import sys

import genpy
import rosbag
from geometry_msgs.msg import Quaternion, TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage


def stamp_of(seconds):
    return genpy.Time.from_sec(seconds)


def quaternion_of_yaw(yaw):
    return Quaternion(x=0.0, y=0.0, z=math.sin(yaw / 2.0), w=math.cos(yaw / 2.0))


def laser_scan(record):
    msg = LaserScan()
    msg.header.stamp = stamp_of(record["stamp"])
    msg.header.frame_id = "laser"
    msg.angle_min = record["angle_min"]
    msg.angle_increment = record["angle_increment"]
    msg.angle_max = record["angle_min"] + (len(record["ranges"]) - 1) * record["angle_increment"]
    msg.range_min = record["range_min"]
    msg.range_max = record["range_max"]
    msg.ranges = record["ranges"]
    msg.intensities = []
    return msg


def odometry(record):
    msg = Odometry()
    msg.header.stamp = stamp_of(record["stamp"])
    msg.header.frame_id = "odom"
    msg.child_frame_id = "base_link"
    msg.pose.pose.position.x = record["x"]
    msg.pose.pose.position.y = record["y"]
    msg.pose.pose.orientation = quaternion_of_yaw(record["yaw"])
    msg.twist.twist.linear.x = record["tv"]
    msg.twist.twist.angular.z = record["rv"]
    return msg


def transform(stamp, parent, child, x, y, yaw, roll=0.0):
    t = TransformStamped()
    t.header.stamp = stamp
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x = x
    t.transform.translation.y = y
    # rotation = Rz(yaw) * Rx(roll), as a quaternion
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    t.transform.rotation = Quaternion(x=cy * sr, y=sy * sr, z=sy * cr, w=cy * cr)
    return t


class Recorder:
    """Writes messages to the bag and keeps, per topic, what the manifest states."""

    def __init__(self, bag, out_path, dump):
        self.bag = bag
        self.out_path = out_path
        self.dump = dump
        self.topics = {}

    def write(self, topic, msg, stamp, connection_header=None):
        buffer = io.BytesIO()
        msg.serialize(buffer)
        data = buffer.getvalue()
        entry = self.topics.get(topic)
        if entry is None:
            entry = {"type": msg._type, "messages": 0, "hash": hashlib.sha256(), "bytes": 0,
                     "first_ns": stamp.to_nsec(), "last_ns": stamp.to_nsec(), "file": None}
            if self.dump:
                name = self.out_path + "." + topic.strip("/").replace("/", "_") + ".bin"
                entry["file"] = open(name, "wb")
                entry["dump"] = name
            self.topics[topic] = entry
        entry["messages"] += 1
        entry["hash"].update(data)
        entry["bytes"] += len(data)
        entry["first_ns"] = min(entry["first_ns"], stamp.to_nsec())
        entry["last_ns"] = max(entry["last_ns"], stamp.to_nsec())
        if entry["file"]:
            entry["file"].write(data)
        self.bag.write(topic, msg, stamp, connection_header=connection_header)

    def manifest(self):
        topics = {}
        for topic, e in self.topics.items():
            if e["file"]:
                e["file"].close()
            topics[topic] = {k: e[k] for k in ("type", "messages", "bytes", "first_ns", "last_ns")}
            topics[topic]["sha256"] = e["hash"].hexdigest()
            if "dump" in e:
                topics[topic]["dump"] = e["dump"]
        return topics


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("records")
    parser.add_argument("out")
    parser.add_argument("--compression", choices=["none", "bz2", "lz4"], default="none")
    parser.add_argument("--chunk-threshold", type=int, default=768 * 1024)
    parser.add_argument("--no-odom", action="store_true", help="leave out /odom (odometry "
                        "comes from /tf only)")
    parser.add_argument("--mount", help="x,y,yaw[,roll]: the laser on base_link instead of the "
                        "records' mount (roll pi: mounted upside down)")
    parser.add_argument("--no-scan", action="store_true", help="leave out /scan")
    parser.add_argument("--odom-every", type=int, default=1, help="write only every Nth pose "
                        "record's /odom and /tf (the first and last always)")
    parser.add_argument("--extra-scan-topic", help="also write every scan on this topic")
    parser.add_argument("--mount-chain", type=int, default=1, help="the mount on /tf_static as "
                        "a chain of this many links")
    parser.add_argument("--dump", action="store_true", help="also write each topic's "
                        "concatenated serialized messages to OUT.<topic>.bin")
    args = parser.parse_args()

    with open(args.records) as f:
        records = [json.loads(line) for line in f if line.strip()]
    mount = next((r for r in records if r["kind"] == "mount"), None)
    if args.mount:
        values = [float(v) for v in args.mount.split(",")]
        mount = {"kind": "mount", "x": values[0], "y": values[1], "yaw": values[2],
                 "roll": values[3] if len(values) > 3 else 0.0}
    first_stamp = next((r["stamp"] for r in records if "stamp" in r), None)

    with rosbag.Bag(args.out, "w", compression=args.compression,
                    chunk_threshold=args.chunk_threshold) as bag:
        rec = Recorder(bag, args.out, args.dump)
        if mount is not None and first_stamp is not None:
            stamp = stamp_of(first_stamp)
            n = args.mount_chain
            if n == 1:
                links = [transform(stamp, "base_link", "laser", mount["x"], mount["y"],
                                   mount["yaw"], mount.get("roll", 0.0))]
            else:
                # A chain whose composition is the mount: link k turns by yaw / n after moving
                # by (x, y) / n rotated back by the turn so far (roll is not chained).
                links, yaw = [], mount["yaw"] / n
                for k in range(n):
                    parent = "base_link" if k == 0 else f"link{k}"
                    child = "laser" if k == n - 1 else f"link{k + 1}"
                    c, s = math.cos(-k * yaw), math.sin(-k * yaw)
                    dx, dy = mount["x"] / n, mount["y"] / n
                    links.append(transform(stamp, parent, child, c * dx - s * dy, s * dx + c * dy,
                                           yaw))
            static = TFMessage(transforms=links)
            header = {"topic": "/tf_static", "type": TFMessage._type,
                      "md5sum": TFMessage._md5sum, "message_definition": TFMessage._full_text,
                      "callerid": "/write_ros1_bag", "latching": "1"}
            rec.write("/tf_static", static, stamp, connection_header=header)
        poses = [r for r in records if r["kind"] == "pose"]
        kept = {id(r) for i, r in enumerate(poses)
                if i % args.odom_every == 0 or i == len(poses) - 1}
        for r in records:
            if r["kind"] == "pose" and id(r) not in kept:
                continue
            if r["kind"] == "pose":
                stamp = stamp_of(r["stamp"])
                if not args.no_odom:
                    rec.write("/odom", odometry(r), stamp)
                rec.write("/tf", TFMessage(transforms=[
                    transform(stamp, "odom", "base_link", r["x"], r["y"], r["yaw"])]), stamp)
            elif r["kind"] == "scan":
                if not args.no_scan:
                    rec.write("/scan", laser_scan(r), stamp_of(r["stamp"]))
                if args.extra_scan_topic:
                    rec.write(args.extra_scan_topic, laser_scan(r), stamp_of(r["stamp"]))
        topics = rec.manifest()

    manifest = {"compression": args.compression, "chunk_threshold": args.chunk_threshold,
                "messages": sum(t["messages"] for t in topics.values()),
                "start_ns": min((t["first_ns"] for t in topics.values()), default=0),
                "end_ns": max((t["last_ns"] for t in topics.values()), default=0),
                "topics": topics}
    with open(args.out + ".json", "w") as f:
        json.dump(manifest, f, indent=1)
    print(f"{manifest['messages']} messages on {len(topics)} topics written to {args.out}",
          file=sys.stderr)


if __name__ == "__main__":
    main()
