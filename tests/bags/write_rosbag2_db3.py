#!/usr/bin/python3
"""Writes a rosbag2 sqlite3 bag (a folder: metadata.yaml + .db3 files) of ROS 2 messages from
the neutral JSON records of carmen_to_records.py, with Python's sqlite3 and a CDR encoder of its
own: an independent writer, so floorgrid's rosbag2 reader is tested against files it had no hand
in. The tables are rosbag2's (Humble): topics(id, name, type, serialization_format,
offered_qos_profiles) and messages(id, topic_id, timestamp, data) with its timestamp index.

CDR here is XCDR1 little-endian as ROS 2 writes it: the header 00 01 00 00, each primitive
aligned to its size counted from the byte after the header, strings as a u32 length that counts
the terminating NUL then the bytes and the NUL, sequences as a u32 count then the elements,
fixed arrays as the elements alone.

Usage: write_rosbag2_db3.py RECORDS.jsonl OUT_FOLDER [--no-odom] [--split-every N]
         [--manifest OUT.json] [--dump-dir DIR]
--split-every N starts a new .db3 after every N messages; each file defines its topics as they
first appear in it (so ids differ between files, as in rosbag2's splits). The manifest and DIR
are as write_mcap.mjs writes them.
"""
import json
import math
import os
import sqlite3
import struct
import sys


class Cdr:
    def __init__(self):
        self.b = bytearray(b"\x00\x01\x00\x00")

    def align(self, size):
        self.b += b"\x00" * ((-(len(self.b) - 4)) % size)

    def prim(self, fmt, size, value):
        self.align(size)
        self.b += struct.pack("<" + fmt, value)

    def int32(self, v):
        self.prim("i", 4, v)

    def uint32(self, v):
        self.prim("I", 4, v)

    def float32(self, v):
        self.prim("f", 4, v)

    def float64(self, v):
        self.prim("d", 8, v)

    def string(self, s):
        data = s.encode() + b"\x00"
        self.uint32(len(data))
        self.b += data

    def float32_sequence(self, values):
        self.uint32(len(values))
        if values:
            self.align(4)
            self.b += struct.pack("<%df" % len(values), *values)

    def float64_array(self, values):
        self.align(8)
        self.b += struct.pack("<%dd" % len(values), *values)

    def header(self, time, frame):
        self.int32(time[0])
        self.uint32(time[1])
        self.string(frame)

    def vector3(self, x, y, z):
        for v in (x, y, z):
            self.float64(v)

    def quaternion(self, yaw):
        for v in (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)):
            self.float64(v)


def ros_time(stamp):
    """Seconds -> (sec, nanosec), rounding half up as write_mcap.mjs does."""
    sec = math.floor(stamp)
    nanosec = math.floor((stamp - sec) * 1e9 + 0.5)
    if nanosec >= 1000000000:
        sec, nanosec = sec + 1, nanosec - 1000000000
    return sec, nanosec


def tf_message(time, parent, child, x, y, yaw):
    c = Cdr()
    c.uint32(1)
    c.header(time, parent)
    c.string(child)
    c.vector3(x, y, 0.0)
    c.quaternion(yaw)
    return bytes(c.b)


def odometry(time, r):
    c = Cdr()
    c.header(time, "odom")
    c.string("base_link")
    c.vector3(r["x"], r["y"], 0.0)
    c.quaternion(r["yaw"])
    c.float64_array([0.0] * 36)
    c.vector3(r["tv"], 0.0, 0.0)
    c.vector3(0.0, 0.0, r["rv"])
    c.float64_array([0.0] * 36)
    return bytes(c.b)


def laser_scan(time, r):
    n = len(r["ranges"])
    c = Cdr()
    c.header(time, "laser")
    for v in (r["angle_min"], r["angle_min"] + (n - 1) * r["angle_increment"],
              r["angle_increment"], 0.0, 0.0, r["range_min"], r["range_max"]):
        c.float32(v)
    c.float32_sequence(r["ranges"])
    c.float32_sequence([])
    return bytes(c.b)


TYPES = {"/tf_static": "tf2_msgs/msg/TFMessage", "/scan": "sensor_msgs/msg/LaserScan",
         "/odom": "nav_msgs/msg/Odometry", "/tf": "tf2_msgs/msg/TFMessage"}

SCHEMA = """
CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                    serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);
CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,
                      timestamp INTEGER NOT NULL, data BLOB NOT NULL);
CREATE INDEX timestamp_idx ON messages (timestamp ASC);
"""


def messages(records, with_odom):
    """(topic, log time ns, CDR bytes) in the order write_mcap.mjs writes them."""
    first = next((r["stamp"] for r in records if "stamp" in r), 0.0)
    for r in records:
        if r["kind"] == "mount":
            t = ros_time(first)
            yield "/tf_static", t, tf_message(t, "base_link", "laser", r["x"], r["y"], r["yaw"])
        elif r["kind"] == "pose":
            t = ros_time(r["stamp"])
            if with_odom:
                yield "/odom", t, odometry(t, r)
            yield "/tf", t, tf_message(t, "odom", "base_link", r["x"], r["y"], r["yaw"])
        elif r["kind"] == "scan":
            t = ros_time(r["stamp"])
            yield "/scan", t, laser_scan(t, r)


def main():
    args = sys.argv[1:]
    opts = {"odom": True, "split": 0, "manifest": None, "dump": None}
    positional = []
    i = 0
    while i < len(args):
        a = args[i]
        if a == "--no-odom":
            opts["odom"] = False
        elif a == "--split-every":
            opts["split"] = int(args[i + 1]); i += 1
        elif a == "--manifest":
            opts["manifest"] = args[i + 1]; i += 1
        elif a == "--dump-dir":
            opts["dump"] = args[i + 1]; i += 1
        else:
            positional.append(a)
        i += 1
    if len(positional) != 2:
        sys.exit(__doc__)
    records_path, out = positional
    with open(records_path) as f:
        records = [json.loads(line) for line in f if line.strip()]
    os.makedirs(out, exist_ok=True)
    name = os.path.basename(os.path.normpath(out))

    files, db, ids, in_file = [], None, {}, 0
    topics = {}
    for topic, time, data in messages(records, opts["odom"]):
        if db is None or (opts["split"] and in_file == opts["split"]):
            if db is not None:
                db.commit()
                db.close()
            files.append(f"{name}_{len(files)}.db3")
            path = os.path.join(out, files[-1])
            if os.path.exists(path):
                os.remove(path)
            db = sqlite3.connect(path)
            db.executescript(SCHEMA)
            ids, in_file = {}, 0
        if topic not in ids:
            cursor = db.execute("INSERT INTO topics (name, type, serialization_format, "
                                "offered_qos_profiles) VALUES (?, ?, 'cdr', '')",
                                (topic, TYPES[topic]))
            ids[topic] = cursor.lastrowid
        ns = time[0] * 1000000000 + time[1]
        db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)",
                   (ids[topic], ns, data))
        in_file += 1
        t = topics.setdefault(topic, {"type": TYPES[topic], "count": 0, "first_ns": ns,
                                      "last_ns": ns, "sizes": [], "data": []})
        t["count"] += 1
        t["last_ns"] = ns
        t["sizes"].append(len(data))
        t["data"].append(data)
    db.commit()
    db.close()

    start = min(t["first_ns"] for t in topics.values())
    end = max(t["last_ns"] for t in topics.values())
    total = sum(t["count"] for t in topics.values())
    lines = ["rosbag2_bagfile_information:", "  version: 5", "  storage_identifier: sqlite3",
             "  duration:", f"    nanoseconds: {end - start}", "  starting_time:",
             f"    nanoseconds_since_epoch: {start}", f"  message_count: {total}",
             "  topics_with_message_count:"]
    for topic, t in topics.items():
        lines += ["    - topic_metadata:", f"        name: {topic}", f"        type: {t['type']}",
                  "        serialization_format: cdr", "        offered_qos_profiles: \"\"",
                  f"      message_count: {t['count']}"]
    lines += ["  compression_format: \"\"", "  compression_mode: \"\"",
              "  relative_file_paths:"] + [f"    - {f}" for f in files]
    with open(os.path.join(out, "metadata.yaml"), "w") as f:
        f.write("\n".join(lines) + "\n")

    if opts["manifest"]:
        manifest = {"files": files, "topics": {
            topic: {"type": t["type"], "count": t["count"], "first_ns": str(t["first_ns"]),
                    "last_ns": str(t["last_ns"]), "sizes": t["sizes"]}
            for topic, t in topics.items()}}
        with open(opts["manifest"], "w") as f:
            json.dump(manifest, f, indent=1)
    if opts["dump"]:
        os.makedirs(opts["dump"], exist_ok=True)
        for topic, t in topics.items():
            with open(os.path.join(opts["dump"], topic.replace("/", "_") + ".bin"), "wb") as f:
                f.write(b"".join(t["data"]))


if __name__ == "__main__":
    main()
