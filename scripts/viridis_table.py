#!/usr/bin/python3
# Generates floorgrid/io/report/viridis.cpp's 256 entries from the published degree-6 polynomial
# fit of matplotlib's viridis (Matt Zucker, shadertoy WlfXRN, CC0).
c = [
    (0.2777273272234177, 0.005407344544966578, 0.3340998053353061),
    (0.1050930431085774, 1.404613529898575, 1.384590162594685),
    (-0.3308618287255563, 0.214847559468213, 0.09509516302823659),
    (-4.634230498983486, -5.799100973351585, -19.33244095627987),
    (6.228269936347081, 14.17993336680509, 56.69055260068105),
    (4.776384997670288, -13.74514537774601, -65.35303263337234),
    (-5.435455855934631, 4.645852612178535, 26.3124352495832),
]
def f(t, k):
    v = 0.0
    for i in range(6, -1, -1):
        v = v * t + c[i][k]
    return min(1.0, max(0.0, v))
def lin(u):
    return u / 12.92 if u <= 0.04045 else ((u + 0.055) / 1.055) ** 2.4
def lstar(rgb):
    y = 0.2126 * lin(rgb[0] / 255) + 0.7152 * lin(rgb[1] / 255) + 0.0722 * lin(rgb[2] / 255)
    return 116 * y ** (1 / 3) - 16 if y > 216 / 24389 else 24389 / 27 * y
rows = []
for i in range(256):
    t = i / 255
    rows.append(tuple(int(round(255 * f(t, k))) for k in range(3)))
import sys
if len(sys.argv) > 1:
    L = [lstar(r) for r in rows]
    d = [L[i+1]-L[i] for i in range(255)]
    print(rows[0], rows[-1], min(d), max(d), L[0], L[-1])
else:
    for i in range(0, 256, 4):
        print("    " + " ".join("{{%d, %d, %d}}," % r for r in rows[i:i+4]))
