#!/usr/bin/env python3
"""Converts a CARMEN log into neutral JSON lines that every independent bag writer under
tests/bags/ turns into ROS messages: so the ROS 1 bag, the MCAP file and the rosbag2 sqlite3 file
all hold the same run as the CARMEN log.

Written from CARMEN's conventions (not with floorgrid's reader): FLASER n r1..rn laser_x laser_y
laser_theta robot_x robot_y robot_theta timestamp host logger_timestamp; beam i at -pi/2 + i*inc,
inc and max range from the PARAMs laser_front_laser_resolution (degrees) and
robot_front_laser_max (or laser_front_laser_maxrange), else CARMEN's guess. Scans with a zero or
backwards timestamp are dropped, as CARMEN's readers do.

One record per line, in time order:
  {"kind": "mount", "x":, "y":, "yaw":}                  the laser on the robot (first scan's)
  {"kind": "scan", "stamp": s, "angle_min":, "angle_increment":, "range_min":, "range_max":,
   "ranges": [...]}
  {"kind": "pose", "stamp": s, "x":, "y":, "yaw":, "tv":, "rv":}  the robot's pose at that scan

Usage: carmen_to_records.py LOG[.gz] OUT.jsonl [--max-scans N]
"""
import gzip
import json
import math
import sys


def guess_increment(n):
    if n in (180, 181):
        return math.radians(1.0)
    if n in (360, 361):
        return math.radians(0.5)
    if n in (400, 401):
        return math.radians(0.25)
    return math.pi / (n - 1)


def main():
    args = sys.argv[1:]
    max_scans = None
    if "--max-scans" in args:
        i = args.index("--max-scans")
        max_scans = int(args[i + 1])
        del args[i:i + 2]
    log, out = args
    opener = gzip.open if open(log, "rb").read(2) == b"\x1f\x8b" else open
    params = {}
    records = []
    mount = None
    last_stamp = None
    scans = 0
    with opener(log, "rt") as f:
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "PARAM" and len(fields) >= 3:
                params[fields[1]] = fields[2]
                continue
            if fields[0] != "FLASER":
                continue
            n = int(fields[1])
            ranges = [float(v) for v in fields[2:2 + n]]
            lx, ly, lt, rx, ry, rt, stamp = (float(v) for v in fields[2 + n:9 + n])
            if stamp <= 0 or (last_stamp is not None and stamp < last_stamp):
                continue
            last_stamp = stamp
            inc = (math.radians(float(params["laser_front_laser_resolution"]))
                   if "laser_front_laser_resolution" in params else guess_increment(n))
            max_range = float(params.get("laser_front_laser_maxrange",
                                         params.get("robot_front_laser_max", 80.0)))
            if mount is None:
                dx, dy = lx - rx, ly - ry
                mount = {"kind": "mount",
                         "x": math.cos(rt) * dx + math.sin(rt) * dy,
                         "y": -math.sin(rt) * dx + math.cos(rt) * dy,
                         "yaw": math.atan2(math.sin(lt - rt), math.cos(lt - rt))}
                records.append(mount)
            records.append({"kind": "pose", "stamp": stamp, "x": rx, "y": ry, "yaw": rt,
                            "tv": 0.0, "rv": 0.0})
            records.append({"kind": "scan", "stamp": stamp, "angle_min": -math.pi / 2,
                            "angle_increment": inc, "range_min": 0.0, "range_max": max_range,
                            "ranges": ranges})
            scans += 1
            if max_scans is not None and scans >= max_scans:
                break
    with open(out, "w") as f:
        for r in records:
            f.write(json.dumps(r) + "\n")
    print(f"{scans} scans written to {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
