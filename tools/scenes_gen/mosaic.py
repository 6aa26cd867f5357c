"""Scene mosaic: a fine, high-contrast mosaic panel on a wall."""
import math
import random

from .gltf import Gltf
from .mesh import Mesh, box, cylinder, room, sphere
from .texture import Texture
from .vec import axis, mix, mul


def tile_color(rng, u, v):
    """A random tile at (u, v) in [0, 1]^2 of the panel: a quarter are off, intensities are
    skewed so that a few are much brighter than the rest, and hues drift from blue (top left)
    through magenta to orange (bottom right) so that the light varies at large scale too."""
    if rng.random() < 0.25:
        return (0.0, 0.0, 0.0)
    hue = 0.62 + 0.45 * (u + v) / 2 + 0.15 * (rng.random() - 0.5)
    level = rng.random() ** 3
    rgb = tuple(0.5 + 0.5 * math.cos(2 * math.pi * (hue - k / 3)) for k in range(3))
    return mul(mix(rgb, (1.0, 1.0, 1.0), 0.25), level)


def mosaic_pixel(size, seed=7):
    """8-texel cells, 30% of them split into four 4-texel tiles; the last texel row and column
    of every tile is black grout."""
    rng = random.Random(seed)
    cells = size // 8
    split = [[rng.random() < 0.3 for _ in range(cells)] for _ in range(cells)]
    tiles = {}  # (column, row, tile size) -> linear RGB; drawn in a fixed order from the seed
    for j in range(cells):
        for i in range(cells):
            if split[j][i]:
                for k in range(4):
                    tile = (2 * i + k % 2, 2 * j + k // 2, 4)
                    tiles[tile] = tile_color(rng, i / cells, j / cells)
            else:
                tiles[(i, j, 8)] = tile_color(rng, i / cells, j / cells)

    def pixel(x, y):
        tile = 4 if split[y // 8][x // 8] else 8
        if x % tile == tile - 1 or y % tile == tile - 1:
            return (0.0, 0.0, 0.0)
        return tiles[(x // tile, y // tile, tile)]
    return pixel


def mosaic():
    """A fine, high-contrast mosaic on four large triangles: 262,144 texels per triangle."""
    gltf = Gltf("mosaic")
    gltf.mesh("room", room(-2.5, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.6,) * 3))
    gltf.mesh("ball", sphere((-1.0, 0.45, 0.4), 0.45),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("crate", box((0.2, 0.4, -0.8), (0.8, 0.8, 0.8), 0.5),
              gltf.material("clay", (0.6, 0.45, 0.35)))
    gltf.mesh("post", cylinder((-0.6, 0.0, -1.6), 0.22, 1.3),
              gltf.material("gold", (1.0, 0.78, 0.35), 1.0, 0.35))
    texture = Texture("mosaic.png", 1024, 1024, mosaic_pixel(1024))
    panel = Mesh()  # 2.6 x 2.6 m, 1 cm off the left-hand wall, facing the room (+x)
    panel.add_quad((-2.49, 2.8, 1.3), axis(2, -2.6), axis(1, -2.6), (1, 0, 0), cols=2)
    gltf.mesh("mosaic panel", panel, gltf.emissive_material("mosaic", texture, 20.0))
    gltf.camera((0.9, 1.8, 4.3), (-0.7, 0.8, -1.0), 0.8)
    return gltf, "Mosaic", 16
