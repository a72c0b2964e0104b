"""Inputs of a 250 x 236 m building, the MIT infinite corridor's class (bench/large_building.sh).

  large_building_plan.py draw OUT.pgm
      A drawing of such a building: two crossing corridors (3 m wide) lined with 150 rooms,
      8 m deep and 6 m wide, each with a 1 m door; walls 0.2 m thick. PGM at 0.05 m a pixel
      (white free, black walls): 5000 x 4720 pixels.
  large_building_plan.py tile GRIDMAP.yaml N
      The map_server gridmap tiled N x N times in place (image and YAML rewritten, the origin
      kept): a gridmap N times as wide and high, whose run and plan cover one tile.
"""
import os
import sys

import numpy as np

RESOLUTION = 0.05
WIDTH, HEIGHT = 250.0, 236.0
CORRIDOR, ROOM_DEPTH, ROOM_WIDTH = 3.0, 8.0, 6.0


def draw(out):
    img = np.full((int(HEIGHT / RESOLUTION), int(WIDTH / RESOLUTION)), 255, np.uint8)

    def px(v):
        return int(round(v / RESOLUTION))

    def paint(x0, y0, x1, y1, pad, value):
        xa, xb = sorted((x0, x1))
        ya, yb = sorted((y0, y1))
        img[px(ya - pad):px(yb + pad) + 1, px(xa - pad):px(xb + pad) + 1] = value

    def wall(x0, y0, x1, y1):
        paint(x0, y0, x1, y1, 0.1, 0)

    def door(x0, y0, x1, y1):
        paint(x0, y0, x1, y1, 0.2, 255)

    cy, cx = HEIGHT / 2, WIDTH / 2
    half, outer = CORRIDOR / 2, CORRIDOR / 2 + ROOM_DEPTH
    for s in (-1, 1):  # the corridor along x and its two rows of rooms
        yi, yo = cy + s * half, cy + s * outer
        wall(2, yi, WIDTH - 2, yi)
        wall(2, yo, WIDTH - 2, yo)
        x = 2.0
        while x + ROOM_WIDTH <= WIDTH - 2 + 1e-9:
            wall(x, yi, x, yo)
            if abs(x + ROOM_WIDTH / 2 - cx) > outer:
                door(x + 2.0, yi, x + 3.0, yi)
            x += ROOM_WIDTH
        wall(x, yi, x, yo)
    for s in (-1, 1):  # the corridor along y and its rooms, apart from the crossing
        xi, xo = cx + s * half, cx + s * outer
        for ya, yb in ((2, cy - outer), (cy + outer, HEIGHT - 2)):
            wall(xi, ya, xi, yb)
            wall(xo, ya, xo, yb)
            y = ya
            while y + ROOM_WIDTH <= yb + 1e-9:
                wall(xi, y, xo, y)
                door(xi, y + 2.0, xi, y + 3.0)
                y += ROOM_WIDTH
            wall(xi, y, xo, y)
    for s in (-1, 1):  # the crossing opened, the corridors' ends closed
        door(cx - half, cy + s * half, cx + half, cy + s * half)
        door(cx - half, cy + s * outer, cx + half, cy + s * outer)
        door(cx - half + 0.2, cy + s * (half + 0.2), cx + half - 0.2, cy + s * (outer - 0.2))
    wall(2, cy - half, 2, cy + half)
    wall(WIDTH - 2, cy - half, WIDTH - 2, cy + half)
    wall(cx - half, 2, cx + half, 2)
    wall(cx - half, HEIGHT - 2, cx + half, HEIGHT - 2)
    with open(out, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (img.shape[1], img.shape[0]))
        f.write(img.tobytes())


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:  # magic, width, height, maxval; comments skipped
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    if fields[0] != b"P5" or int(fields[3]) > 255:
        sys.exit(f"{path}: not an 8-bit binary PGM")
    w, h = int(fields[1]), int(fields[2])
    return np.frombuffer(data[pos + 1:pos + 1 + w * h], np.uint8).reshape(h, w)


def tile(yaml_path, n):
    folder = os.path.dirname(yaml_path)
    image = None
    for line in open(yaml_path):
        if line.startswith("image:"):
            image = os.path.join(folder, line.split(":", 1)[1].strip().strip('"'))
    if not image or not image.endswith(".pgm"):
        sys.exit(f"{yaml_path}: no PGM image named")
    tiled = np.tile(read_pgm(image), (n, n))
    with open(image, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (tiled.shape[1], tiled.shape[0]))
        f.write(tiled.tobytes())


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "draw":
        draw(sys.argv[2])
    elif len(sys.argv) == 4 and sys.argv[1] == "tile":
        tile(sys.argv[2], int(sys.argv[3]))
    else:
        sys.exit(__doc__)
