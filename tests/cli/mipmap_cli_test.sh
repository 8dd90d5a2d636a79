#!/bin/sh
# ggx mipmap from the command line: a constant normal map keeps its lobe at every level, a checkerboard's tilts
# widen its levels across them and nowhere else, the levels' OpenEXR files hold the six channels at the sizes of the
# chain (odd sizes included), rejected texels are counted, and malformed input exits 2 with one line and no files.
# Usage: mipmap_cli_test.sh GGX   SPDX-License-Identifier: MIT
set -u
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
. "$ROOT/tests/support/cli_common.sh"
PY=/usr/bin/python3

"$GGX" mipmap --help > h.txt && grep -q "usage: ggx mipmap" h.txt && ok || bad "ggx mipmap --help"
# maps as CSVs of normals (x,y,z), written as 8-bit PNGs by tests/support/fit_png_map.py
"$PY" - <<'EOF_PY'
import math
def write(name, w, h, f):
    with open(name, "w") as out:
        out.write("x,y,z\n")
        for j in range(h):
            for i in range(w):
                v = f(i, j)
                z = v[2] if len(v) > 2 else math.sqrt(max(0.0, 1 - v[0] * v[0] - v[1] * v[1]))
                out.write("%r,%r,%r\n" % (v[0], v[1], z))
write("const.csv", 10, 6, lambda i, j: (0.3, -0.2))
write("checker.csv", 8, 8, lambda i, j: (0.3 if (i + j) % 2 else -0.3, 0.0))
write("flat_edge.csv", 4, 4, lambda i, j: (0.6, 0.0, -0.8) if i == 0 and j == 0 else (0.0, 0.0))
write("one.csv", 1, 1, lambda i, j: (0.3, -0.2))
write("row.csv", 1, 3, lambda i, j: (0.3 * j, 0.0))
write("below.csv", 2, 2, lambda i, j: (0.6, 0.0, -0.8))
EOF_PY
if ! "$PY" "$ROOT/tests/support/fit_png_map.py" const.csv 10 6 const.png c1.csv ||
   ! "$PY" "$ROOT/tests/support/fit_png_map.py" checker.csv 8 8 checker.png c2.csv ||
   ! "$PY" "$ROOT/tests/support/fit_png_map.py" flat_edge.csv 4 4 edge.png c3.csv ||
   ! "$PY" "$ROOT/tests/support/fit_png_map.py" one.csv 1 1 one.png c4.csv ||
   ! "$PY" "$ROOT/tests/support/fit_png_map.py" row.csv 1 3 row.png c5.csv ||
   ! "$PY" "$ROOT/tests/support/fit_png_map.py" below.csv 2 2 below.png c6.csv; then
    bad "writing the test maps"
fi
if "$GGX" mipmap --normal-map const.png --alpha 0.2 --out cm > cm.txt 2> cm.err; then
    # a constant map: every level the same mean slope and width (10 x 6 -> 5 x 3 -> 3 x 2 -> 2 x 1 -> 1 x 1)
    [ "$(grep -c '^| [0-9]' cm.txt)" -eq 5 ] && [ "$(grep '^| [0-9]' cm.txt | cut -d'|' -f4,5 | sort -u | wc -l)" -eq 1 ] &&
        ok || bad "constant map: levels differ: $(cat cm.txt)"
    grep -q "(0 rejected)" cm.txt && ok || bad "constant map: rejected texels: $(head -1 cm.txt)"
    # the files: six float channels each, at the chain's sizes
    "$PY" - <<'EOF_PY' && ok || bad "constant map: the levels' OpenEXR headers"
import struct
sizes = [(10, 6), (5, 3), (3, 2), (2, 1), (1, 1)]
for k, (w, h) in enumerate(sizes):
    d = open("cm/level-%d.exr" % k, "rb").read()
    assert d[:4] == b"\x76\x2f\x31\x01", k
    p, attrs = 8, {}
    while d[p] != 0:
        name_end = d.index(b"\0", p); name = d[p:name_end].decode()
        type_end = d.index(b"\0", name_end + 1)
        size = struct.unpack("<i", d[type_end + 1:type_end + 5])[0]
        attrs[name] = d[type_end + 5:type_end + 5 + size]
        p = type_end + 5 + size
    ch, names = attrs["channels"], []
    q = 0
    while ch[q] != 0:
        e = ch.index(b"\0", q); names.append(ch[q:e].decode())
        assert struct.unpack("<i", ch[e + 1:e + 5])[0] == 2, "FLOAT"
        q = e + 17
    assert sorted(names) == sorted(["t.x", "t.y", "sigma.xx", "sigma.xy", "sigma.yy", "weight"]), names
    x0, y0, x1, y1 = struct.unpack("<iiii", attrs["dataWindow"])
    assert (x1 - x0 + 1, y1 - y0 + 1) == (w, h), (k, x0, y0, x1, y1)
EOF_PY
    [ ! -e cm/level-5.exr ] && ok || bad "a level below 1 x 1"
    # png16: the normal image is a normal map again (its level 0 has the same mean slope, to 16-bit levels), the
    # sigma image decodes to alpha 0.2 on both axes and no correlation at every level, and its alpha to the share
    # of the box's base texels in the map
    "$GGX" mipmap --normal-map const.png --alpha 0.2 --format png16 --out pm > pm.txt && ok || bad "png16"
    [ "$(ls pm | wc -l)" -eq 10 ] && ok || bad "png16 files: $(ls pm)"
    "$GGX" mipmap --normal-map pm/level-2-normal.png --alpha 0.2 --out pm2 > pm2.txt &&
        awk -F'|' 'NR == FNR && /^\| 0 / { split($4, a, ","); next } /^\| 0 / && NR != FNR {
            split($4, b, ","); d0 = a[1] - b[1]; d1 = a[2] - b[2]; if (d0 < 0) d0 = -d0; if (d1 < 0) d1 = -d1;
            exit !(d0 < 1e-4 && d1 < 1e-4) }' cm.txt pm2.txt && ok || bad "png16 normal image: $(sed -n 3,4p pm2.txt)"
    "$PY" - <<'EOF_PY' && ok || bad "png16 sigma image"
import struct, zlib
def png16(path):
    d = open(path, "rb").read()
    p, idat, hdr = 8, b"", None
    while p < len(d):
        n = struct.unpack(">I", d[p:p + 4])[0]; kind = d[p + 4:p + 8]; body = d[p + 8:p + 8 + n]; p += 12 + n
        if kind == b"IHDR": hdr = struct.unpack(">IIBB", body[:10])
        if kind == b"IDAT": idat += body
    w, h, bits, ctype = hdr
    ch = {0: 1, 4: 2, 2: 3, 6: 4}[ctype]
    bpp, raw, rows, prev = 2 * ch, zlib.decompress(idat), [], bytearray(w * 2 * ch)
    stride = w * bpp
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0; b = prev[i]; c = prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([[(line[(x * ch + k) * 2] << 8 | line[(x * ch + k) * 2 + 1]) / 65535 for k in range(ch)]
                     for x in range(w)])
        prev = line
    return rows
for k in range(5):
    for row in png16("pm/level-%d-sigma.png" % k):
        for r, g, b, a in row:
            assert abs(4 * r - 0.2) < 1e-4 and abs(4 * g - 0.2) < 1e-4 and abs(2 * b - 1) < 1e-4, (k, r, g, b)
    # the weight share of texel (0, 0): the base texels of its box inside the 10 x 6 map over 4^k
    want = min(2 ** k, 10) * min(2 ** k, 6) / 4 ** k
    assert abs(png16("pm/level-%d-sigma.png" % k)[0][0][3] - want) < 1e-4, (k, want)
EOF_PY
    # a checkerboard of tilts +-0.3 in x: every coarser level is wider than the base lobe, centred on t = 0
    "$GGX" mipmap --normal-map checker.png --alpha 0.1 --out ck > ck.txt && ok || bad "checker"
    awk -F'|' '/^\| [1-9]/ { split($4, t, ","); if (!($5 + 0 > 0.15) || t[1] + 0 > 1e-3 || t[1] + 0 < -1e-3) bad = 1 }
               /^\| 0 / { if ($5 + 0 != 0.1) bad = 1 } END { exit bad }' ck.txt && ok || bad "checker levels: $(cat ck.txt)"
    # roughness maps (grey 8-bit PNGs): 51 / 255 = 0.2 everywhere is --alpha 0.2, level for level; with --perceptual
    # 102 / 255 = 0.4 is alpha 0.16; a map whose texel is 0 gives that texel alpha 1e-4 (the mean width drops)
    "$PY" - <<'EOF_PY' || bad "writing the roughness maps"
import struct, zlib
def grey(name, w, h, f):
    raw = b"".join(b"\0" + bytes(f(i, j) for i in range(w)) for j in range(h))
    chunk = lambda k, b: struct.pack(">I", len(b)) + k + b + struct.pack(">I", zlib.crc32(k + b) & 0xFFFFFFFF)
    open(name, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0)) +
                           chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
grey("r02.png", 10, 6, lambda i, j: 51)
grey("r04.png", 10, 6, lambda i, j: 102)
grey("r0.png", 10, 6, lambda i, j: 0 if i == 0 and j == 0 else 51)
grey("small.png", 5, 3, lambda i, j: 51)
EOF_PY
    "$GGX" mipmap --normal-map const.png --roughness-map r02.png --out rm > rm.txt &&
        [ "$(grep '^| [0-9]' rm.txt | cut -d'|' -f2-5)" = "$(grep '^| [0-9]' cm.txt | cut -d'|' -f2-5)" ] &&
        grep -q "roughness r02.png" rm.txt && ok || bad "roughness map 0.2: $(cat rm.txt)"
    "$GGX" mipmap --normal-map const.png --alpha 0.16 --out a16 > a16.txt &&
        "$GGX" mipmap --normal-map const.png --roughness-map r04.png --perceptual --out rp > rp.txt &&
        [ "$(grep '^| [0-9]' rp.txt | cut -d'|' -f2-5)" = "$(grep '^| [0-9]' a16.txt | cut -d'|' -f2-5)" ] && ok ||
        bad "perceptual roughness map 0.4: $(cat rp.txt) against $(cat a16.txt)"
    "$GGX" mipmap --normal-map const.png --roughness-map r0.png --out r0 > r0.txt &&
        grep -q "(0 rejected)" r0.txt && awk -F'|' '/^\| 0 / { exit !($5 + 0 < 0.2 && $5 + 0 > 0.19) }' r0.txt && ok ||
        bad "a roughness map's 0: $(cat r0.txt)"
    # a multi-channel OpenEXR (a level of a chain: six channels) is no roughness map
    one_line "roughness map of six channels" "6 channels: give a one-channel OpenEXR" 2 "$GGX" mipmap \
        --normal-map const.png --roughness-map cm/level-0.exr --out none
    # the largest alpha: the chain holds Sigma's eigenvalues within GGX_ALPHA_MAX^2 at every level
    "$GGX" mipmap --normal-map checker.png --alpha 1e4 --out big > big.txt && grep -q "^| 3 | 1 x 1" big.txt && ok ||
        bad "alpha 1e4: $(cat big.txt)"
    # the fast mode: the constant map's levels are the same lobe, the checkerboard's widen as the exact filter's do
    "$GGX" mipmap --normal-map const.png --alpha 0.2 --fast --out cf > cf.txt &&
        [ "$(grep '^| [0-9]' cf.txt | cut -d'|' -f2-5)" = "$(grep '^| [0-9]' cm.txt | cut -d'|' -f2-5)" ] &&
        grep -q "fast mode" cf.txt && ok || bad "fast mode, constant map: $(cat cf.txt)"
    "$GGX" mipmap --normal-map checker.png --alpha 0.1 --fast --out kf > kf.txt &&
        awk -F'|' '/^\| [1-9]/ { split($4, t, ","); if (!($5 + 0 > 0.15) || t[1] + 0 > 1e-3 || t[1] + 0 < -1e-3) bad = 1 }
                   END { exit bad }' kf.txt && ok || bad "fast mode, checker: $(cat kf.txt)"
    # maps of one texel and of one column: a chain of one level, and 1 x 3 -> 1 x 2 -> 1 x 1
    "$GGX" mipmap --normal-map one.png --alpha 0.2 --out one > one.txt && [ "$(grep -c '^| [0-9]' one.txt)" -eq 1 ] &&
        [ -s one/level-0.exr ] && [ ! -e one/level-1.exr ] && ok || bad "1 x 1 map: $(cat one.txt)"
    "$GGX" mipmap --normal-map row.png --alpha 0.2 --out row > row.txt &&
        [ "$(grep '^| [0-9]' row.txt | cut -d'|' -f3 | tr -d ' ' | tr '\n' ' ')" = "1x3 1x2 1x1 " ] && ok ||
        bad "1 x 3 map: $(cat row.txt)"
    # a texel below the tangent plane is rejected and counted; a map of rejected texels only is no chain: one line,
    # exit 2, no folder
    "$GGX" mipmap --normal-map edge.png --alpha 0.3 --out em > em.txt && grep -q "(1 rejected)" em.txt && ok ||
        bad "rejected texel: $(head -1 em.txt)"
    one_line "every texel rejected" "below.png: every texel is rejected" 2 "$GGX" mipmap --normal-map below.png \
        --alpha 0.3 --out none
    # --out - is standard output, no folder: refused with no folder named - made; a folder given as the map is
    # refused with the system's reason
    one_line "--out -" "'-' is standard output" 2 "$GGX" mipmap --normal-map const.png --alpha 0.2 --out -
    [ ! -e ./- ] && ok || bad "--out - made a folder named -"
    mkdir adir.png
    one_line "a folder as the map" "cannot read 'adir.png': Is a directory" 2 "$GGX" mipmap --normal-map adir.png \
        --alpha 0.2 --out dm
    # a chain into the folder of an earlier, longer one: the deeper levels of the earlier one go, of the format
    # written only; other names (the user's files, names the command does not write) stay
    "$GGX" mipmap --normal-map const.png --alpha 0.2 --out stale > /dev/null &&
        "$GGX" mipmap --normal-map const.png --alpha 0.2 --format png16 --out stale > /dev/null &&
        touch stale/level-03.exr stale/level-9.txt stale/notes.exr stale/level-5-sigma.png.bak &&
        "$GGX" mipmap --normal-map row.png --alpha 0.2 --out stale > /dev/null 2> stale.err &&
        [ "$(cd stale && ls level-[0-9]*.exr | tr '\n' ' ')" = "level-0.exr level-03.exr level-1.exr level-2.exr " ] &&
        [ -e stale/level-9.txt ] && [ -e stale/notes.exr ] && [ -e stale/level-4-sigma.png ] &&
        grep -q "removed 2 files of levels 3 and beyond" stale.err && ok ||
        bad "stale exr levels: $(ls stale | tr '\n' ' ') $(cat stale.err)"
    "$GGX" mipmap --normal-map row.png --alpha 0.2 --format png16 --out stale > /dev/null 2> stale.err &&
        [ "$(cd stale && ls level-*.png | tr '\n' ' ')" = "level-0-normal.png level-0-sigma.png level-1-normal.png \
level-1-sigma.png level-2-normal.png level-2-sigma.png " ] && [ -e stale/level-5-sigma.png.bak ] &&
        [ "$(ls stale/level-*.exr | wc -l)" -eq 4 ] && grep -q "removed 4 files" stale.err && ok ||
        bad "stale png16 levels: $(ls stale | tr '\n' ' ') $(cat stale.err)"
    # output folders of any length: 1016 and 2040 bytes, and 4080 (whose temporaries' names pass the system's limit
    # on paths: the levels are created in place); past that limit the system's refusal, in one line
    c=$(printf 'c%.0s' $(seq 1 200))
    long_dir() { # a relative path of exactly $1 bytes, of components of at most 200 bytes
        p=""
        while [ $((${#p} + 201)) -lt "$1" ]; do p="$p$c/"; done
        printf '%s%s' "$p" "$(printf 'e%.0s' $(seq 1 $(($1 - ${#p}))))"
    }
    for len in 1016 2040 4080; do
        d=$(long_dir $len)
        mkdir -p "${d%/*}" && "$GGX" mipmap --normal-map row.png --alpha 0.2 --out "$d" > /dev/null &&
            [ "$(ls "$d" | tr '\n' ' ')" = "level-0.exr level-1.exr level-2.exr " ] &&
            [ "$(find "$c" -type f | wc -l)" -eq 3 ] && ok || bad "mipmap into a $len-byte folder: $(find "$c" -type f | sed 's|.*/||')"
        rm -rf "$c"
    done
    one_line "a folder past the system's limit on paths" "File name too long" 2 "$GGX" mipmap --normal-map row.png \
        --alpha 0.2 --out "$(long_dir 4200)"
    # SIGTERM or SIGINT while the chain is written: the folder the command made goes with the temporaries; a folder
    # that was there stays, with what the user had put in it (SIGINT through perl: a background job ignores it)
    "$PY" - <<'EOF_PY' || bad "writing the large map"
import math, struct, zlib
w = h = 256
raw = b"".join(b"\0" + bytes(v for i in range(w) for v in (int(127.5 + 40 * math.sin(0.7 * i)),
                                                        int(127.5 + 40 * math.cos(1.3 * j)), 240)) for j in range(h))
chunk = lambda k, b: struct.pack(">I", len(b)) + k + b + struct.pack(">I", zlib.crc32(k + b) & 0xFFFFFFFF)
open("wide.png", "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                             chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
EOF_PY
    for sig in TERM INT; do
        for folder in made found; do
            rm -rf sig
            [ $folder = found ] && mkdir sig && echo mine > sig/mine.txt
            perl -e '$SIG{INT} = "DEFAULT"; exec @ARGV' "$GGX_BIN" mipmap --normal-map wide.png --alpha 0.2 --out sig \
                > /dev/null &
            pid=$!
            i=0; while [ $i -lt 250 ] && [ -z "$(ls sig 2>/dev/null | grep tmp)" ]; do sleep 0.02; i=$((i + 1)); done
            kill -$sig $pid; wait $pid; rc=$?
            if [ $folder = made ]; then left=$(ls -d sig 2>/dev/null); else left=$(ls sig | grep -vx mine.txt); fi
            [ $rc -gt 128 ] && [ -z "$left" ] && { [ $folder = made ] || [ "$(cat sig/mine.txt)" = mine ]; } && ok ||
                bad "SIG$sig during mipmap into a folder it $folder: status $rc, left $left $(ls sig 2>/dev/null)"
        done
    done
elif grep -q "not built" cm.err; then
    echo "mipmap CLI: PNG or OpenEXR support is off, the maps are not tested"
else
    bad "mipmap: $(cat cm.err)"
fi
# malformed input: one line, exit 2, nothing written
one_line "no normal map" "--normal-map FILE is required" 2 "$GGX" mipmap --alpha 0.2 --out none
one_line "no alpha" "give the base roughness" 2 "$GGX" mipmap --normal-map const.png --out none
one_line "alpha and a map" "give the base roughness" 2 "$GGX" mipmap --normal-map const.png --alpha 0.2 \
    --roughness-map r02.png --out none
one_line "perceptual alone" "--perceptual applies to --roughness-map" 2 "$GGX" mipmap --normal-map const.png \
    --alpha 0.2 --perceptual --out none
if [ -e r02.png ]; then
    one_line "roughness map of another size" "5 x 3 texels, the normal map 10 x 6" 2 "$GGX" mipmap \
        --normal-map const.png --roughness-map small.png --out none
fi
one_line "bad format" "is not exr or png16" 2 "$GGX" mipmap --normal-map const.png --alpha 0.2 --format png --out none
one_line "alpha 0" "--alpha" 2 "$GGX" mipmap --normal-map const.png --alpha 0 --out none
one_line "missing file" "missing.png" 2 "$GGX" mipmap --normal-map missing.png --alpha 0.2 --out none
[ ! -e none ] && ok || bad "a failed mipmap left its folder"

echo "mipmap CLI: $pass passed, $fail failed"
[ $fail -eq 0 ]
