"""Writes the synthetic normal maps of the filter's rendered comparison (tests/render_mip_test.sh), 64 x 64 texels,
16-bit RGB PNGs of (n + 1) / 2 (+y up, OpenGL's convention), made from height fields h(x, y) in texel units, the
normal (-dh/dx, -dh/dy, 1) normalised:
  bumps.png      three sines: slopes up to about 0.5 in every direction
  checker.png    cells of 2 x 2 texels tilted by slope +0.35 or -0.35 along x, alternating
  scratches.png  grooves along x: the slope along y a sine of period 3 texels, amplitude 0.6 (anisotropic)
  sawtooth.png   ramps along x of slope 0.2 for 7 texels and a riser of slope -1.4 for 1 (skewed: mean slope 0,
                 most facets tilted one way)
Usage: make_maps.py [DIR] (default: this file's folder). Deterministic: the test compares the shipped files with a
fresh run. SPDX-License-Identifier: MIT"""
import math
import os
import struct
import sys
import zlib

N = 64


def slopes(name, x, y):
    if name == "bumps":
        gx = 0.25 * math.cos(0.35 * x + 0.2 * y) + 0.2 * math.cos(0.9 * x - 0.5 * y + 1.0)
        gy = 0.25 * math.sin(0.6 * y + 0.3 * x) - 0.2 * math.cos(0.9 * x - 0.5 * y + 1.0)
        return gx, gy
    if name == "checker":
        return (0.35 if ((x // 2) + (y // 2)) % 2 else -0.35), 0.0
    if name == "scratches":
        return 0.0, 0.6 * math.sin(2.0 * math.pi * y / 3.0)
    if name == "sawtooth":
        return (0.2 if x % 8 else -1.4), 0.0
    raise ValueError(name)


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)


def write(path, name):
    raw = bytearray()
    for row in range(N):
        raw.append(0)
        y = N - 1 - row  # the top row is the largest y: +y up
        for x in range(N):
            gx, gy = slopes(name, x, y)
            l = math.sqrt(1.0 + gx * gx + gy * gy)
            for c in (-gx / l, -gy / l, 1.0 / l):
                raw += struct.pack(">H", max(0, min(65535, round((c + 1.0) / 2.0 * 65535.0))))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", N, N, 16, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b""))


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name in ("bumps", "checker", "scratches", "sawtooth"):
        write(os.path.join(out, name + ".png"), name)
