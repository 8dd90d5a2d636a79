"""Writes the odd inputs of fit_cli_test.sh into the current folder: RGB normal maps of 64 x 1 and 1 x 64 texels,
8- and 16-bit maps whose normals all point below the plane, a height field with one absurd finite height, and x3p
archives damaged or lying in every way the reader checks (truncated, a flipped CRC, a wrong MD5, sizes that are not
the data's, a profile). Usage: fit_odd_inputs.py. SPDX-License-Identifier: MIT"""
import hashlib
import math
import random
import struct
import zipfile
import zlib


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)


def png(name, w, h, bits, texels):
    """An RGB PNG of w x h texels, each (r, g, b) in levels of the given depth."""
    data = bytearray()
    for j in range(h):
        data.append(0)
        for i in range(w):
            for c in texels[j * w + i]:
                data += struct.pack(">H", c) if bits == 16 else bytes([c])
    with open(name, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, bits, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(bytes(data))) + chunk(b"IEND", b""))


def level(c, bits):
    top = (1 << bits) - 1
    return max(0, min(top, round((c + 1.0) / 2.0 * top)))


random.seed(4)
normals = []
for k in range(64):
    x, y = random.gauss(0, 0.2), random.gauss(0, 0.2)
    n = math.sqrt(1 + x * x + y * y)
    normals.append((x / n, y / n, 1 / n))
png("row.png", 64, 1, 8, [tuple(level(c, 8) for c in m) for m in normals])
png("column.png", 1, 64, 8, [tuple(level(c, 8) for c in m) for m in normals])
below = [(m[0], m[1], -m[2]) for m in normals]
for bits in (8, 16):
    png("below%d.png" % bits, 8, 8, bits, [tuple(level(c, bits) for c in m) for m in below])

rows = [[random.gauss(0, 1) for i in range(40)] for j in range(40)]
rows[20][20] = 1e308
with open("absurd.txt", "w") as f:
    f.write("\n".join(" ".join("%.17g" % v for v in r) for r in rows) + "\n")

AXIS = "<AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset>0</Offset>"


def main_xml(feature, sx, sy, md5=None):
    link = "<PointDataLink>bindata/data.bin</PointDataLink>"
    if md5:
        link += "<MD5ChecksumPointData>%s</MD5ChecksumPointData>" % md5
    return ('<?xml version="1.0"?><p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2"><Record1>'
            "<Revision>ISO5436 - 2000</Revision><FeatureType>%s</FeatureType><Axes><CX>%s</CX><CY>%s</CY>"
            "<CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1><Record3><MatrixDimension>"
            "<SizeX>%d</SizeX><SizeY>%d</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataLink>%s</DataLink></Record3>"
            "<Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4></p:ISO5436_2>"
            % (feature, AXIS, AXIS, sx, sy, link)).encode()


def x3p(name, xml, data, xml_md5=None):
    with zipfile.ZipFile(name, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("main.xml", xml)
        z.writestr("bindata/data.bin", data)
        z.writestr("md5checksum.hex", (xml_md5 or hashlib.md5(xml).hexdigest()) + " *main.xml\n")


pts = struct.pack("<16d", *[random.gauss(0, 1e-6) for k in range(16)])
good = main_xml("SUR", 4, 4, hashlib.md5(pts).hexdigest())
x3p("good.x3p", good, pts)
x3p("lying.x3p", main_xml("SUR", 5, 4), pts)
x3p("profile.x3p", main_xml("PRF", 16, 1), pts)
x3p("md5.x3p", good, pts, "0" * 32)
x3p("datamd5.x3p", main_xml("SUR", 4, 4, "f" * 32), pts)
raw = open("good.x3p", "rb").read()
open("truncated.x3p", "wb").write(raw[: len(raw) - 40])
b = bytearray(raw)
for sig, off, name_at in ((b"PK\x03\x04", 14, 30), (b"PK\x01\x02", 16, 46)):
    at = 0
    while (at := b.find(sig, at)) >= 0:
        if b[at + name_at: at + name_at + 16] == b"bindata/data.bin":
            b[at + off] ^= 1
        at += 4
open("crc.x3p", "wb").write(bytes(b))
