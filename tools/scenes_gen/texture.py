"""Emission textures: images given texel by texel, stored as 8-bit sRGB PNG."""
# One PNG writer and one sRGB curve for every generated scene: the demo scene's, beside this
# package in tools/.
from make_demo_scene import srgb_encode, write_png


class Texture:
    """An image given by pixel(x, y) -> linear RGB in [0, 1], x right and y down; kept and written
    as 8-bit sRGB. With `frames` (Textures) it plays them, frame k written to `frames_pattern % k`
    (a path relative to the scene's folder), and this image is their poster."""

    def __init__(self, name, width, height, pixel, frames=None, frames_pattern=None):
        self.name, self.width, self.height = name, width, height
        self.rows = [[encode(pixel(x, y)) for x in range(width)] for y in range(height)]
        self.frames, self.frames_pattern = frames or [], frames_pattern

    def nonzero_fraction(self):
        """Texels with any non-zero channel: where a light sampler can land."""
        lit = sum(1 for row in self.rows for px in row if px != (0, 0, 0))
        return lit / (self.width * self.height)

    def write(self, folder):
        write_png(folder / self.name, self.width, self.height, self.rows)
        for k, frame in enumerate(self.frames):
            path = folder / (self.frames_pattern % k)
            path.parent.mkdir(parents=True, exist_ok=True)
            write_png(path, frame.width, frame.height, frame.rows)


def encode(rgb):
    return tuple(round(255 * srgb_encode(c)) for c in rgb)


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
