#!/usr/bin/python3
"""Seed corpora for the fuzz targets, made at run time (nothing of the shared data is copied
into the repository): small hand-made inputs of every kind the parsers know, pieces of the real
files in ../shared/data when it is there, and the model files of tests/fixtures/models.

Usage: fuzz/make_corpus.py OUT_DIR [DATA_DIR]
Writes OUT_DIR/<target>/ for dxf, image, map_yaml, carmen, pairs_csv, points_csv, model_json,
dataset_yaml, ros_messages, ros1_bag, mcap, scans_csv, viewer_request. Every seed is at most MAX_SEED bytes (the
fuzzers run with -max_len of that size).
"""
import gzip
import os
import struct
import sys
import zlib
from pathlib import Path

MAX_SEED = 8192
ROOT = Path(__file__).resolve().parent.parent


def put(out: Path, target: str, name: str, data) -> None:
    if isinstance(data, str):
        data = data.encode()
    if len(data) > MAX_SEED:
        data = data[:MAX_SEED]
    folder = out / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data)


# ---- DXF ----

def dxf(entities: str, header: str = "", blocks: str = "") -> str:
    text = "0\nSECTION\n2\nHEADER\n" + header + "0\nENDSEC\n"
    if blocks:
        text += "0\nSECTION\n2\nBLOCKS\n" + blocks + "0\nENDSEC\n"
    return text + "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n"


def group_lines(pairs):
    return "".join(f"{code}\n{value}\n" for code, value in pairs)


DXF_SEEDS = {
    "line": dxf(group_lines([(0, "LINE"), (8, "WALL"), (10, 0), (20, 0), (11, 5), (21, 0)]),
                group_lines([(9, "$INSUNITS"), (70, 6)])),
    "lwpolyline": dxf(group_lines([(0, "LWPOLYLINE"), (8, "A-WALL"), (90, 4), (70, 1),
                                   (10, 0), (20, 0), (42, 0.5), (10, 4), (20, 0), (10, 4),
                                   (20, 3), (10, 0), (20, 3)])),
    "arcs": dxf(group_lines([(0, "ARC"), (8, "DOORS"), (10, 1), (20, 1), (40, 0.9), (50, 0),
                             (51, 90), (0, "CIRCLE"), (8, "0"), (10, 5), (20, 5), (40, 0.3),
                             (0, "ELLIPSE"), (8, "0"), (10, 2), (20, 2), (11, 1), (21, 0),
                             (40, 0.5), (41, 0), (42, 6.283185307)])),
    "spline": dxf(group_lines([(0, "SPLINE"), (8, "0"), (71, 3), (72, 8), (73, 4)] +
                              [(40, k) for k in (0, 0, 0, 0, 1, 1, 1, 1)] +
                              [(c, v) for x, y in ((0, 0), (1, 2), (3, 2), (4, 0))
                               for c, v in ((10, x), (20, y), (30, 0))])),
    "polyline": dxf(group_lines([(0, "POLYLINE"), (8, "0"), (66, 1), (70, 1),
                                 (0, "VERTEX"), (8, "0"), (10, 0), (20, 0),
                                 (0, "VERTEX"), (8, "0"), (10, 2), (20, 0), (42, 1),
                                 (0, "VERTEX"), (8, "0"), (10, 2), (20, 2),
                                 (0, "SEQEND")])),
    "solid_text": dxf(group_lines([(0, "SOLID"), (8, "0"), (10, 0), (20, 0), (11, 1), (21, 0),
                                   (12, 0), (22, 1), (13, 1), (23, 1), (0, "TEXT"), (8, "0"),
                                   (10, 0), (20, 0), (40, 1), (1, "Room 101"), (0, "DIMENSION"),
                                   (8, "0")])),
    "insert": dxf(group_lines([(0, "INSERT"), (8, "X"), (2, "DOOR"), (10, 3), (20, 4), (41, 2),
                               (42, -1), (50, 30), (70, 2), (71, 3), (44, 5), (45, 4)]),
                  group_lines([(9, "$INSUNITS"), (70, 4)]),
                  group_lines([(0, "BLOCK"), (8, "0"), (2, "DOOR"), (10, 0), (20, 0),
                               (0, "LINE"), (8, "0"), (10, 0), (20, 0), (11, 1), (21, 0),
                               (0, "INSERT"), (8, "0"), (2, "INNER"), (10, 0), (20, 0),
                               (0, "ENDBLK"), (0, "BLOCK"), (8, "0"), (2, "INNER"), (10, 0),
                               (20, 0), (0, "ARC"), (8, "0"), (10, 0), (20, 0), (40, 1),
                               (50, 0), (51, 90), (0, "ENDBLK")])),
    "ocs": dxf(group_lines([(0, "ARC"), (8, "0"), (10, 1), (20, 1), (30, 0), (40, 2), (50, 10),
                            (51, 100), (210, 0), (220, 0), (230, -1)])),
    "binary": b"AutoCAD Binary DXF\r\n\x1a\x00" + bytes(range(64)),
}


def dxf_pieces(path: Path, out: Path, per_seed: int = 12, most: int = 20) -> None:
    """Seeds of a real DXF: its header's units and a few entities (or blocks) at a time."""
    lines = path.read_text(errors="replace").splitlines()
    pairs = [(lines[i].strip(), lines[i + 1]) for i in range(0, len(lines) - 1, 2)]
    header = ""
    for k, (code, value) in enumerate(pairs):
        if code == "9" and value.strip() == "$INSUNITS" and k + 1 < len(pairs):
            header = group_lines([pairs[k], pairs[k + 1]])
    for section in ("ENTITIES", "BLOCKS"):
        start = next((k for k, p in enumerate(pairs) if p == ("2", section)), None)
        if start is None:
            continue
        items, current = [], []
        for code, value in pairs[start + 1:]:
            if code == "0" and value.strip() == "ENDSEC":
                break
            if code == "0" and current:
                items.append(current)
                current = []
            current.append((code, value))
        if current:
            items.append(current)
        for n in range(min(most, len(items) // per_seed + 1)):
            chunk = "".join(group_lines(item) for item in items[n * per_seed:(n + 1) * per_seed])
            body = dxf(chunk, header) if section == "ENTITIES" else dxf("", header, chunk)
            put(out, "dxf", f"{path.stem}-{section.lower()}-{n}.dxf", body)


# ---- images ----

def png(width: int, height: int, color_type: int, bit_depth: int, rows: list,
        palette: bytes = b"", trns: bytes = b"") -> bytes:
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(
            ">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + row for row in rows)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth,
                                                           color_type, 0, 0, 0))
    if palette:
        out += chunk(b"PLTE", palette)
    if trns:
        out += chunk(b"tRNS", trns)
    return out + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def image_seeds(out: Path) -> None:
    w, h = 6, 4
    grey = [bytes((x * 40 + y * 10) % 256 for x in range(w)) for y in range(h)]
    put(out, "image", "grey8.png", png(w, h, 0, 8, grey))
    put(out, "image", "grey16.png", png(w, h, 0, 16, [bytes(2 * w) for _ in range(h)]))
    put(out, "image", "grey1.png", png(w, h, 0, 1, [b"\xa8" for _ in range(h)]))
    put(out, "image", "grey_alpha.png", png(w, h, 4, 8, [bytes(2 * w) for _ in range(h)]))
    put(out, "image", "rgb.png", png(w, h, 2, 8, [bytes(range(3 * w)) for _ in range(h)]))
    put(out, "image", "rgba.png", png(w, h, 6, 8, [bytes(range(4 * w)) for _ in range(h)]))
    put(out, "image", "palette.png", png(w, h, 3, 8, [bytes(x % 3 for x in range(w))] * h,
                                         palette=bytes([0, 0, 0, 255, 255, 255, 205, 205, 205]),
                                         trns=b"\xff\x00"))
    put(out, "image", "p5.pgm", b"P5\n# comment\n6 4\n255\n" + b"".join(grey))
    put(out, "image", "p5_16.pgm", b"P5\n3 2\n1000\n" + bytes(12))
    put(out, "image", "p2.pgm", b"P2\n3 2\n15\n0 5 10\n15 3 7\n")


# ---- maps, logs, CSV, manifests ----

MAP_YAMLS = {
    "trinary": "image: map.pgm\nresolution: 0.05\norigin: [-1.0, 2.0, 0.0]\nnegate: 0\n"
               "occupied_thresh: 0.65\nfree_thresh: 0.196\n",
    "scale": "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0.5]\nnegate: 1\nmode: scale\n"
             "occupied_thresh: 0.6\nfree_thresh: 0.2\n",
    "raw": "image: map.pgm\nmode: raw\nresolution: 0.025\norigin: [1e3, -1e3, -3.1]\n",
    "flow": "{image: map.pgm, resolution: 0.05, origin: [0, 0, 0]}\n",
}

CARMEN = (
    "# a CARMEN log\nPARAM laser_front_laser_resolution 1.0 nohost 0\n"
    "PARAM robot_front_laser_max 30 nohost 0\n"
    "ODOM 0.0 0.0 0.0 0.1 0.0 0.0 1.0 h 1.0\n"
    "FLASER 5 1.0 2.0 3.0 30.0 nan 0.1 0.0 0.0 0.0 0.0 0.0 1.1 h 1.1\n"
    "RLASER 3 1.0 2.0 3.0 0.0 0.0 3.14 0.0 0.0 0.0 1.2 h 1.2\n"
    "ROBOTLASER1 0 -1.57 3.14 1.57 30 0.01 0 4 1 2 3 4 0 0 0 0 0 0 0 0 0 0 0 0 0 1.3 h 1.3\n"
    "NEFF 1 2 3\nTRUEPOS 0 0 0 0 0 0 1.4 h 1.4\n"
    "ODOM 0.1 0.0 0.01 0.1 0.0 0.0 0.0 h 2.0\n")

PAIRS = {
    "metres": "plan_x,plan_y,grid_x,grid_y\n0,0,1,1\n4,0,5.1,1\n0,3,0.9,4\n2.5,1.5,3.5,2.5\n",
    "weights": "plan_x,plan_y,grid_x,grid_y,weight\n0,0,1,1,1\n4,0,5,1,0.5\n0,3,1,4,2\n",
    "bom": "\ufeffplan_x,plan_y,grid_x,grid_y\r\n# comment\r\n1e3,-2e-3,+3,4\r\n",
}

POINTS = {
    "xy": "x,y\n1,2\n-3.5,4e1\n",
    "xytheta": "x,y,theta\n1,2,0.5\n# c\n3,4,-3.14\n",
}

MANIFESTS = {
    "full": "name: test\nfloorplan: plan.pgm\nfloorplan_resolution: 0.05\n"
            "floorplan_origin: [0, 0, 0]\nfloorplan_scale: auto\ngridmap: gridmap.yaml\n"
            "log: log.carmen\ninitial_pose:\n  plan: [1, 2, 0.5]\n  grid: [0, 0, 0]\n"
            "laser: {max_range: 30.0, min_range: 0.02, start_angle: -1.57, "
            "angle_increment: 0.0174}\nodometry_noise: [0.05, 0.01, 0.02, 0.05]\n"
            "truth:\n  manual_pairs: pairs.csv\n",
    "bare": "floorplan: plan.pgm\nfloorplan_resolution: 0.1\ngridmap: gridmap.pgm\n"
            "gridmap_resolution: 0.05\ngridmap_origin: [1, 2, 0]\nfloorplan_scale: 1.02\n",
    "dxf_keys": "floorplan: plan.pgm\nfloorplan_resolution: 0.05\nfloorplan_units: mm\n"
                "floorplan_layers: [\"A-WALL*\"]\nfloorplan_layers_exclude: \"*FURN*\"\n"
                "gridmap: gridmap.yaml\n",
}


# ---- ROS 1 bags ----

def ros1_record(fields: dict, data: bytes = b"") -> bytes:
    header = b"".join(struct.pack("<I", len(k) + 1 + len(v)) + k.encode() + b"=" + v
                      for k, v in fields.items())
    return struct.pack("<I", len(header)) + header + struct.pack("<I", len(data)) + data


def ros1_bag(compression: str = "none", index: bool = True) -> bytes:
    """A small ROS 1 bag 2.0 made by hand (the fuzz seeds must stay under MAX_SEED; the bag
    header is not padded to 4096 bytes as rosbag pads it): one chunk with a connection and three
    messages, its index data, and an index section of the connection and the chunk info."""
    u8, u32, u64 = (lambda v: struct.pack("<B", v)), (lambda v: struct.pack("<I", v)), (
        lambda v: struct.pack("<Q", v))
    time = lambda sec, nsec: struct.pack("<II", sec, nsec)
    conn_data = ros1_record({"topic": b"/scan", "type": b"std_msgs/String",
                             "md5sum": b"992ce8a1687cec8c8bd883ec73ca41d1",
                             "message_definition": b"string data\n"})[4:]
    # A connection's data is a header on its own: drop the record's own data length.
    conn_data = conn_data[:-4]
    connection = ros1_record({"op": u8(7), "conn": u32(0), "topic": b"/scan"}, conn_data)
    messages = [ros1_record({"op": u8(2), "conn": u32(0), "time": time(100 + k, 5)},
                            u32(5) + b"hello") for k in range(3)]
    plain = connection + b"".join(messages)
    if compression == "bz2":
        import bz2
        packed = bz2.compress(plain)
    elif compression == "lz4":
        import roslz4  # Debian's python3-roslz4 (LZ4 frame format)
        packed = roslz4.compress(plain)
    else:
        packed = plain
    offsets, at = [], len(connection)
    for m in messages:
        offsets.append(at)
        at += len(m)
    index_data = ros1_record({"op": u8(4), "ver": u32(1), "conn": u32(0), "count": u32(3)},
                             b"".join(time(100 + k, 5) + u32(o) for k, o in enumerate(offsets)))

    def whole(index_pos: int) -> bytes:
        head = ros1_record({"op": u8(3), "index_pos": u64(index_pos), "conn_count": u32(1),
                            "chunk_count": u32(1)})
        return b"#ROSBAG V2.0\n" + head

    chunk_pos = len(whole(0))
    chunk = ros1_record({"op": u8(5), "compression": compression.encode(),
                         "size": u32(len(plain))}, packed)
    chunk_info = ros1_record({"op": u8(6), "ver": u32(1), "chunk_pos": u64(chunk_pos),
                              "start_time": time(100, 5), "end_time": time(102, 5),
                              "count": u32(1)}, u32(0) + u32(3))
    body = chunk + index_data
    index_pos = chunk_pos + len(body) if index else 0
    return whole(index_pos) + body + connection + chunk_info


def compact_model(path: Path) -> str:
    """A model file made small enough for a seed: numbers to 6 digits, lists of points cut to
    their first 16 (every list of one model is cut alike, so their lengths still agree)."""
    import json

    def shrink(v):
        if isinstance(v, float):
            return float(f"{v:.6g}")
        if isinstance(v, list):
            return [shrink(x) for x in v[:16]]
        if isinstance(v, dict):
            return {k: shrink(x) for k, x in v.items()}
        return v
    return json.dumps(shrink(json.loads(path.read_text())), separators=(",", ":"))


def ros_payload(cdr: bool, fields) -> bytes:
    """A message payload: fields are (struct format char, value) or ("s", text); CDR aligns
    each primitive to its size after the 4-byte encapsulation header."""
    out = bytearray(b"\x00\x01\x00\x00" if cdr else b"")
    base = 4 if cdr else 0
    for kind, value in fields:
        if kind == "s":
            raw = value.encode() + (b"\0" if cdr else b"")
            fields_out = [("I", len(raw))]
        else:
            raw, fields_out = None, [(kind, value)]
        for k, v in fields_out:
            size = struct.calcsize("<" + k)
            while cdr and (len(out) - base) % size:
                out.append(0)
            out += struct.pack("<" + k, v)
        if raw is not None:
            out += raw
    return bytes(out)


def ros_message_seeds(out: Path) -> None:
    for cdr in (False, True):
        head = ([] if cdr else [("I", 7)]) + [("i" if cdr else "I", 12), ("I", 5), ("s", "laser")]
        scan = head + [("f", v) for v in (-1.57, 1.57, 0.785, 0, 0, 0.02, 30)] + [
            ("I", 5)] + [("f", v) for v in (1, 2, float("inf"), float("nan"), -float("inf"))] + [
            ("I", 0)]
        odom = head[:-1] + [("s", "odom"), ("s", "base_link")] + [
            ("d", v) for v in (1, 2, 0, 0, 0, 0.2, 0.98)] + [("d", 0)] * 36 + [
            ("d", v) for v in (0.3, 0, 0, 0, 0, 0.1)] + [("d", 0)] * 36
        tf = [("I", 1)] + head[:-1] + [("s", "base_link"), ("s", "laser")] + [
            ("d", v) for v in (0.2, 0, 0.3, 1, 0, 0, 0)]
        for index, (name, fields) in enumerate((("scan", scan), ("odom", odom), ("tf", tf))):
            selector = bytes([(index << 1) | int(cdr)])
            put(out, "ros_messages", f"{name}-{'cdr' if cdr else 'ros1'}.bin",
                selector + ros_payload(cdr, fields))
# ---- MCAP: small hand-made files (records as the MCAP spec lays them out) ----

def mcap_record(opcode: int, content: bytes) -> bytes:
    return struct.pack("<BQ", opcode, len(content)) + content


def mcap_string(s: str) -> bytes:
    return struct.pack("<I", len(s)) + s.encode()


def mcap_file(chunked: bool, summary: bool, compression_name: str = "") -> bytes:
    magic = b"\x89MCAP0\r\n"
    schema = mcap_record(3, struct.pack("<H", 1) + mcap_string("sensor_msgs/msg/LaserScan") +
                         mcap_string("ros2msg") + struct.pack("<I", 3) + b"a b")
    metadata = mcap_string("k") + mcap_string("v")
    channel = mcap_record(4, struct.pack("<HH", 1, 1) + mcap_string("/scan") +
                          mcap_string("cdr") + struct.pack("<I", len(metadata)) + metadata)
    messages = b"".join(mcap_record(5, struct.pack("<HIQQ", 1, i, 1000 + i, 1000 + i) +
                                    b"\x00\x01\x00\x00" + bytes(range(i * 4)))
                        for i in range(3))
    head = magic + mcap_record(1, mcap_string("ros2") + mcap_string("fuzz seed"))
    if chunked:
        inner = schema + channel + messages
        chunk = mcap_record(6, struct.pack("<QQQI", 1000, 1002, len(inner), zlib.crc32(inner)) +
                            mcap_string(compression_name) + struct.pack("<Q", len(inner)) + inner)
        body = chunk
    else:
        body = schema + channel + messages
    data = head + body + mcap_record(15, struct.pack("<I", 0))
    summary_start = 0
    if summary:
        summary_start = len(data)
        counts = struct.pack("<HQ", 1, 3)
        statistics = mcap_record(11, struct.pack("<QHIIIIQQ", 3, 1, 1, 0, 0, 1 if chunked else 0,
                                                 1000, 1002) +
                                 struct.pack("<I", len(counts)) + counts)
        data += schema + channel + statistics
    return data + mcap_record(2, struct.pack("<QQI", summary_start, 0, 0)) + magic


def mcap_seeds(out: Path) -> None:
    put(out, "mcap", "chunked_summary.mcap", mcap_file(True, True))
    put(out, "mcap", "chunked.mcap", mcap_file(True, False))
    put(out, "mcap", "unchunked_summary.mcap", mcap_file(False, True))
    put(out, "mcap", "unchunked.mcap", mcap_file(False, False))
    put(out, "mcap", "unknown_compression.mcap", mcap_file(True, False, "brotli"))
    # A real writer's file (tests/bags/write_mcap.mjs, lz4 chunks), cut to MAX_SEED.
    put(out, "mcap", "fr079_small_head.mcap", (ROOT / "tests/bags/fr079_small.mcap").read_bytes())


# ---- scans.csv (serve --replay) and the viewer's request bodies ----
SCANS = {
    "written": "scan,time,plan_x,plan_y,plan_theta,plan_state,plan_converged,plan_fit,"
               "plan_scale,grid_x,grid_y,grid_theta,grid_state,grid_converged,grid_fit,"
               "grid_scale,consistent,pairs\n"
               "0,1000,1.2,9.5,-0.37,tracking,0,0.7930,0.99,0.04,-2.01,-2.83,tracking,0,0.9768,1,1,0\n"
               "1,nan,1.3,9.5,-0.36,global,0,,1,-0.08,-2.04,-2.82,global,0,,1,0,0\n"
               "2,1000.4,1.4,9.4,-0.35,tracking,1,0.8,1,-0.1,-2.1,-2.8,tracking,1,0.9,1,1,12\n",
    "columns-moved": "grid_state,grid_theta,grid_y,grid_x,time\ntracking,0.5,2,1,3.25\n",
}
REQUESTS = {
    "map-plan": '{"from": "plan", "points": [[1, 2], [3.5, -4, 0.25]], "model": "gt"}',
    "map-grid": '{"from": "grid", "points": [[2, 2, 1e300], [-1e7, 1e7]]}',
    "map-bad": '{"from": "plan", "points": [[1], [1, 2, 3, 4], ["x", 2], [NaN, 1]]}',
    "pair": '{"plan": [1.5, 2], "grid": [3, -4.25]}',
    "pose": '{"x": 1.5, "y": -2.0, "theta": 0.25}',
    "fit": '{"model": "tps"}',
    "nested": '{"from": "plan", "points": [[[[[[[1, 2]]]]]]], "x": {"y": [1, {"z": null}]}}',
}
PLAN_LAYERS = {
    "zones": '{"type": "FeatureCollection", "features": ['
             '{"type": "Feature", "properties": {"name": "bay", "speed_percent": 40}, '
             '"geometry": {"type": "Polygon", "coordinates": [[[0, 0], [4, 0], [4, 3], [0, 3], '
             '[0, 0]], [[1, 1], [2, 1], [2, 2], [1, 1]]]}}, '
             '{"type": "Feature", "properties": {"name": "dock", "heading_deg": 90}, '
             '"geometry": {"type": "Point", "coordinates": [5.5, 2.25]}}, '
             '{"type": "Feature", "properties": {}, "geometry": {"type": "MultiPolygon", '
             '"coordinates": [[[[10, 10], [12, 10], [11, 12], [10, 10]]]]}}]}',
    "bow-tie": '{"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": '
               '{"type": "Polygon", "coordinates": [[[0, 0], [2, 2], [2, 0], [0, 2], [0, 0]]]}}]}',
    "waypoints": "name,x,y,theta\nstation A,1.5,2.25,0.5\ndock,-3,4,\nbad,nan,1,0\n",
    "polyline": dxf("0\nLWPOLYLINE\n8\nZONES\n90\n4\n70\n1\n10\n0\n20\n0\n"
                    "10\n4\n20\n0\n42\n0.5\n10\n4\n20\n3\n10\n0\n20\n3\n"),
}


def main() -> None:
    out = Path(sys.argv[1])
    data = Path(sys.argv[2]) if len(sys.argv) > 2 else ROOT.parent / "shared" / "data"
    for name, text in DXF_SEEDS.items():
        put(out, "dxf", name + ".dxf", text)
    image_seeds(out)
    for name, text in MAP_YAMLS.items():
        put(out, "map_yaml", name + ".yaml", text)
    put(out, "carmen", "plain.log", CARMEN)
    ros_message_seeds(out)
    put(out, "carmen", "packed.log.gz", gzip.compress(CARMEN.encode(), mtime=0))
    for name, text in PAIRS.items():
        put(out, "pairs_csv", name + ".csv", text)
    for name, text in POINTS.items():
        put(out, "points_csv", name + ".csv", text)
    for name, text in MANIFESTS.items():
        put(out, "dataset_yaml", name + ".yaml", text)
    for compression in ("none", "bz2", "lz4"):
        try:
            put(out, "ros1_bag", f"tiny-{compression}.bag", ros1_bag(compression))
        except ImportError:
            pass
    put(out, "ros1_bag", "tiny-unindexed.bag", ros1_bag("none", index=False))
    put(out, "ros1_bag", "fr079_5scans_lz4.bag",
        (ROOT / "tests" / "bags" / "fr079_5scans_lz4.bag").read_bytes())
    mcap_seeds(out)
    for name, text in SCANS.items():
        put(out, "scans_csv", name + ".csv", text)
    for name, text in REQUESTS.items():
        put(out, "viewer_request", name + ".json", text)
    for name, text in PLAN_LAYERS.items():
        put(out, "plan_layers", name + ".txt", text)
    for model in sorted((ROOT / "tests" / "fixtures" / "models").glob("*.json")):
        put(out, "model_json", model.name, compact_model(model))
    if data.is_dir():
        for path in sorted((data / "dxf").glob("*.dxf")):
            if not path.read_bytes().startswith(b"AutoCAD Binary"):
                dxf_pieces(path, out)
        for path in sorted((data / "carmen").glob("*.log.gz")) + [
                data / "fr079" / "freiburg-079-corrected.log.gz"]:
            if path.exists():
                with gzip.open(path, "rb") as log:
                    head = log.read(6000)
                head = head[:head.rfind(b"\n") + 1]
                put(out, "carmen", path.stem + ".head", head)
                put(out, "carmen", path.stem + ".head.gz", gzip.compress(head, mtime=0))
        for path in sorted(data.glob("halmstad/*/pairs/*.csv"))[:6]:
            put(out, "pairs_csv", path.name, path.read_bytes()[:2000])
    # Inputs that once crashed a parser (fuzz/regressions/<target>-<what>.*) stay in the corpus.
    for path in sorted((ROOT / "fuzz" / "regressions").glob("*-*")):
        put(out, path.name.split("-")[0], path.name, path.read_bytes())
    counts = {t.name: len(list(t.iterdir())) for t in sorted(out.iterdir()) if t.is_dir()}
    print("corpus:", ", ".join(f"{k} {v}" for k, v in counts.items()))


if __name__ == "__main__":
    main()
