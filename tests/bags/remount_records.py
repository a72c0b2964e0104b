#!/usr/bin/python3
"""Rewrites the neutral JSON records of carmen_to_records.py as another robot would have logged
the same run: the laser mounted elsewhere on base_link, and made-up stamps.

The laser stays where it was in the world (every scan is unchanged); the robot's base_link is
moved so that base_link composed with the new mount gives the old laser pose:
  laser = base_old * mount_old = base_new * mount_new  =>  base_new = laser * mount_new^-1.
With --rate HZ the records' stamps are replaced by start + k / HZ for the k-th scan (its pose
record shares the scan's stamp), as a driver stamping at a fixed rate would.

Usage: remount_records.py IN.jsonl OUT.jsonl [--mount x,y,yaw] [--rate HZ] [--start SECONDS]
"""
import argparse
import json
import math


def compose(a, b):
    """Pose a then pose b, each (x, y, yaw)."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1],
            math.atan2(math.sin(a[2] + b[2]), math.cos(a[2] + b[2])))


def inverse(a):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-(c * a[0] + s * a[1]), -(-s * a[0] + c * a[1]), -a[2])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("records")
    parser.add_argument("out")
    parser.add_argument("--mount", default="0,0,0", help="x,y,yaw of the laser on base_link")
    parser.add_argument("--rate", type=float, help="restamp the scans at this rate (Hz)")
    parser.add_argument("--start", type=float, default=1700000000.0,
                        help="the first made-up stamp (seconds)")
    args = parser.parse_args()
    new_mount = tuple(float(v) for v in args.mount.split(","))
    with open(args.records) as f:
        records = [json.loads(line) for line in f if line.strip()]
    old = next((r for r in records if r["kind"] == "mount"), {"x": 0.0, "y": 0.0, "yaw": 0.0})
    old_mount = (old["x"], old["y"], old["yaw"])
    stamps = {}
    out = []
    for r in records:
        if r["kind"] == "mount":
            out.append({"kind": "mount", "x": new_mount[0], "y": new_mount[1],
                        "yaw": new_mount[2]})
            continue
        r = dict(r)
        if args.rate:
            # One made-up stamp per distinct original stamp, in order (a pose and its scan
            # share one).
            if r["stamp"] not in stamps:
                stamps[r["stamp"]] = args.start + len(stamps) / args.rate
            r["stamp"] = stamps[r["stamp"]]
        if r["kind"] == "pose":
            laser = compose((r["x"], r["y"], r["yaw"]), old_mount)
            base = compose(laser, inverse(new_mount))
            r["x"], r["y"], r["yaw"] = base
        out.append(r)
    with open(args.out, "w") as f:
        for r in out:
            f.write(json.dumps(r) + "\n")


if __name__ == "__main__":
    main()
