#!/usr/bin/env python3
"""Convert a binary PGM (P5, 8-bit) to a greyscale PNG, optionally enlarged by an
integer factor (nearest neighbour). Standard library only (zlib, struct).

    tools/pgm_to_png.py in.pgm out.png [scale]
"""
import struct
import sys
import zlib


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:
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
    if fields[0] != b"P5" or int(fields[3]) != 255:
        sys.exit(f"{path}: not an 8-bit binary PGM")
    width, height = int(fields[1]), int(fields[2])
    raster = data[pos + 1:pos + 1 + width * height]
    return width, height, raster


def write_png(path, width, height, raster, scale):
    rows = []
    for y in range(height * scale):
        src = raster[(y // scale) * width:(y // scale + 1) * width]
        rows.append(b"\x00" + bytes(b for b in src for _ in range(scale)))

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))

    header = struct.pack(">IIBBBBB", width * scale, height * scale, 8, 0, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
                chunk(b"IDAT", zlib.compress(b"".join(rows), 9)) + chunk(b"IEND", b""))


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    w, h, pixels = read_pgm(sys.argv[1])
    write_png(sys.argv[2], w, h, pixels, int(sys.argv[3]) if len(sys.argv) == 4 else 1)
