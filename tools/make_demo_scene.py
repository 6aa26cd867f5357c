#!/usr/bin/env python3
"""Writes the demo scene: a curved panel (OBJ) and a neon-sign emission map (8-bit sRGB PNG).

Python standard library only, so the committed files can be regenerated anywhere:
    python3 tools/make_demo_scene.py scenes/demo
"""
import math
import struct
import sys
import zlib
from pathlib import Path

WIDTH, HEIGHT = 512, 128
COLUMNS, ROWS = 64, 16  # panel grid: 2 * 64 * 16 = 2048 triangles


def srgb_encode(linear):
    linear = min(max(linear, 0.0), 1.0)
    if linear <= 0.0031308:
        return 12.92 * linear
    return 1.055 * linear ** (1 / 2.4) - 0.055


def neon_strokes():
    """(distance function, linear RGB) pairs; distances in texels."""
    def wave(x, y):
        return abs(y - (64 + 34 * math.sin(x / 512 * 4 * math.pi)))

    def ring(x, y):
        return abs(math.hypot(x - 420, y - 64) - 40)

    def bar(x, y):
        return math.hypot(max(abs(x - 110) - 70, 0), y - 112)

    return [(wave, (1.0, 0.1, 0.6)), (ring, (0.1, 0.8, 1.0)), (bar, (1.0, 0.6, 0.1))]


def pixel(x, y):
    r = g = b = 0.0
    for distance, color in neon_strokes():
        d = distance(x + 0.5, y + 0.5)
        core = 1.0 if d < 2.0 else 0.0       # the tube
        glow = 0.25 * math.exp(-(d / 6.0) ** 2)  # the halo; exactly zero far from the strokes
        w = core + (glow if d < 18 else 0.0)
        r, g, b = r + w * color[0], g + w * color[1], b + w * color[2]
    return tuple(round(255 * srgb_encode(c)) for c in (r, g, b))


def write_png(path, width, height, rows):
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))

    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"sRGB", b"\x00") + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    path.write_bytes(png)


def write_panel(path):
    """A 4 x 1 panel bent into a shallow arc; OBJ UVs (v up: image row 0 at v = 1)."""
    lines = ["# Curved neon panel, 4 x 1 units, " + str(2 * COLUMNS * ROWS) + " triangles"]
    for j in range(ROWS + 1):
        for i in range(COLUMNS + 1):
            u, v = i / COLUMNS, j / ROWS
            angle = (u - 0.5) * 1.2
            lines.append(f"v {3.5 * math.sin(angle):.6f} {v:.6f} {3.5 * (1 - math.cos(angle)):.6f}")
            lines.append(f"vt {u:.6f} {v:.6f}")
    for j in range(ROWS):
        for i in range(COLUMNS):
            a = j * (COLUMNS + 1) + i + 1
            b, c, d = a + 1, a + COLUMNS + 1, a + COLUMNS + 2
            lines.append(f"f {a}/{a} {b}/{b} {d}/{d}")
            lines.append(f"f {a}/{a} {d}/{d} {c}/{c}")
    path.write_text("\n".join(lines) + "\n")


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "scenes/demo")
    out.mkdir(parents=True, exist_ok=True)
    write_png(out / "neon.png", WIDTH, HEIGHT, [[pixel(x, y) for x in range(WIDTH)] for y in range(HEIGHT)])
    write_panel(out / "neon-panel.obj")


if __name__ == "__main__":
    main()
