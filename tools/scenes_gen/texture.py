"""Textures: images given texel by texel, stored as 8-bit PNG: colour (emission, base colour)
in sRGB, with or without an alpha channel, and data (normal maps) as they are."""
import struct
import zlib

# One PNG writer and one sRGB curve for every generated scene: the demo scene's, beside this
# package in tools/.
from make_demo_scene import srgb_encode, write_png


class Texture:
    """An image given by pixel(x, y) -> linear RGB in [0, 1], x right and y down; kept and written
    as 8-bit sRGB. With `frames` (Textures) it plays them, frame k written to `frames_pattern % k`
    (a path relative to the scene's folder), and this image is their poster.

    A pixel of four components carries an alpha (coverage: stored linear, as glTF reads it), and
    the image is written as RGBA; `data` images (normal maps) store their values linearly, with
    no sRGB chunk, as glTF reads every texture but colour."""

    def __init__(self, name, width, height, pixel, frames=None, frames_pattern=None, data=False):
        self.name, self.width, self.height, self.data = name, width, height, data
        self.rows = [[encode(pixel(x, y), data) for x in range(width)] for y in range(height)]
        self.frames, self.frames_pattern = frames or [], frames_pattern

    def nonzero_fraction(self):
        """Texels with any non-zero colour channel: where a light sampler can land."""
        lit = sum(1 for row in self.rows for px in row if px[:3] != (0, 0, 0))
        return lit / (self.width * self.height)

    def write(self, folder):
        if self.data or len(self.rows[0][0]) == 4:
            write_png_channels(folder / self.name, self.width, self.height, self.rows, srgb=not self.data)
        else:
            write_png(folder / self.name, self.width, self.height, self.rows)
        for k, frame in enumerate(self.frames):
            path = folder / (self.frames_pattern % k)
            path.parent.mkdir(parents=True, exist_ok=True)
            write_png(path, frame.width, frame.height, frame.rows)


def encode(pixel, data=False):
    """8-bit values: colour through the sRGB curve unless `data`, alpha (a fourth value) linear."""
    curve = (lambda c: c) if data else srgb_encode
    return tuple(round(255 * curve(c)) for c in pixel[:3]) + tuple(round(255 * a) for a in pixel[3:])


def write_png_channels(path, width, height, rows, srgb):
    """A PNG of 8-bit RGB or RGBA rows (the channels of the first texel), flagged sRGB if `srgb`:
    make_demo_scene's writer, for alpha and data."""
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))

    colour_type = {3: 2, 4: 6}[len(rows[0][0])]
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0))
    png += (chunk(b"sRGB", b"\x00") if srgb else b"") + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    path.write_bytes(png)


class Atlas:
    """A texture painted region by region: each region a rectangle of texels with a painter of its
    own, pixel(x, y) -> linear RGB in region coordinates. paint() returns its UV rectangle."""

    def __init__(self, name, width, height):
        self.name, self.width, self.height = name, width, height
        self.texels = [[(0.0, 0.0, 0.0)] * width for _ in range(height)]

    def paint(self, x0, y0, w, h, pixel):
        for y in range(h):
            row = self.texels[y0 + y]
            for x in range(w):
                row[x0 + x] = pixel(x, y)
        return (x0 / self.width, y0 / self.height, (x0 + w) / self.width, (y0 + h) / self.height)

    def texture(self):
        return Texture(self.name, self.width, self.height, lambda x, y: self.texels[y][x])
