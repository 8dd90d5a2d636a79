"""Writes an 8-bit RGB PNG normal map (w x h texels, (n + 1) / 2 rounded to levels) from a CSV of normals x,y,z
(header first) and a CSV of the texels' decoded normals (each level's centre, normalised), for fit_cli_test.sh.
Usage: fit_png_map.py NORMALS.csv W H MAP.png CENTRES.csv. SPDX-License-Identifier: MIT"""
import math
import struct
import sys
import zlib

src, w, h, out, centres = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5]
rows = [line.strip().split(",") for line in open(src) if line[:1] not in ("x", "")]
data, dec = bytearray(), ["x,y,z"]
for j in range(h):
    data.append(0)  # filter: none
    for i in range(w):
        lv = [max(0, min(255, round((float(c) + 1.0) / 2.0 * 255.0))) for c in rows[j * w + i]]
        data += bytes(lv)
        v = [2.0 * c / 255.0 - 1.0 for c in lv]
        n = math.sqrt(sum(c * c for c in v))
        dec.append(",".join(repr(c / n) for c in v))


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)


with open(out, "wb") as f:
    f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(bytes(data))) + chunk(b"IEND", b""))
with open(centres, "w") as f:
    f.write("\n".join(dec) + "\n")
