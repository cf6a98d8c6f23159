#!/usr/bin/env python3
"""Writes the peer scene's texture, assets/tex_checker_2048x1024.png, with the standard library only.

The same texels as make_texture.py of the peer baseline (shared/peers/): 2048 x 1024 RGB, 8 bit,
row 0 = the TOP row of the PNG;
  * a checker of 8x8-texel cells: a = 0.9 (cell (0, 0) bright) or 0.1
  * R = a * (0.3 + 0.7 * col / 2047), G = a * (0.3 + 0.7 * row / 1023), B = a
  * 1-texel white lines (1, 1, 1) at col % 128 == 0 and row % 128 == 0
stored as round(255 * value) (round half to even, as numpy rounds). Renderers read it RAW
(value = byte / 255, no sRGB decoding).

usage: python3 scripts/make_peer_texture.py [OUTPUT]   (default: assets/tex_checker_2048x1024.png
beside this script's folder)
"""
import os
import struct
import sys
import zlib

W, H = 2048, 1024


def texel_row(row):
    out = bytearray()
    for col in range(W):
        if col % 128 == 0 or row % 128 == 0:
            v = (1.0, 1.0, 1.0)
        else:
            a = 0.9 if ((col // 8) + (row // 8)) % 2 == 0 else 0.1
            v = (a * (0.3 + 0.7 * col / (W - 1)), a * (0.3 + 0.7 * row / (H - 1)), a)
        out += bytes(min(255, max(0, round(c * 255))) for c in v)
    return bytes(out)


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "assets", "tex_checker_2048x1024.png")
    # Each scanline with PNG filter 1 (Sub): the checker's runs compress far better.
    raw = bytearray()
    for row in range(H):
        line = texel_row(row)
        raw.append(1)
        raw += bytes((line[i] - (line[i - 3] if i >= 3 else 0)) & 0xFF for i in range(len(line)))
    png = (b"\x89PNG\r\n\x1a\n"
           + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(bytes(raw), 9))
           + chunk(b"IEND", b""))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(png)
    os.replace(tmp, path)
    print(f"wrote {path} ({W}x{H}, {len(png)} bytes)")


if __name__ == "__main__":
    main()
