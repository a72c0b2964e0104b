#!/usr/bin/python3
"""Writes the decompression bombs kept as fuzz regression inputs (fuzz/regressions/): small
files whose chunks state their decompressed size honestly, far beyond what a chunk may take.
Before the chunk limit, reading them allocated and decompressed gigabytes.

  ros1_bag-bz2-bomb-4g.bag     ROS 1 bag, one bz2 chunk of 4,000,000,000 bytes (zeros after a
                               connection and three messages), about 3 KB
  mcap-zstd-bomb-240m.mcap     MCAP file, one zstd chunk of 240 MiB (zstd RLE blocks: 4 bytes
                               make 128 KiB), about 8 KB: what a fuzz seed can hold (8192 bytes)

Usage: fuzz/make_bombs.py [OUT_DIR]   (default: fuzz/regressions beside this script)
"""
import bz2
import struct
import sys
import zlib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_corpus  # noqa: E402  (the hand-made ROS 1 and MCAP records)


def ros1_bz2_bomb(size: int) -> bytes:
    """A ROS 1 bag 2.0 whose one chunk is bz2 of `size` bytes: the records of make_corpus's
    tiny bag, then zeros. No index: the chunk is read through."""
    u8, u32, u64 = (lambda v: struct.pack("<B", v)), (lambda v: struct.pack("<I", v)), (
        lambda v: struct.pack("<Q", v))
    rec = make_corpus.ros1_record
    conn_data = rec({"topic": b"/scan", "type": b"std_msgs/String",
                     "md5sum": b"992ce8a1687cec8c8bd883ec73ca41d1",
                     "message_definition": b"string data\n"})[4:-4]
    connection = rec({"op": u8(7), "conn": u32(0), "topic": b"/scan"}, conn_data)
    messages = b"".join(rec({"op": u8(2), "conn": u32(0), "time": struct.pack("<II", 100 + k, 5)},
                            u32(5) + b"hello") for k in range(3))
    plain = connection + messages
    compressor = bz2.BZ2Compressor(9)
    packed = compressor.compress(plain)
    zeros = bytes(1 << 20)
    left = size - len(plain)
    while left > 0:
        piece = zeros[:min(left, len(zeros))]
        packed += compressor.compress(piece)
        left -= len(piece)
    packed += compressor.flush()
    head = rec({"op": u8(3), "index_pos": u64(0), "conn_count": u32(1), "chunk_count": u32(1)})
    chunk = rec({"op": u8(5), "compression": b"bz2", "size": u32(size)}, packed)
    return b"#ROSBAG V2.0\n" + head + chunk


def zstd_frame(prefix: bytes, zeros: int) -> bytes:
    """A zstd frame of `prefix` (a raw block) then `zeros` zero bytes (RLE blocks of 128 KiB),
    with its content size in the header: a decoder knows the size before it decompresses."""
    total = len(prefix) + zeros
    frame = struct.pack("<I", 0xFD2FB528)
    frame += bytes([0xE0]) + struct.pack("<Q", total)  # single segment, 8-byte content size
    blocks = []
    if prefix:
        blocks.append((0, len(prefix), prefix))  # raw
    block = 1 << 17
    while zeros > 0:
        n = min(block, zeros)
        blocks.append((1, n, b"\x00"))  # RLE: one byte, repeated n times
        zeros -= n
    for i, (kind, n, payload) in enumerate(blocks):
        last = 1 if i == len(blocks) - 1 else 0
        header = last | (kind << 1) | (n << 3)
        frame += struct.pack("<I", header)[:3] + payload
    return frame


def mcap_zstd_bomb(size: int) -> bytes:
    """An MCAP file whose one chunk is zstd of `size` bytes: a schema, a channel and a message,
    then zeros."""
    record, string = make_corpus.mcap_record, make_corpus.mcap_string
    magic = b"\x89MCAP0\r\n"
    schema = record(3, struct.pack("<H", 1) + string("sensor_msgs/msg/LaserScan") +
                    string("ros2msg") + struct.pack("<I", 0))
    channel = record(4, struct.pack("<HH", 1, 1) + string("/scan") + string("cdr") +
                     struct.pack("<I", 0))
    message = record(5, struct.pack("<HIQQ", 1, 0, 1000, 1000) + b"\x00\x01\x00\x00")
    inner = schema + channel + message
    frame = zstd_frame(inner, size - len(inner))
    chunk = record(6, struct.pack("<QQQI", 1000, 1000, size, 0) + string("zstd") +
                   struct.pack("<Q", len(frame)) + frame)
    head = magic + record(1, string("ros2") + string("bomb"))
    data = head + chunk + record(15, struct.pack("<I", 0))
    return data + record(2, struct.pack("<QQI", 0, 0, 0)) + magic


def main() -> None:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "regressions"
    out.mkdir(parents=True, exist_ok=True)
    bombs = {"ros1_bag-bz2-bomb-4g.bag": ros1_bz2_bomb(4_000_000_000),
             "mcap-zstd-bomb-240m.mcap": mcap_zstd_bomb(240 << 20)}
    for name, data in bombs.items():
        assert len(data) <= make_corpus.MAX_SEED, (name, len(data))
        (out / name).write_bytes(data)
        print(f"{name}: {len(data)} bytes")


if __name__ == "__main__":
    main()
