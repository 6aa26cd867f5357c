"""Scene tile-emitter: a ceiling light box of many small triangles."""
import math
import random

from .gltf import Gltf
from .mesh import Mesh, box, cylinder, room, sphere
from .texture import Texture
from .vec import add, mul, smoothstep


def light_box_pixel(size, seed=11):
    """An 8 x 8 grid of rounded bright cells (LEDs behind a diffuser), warm or cool white, a
    quarter of them dimmed and some off, with black gaps between them."""
    rng = random.Random(seed)
    cells, pitch = 8, size // 8
    levels = []
    for _ in range(cells * cells):
        on, dim, warm = rng.random(), rng.random(), rng.random() < 0.5
        white = (1.0, 0.8, 0.55) if warm else (0.75, 0.85, 1.0)
        levels.append(mul(white, 0.0 if on < 0.15 else (0.35 if dim < 0.25 else 1.0)))

    def pixel(x, y):
        cx, cy = x % pitch + 0.5 - pitch / 2, y % pitch + 0.5 - pitch / 2
        half, radius = pitch * 0.36, pitch * 0.12  # a rounded square, 72% of the pitch wide
        qx, qy = max(abs(cx) - half + radius, 0.0), max(abs(cy) - half + radius, 0.0)
        inside = 1.0 - smoothstep(radius - 1.0, radius + 1.0, math.hypot(qx, qy))
        return mul(levels[(y // pitch) * cells + x // pitch], inside)
    return pixel


def light_box(centre, size, sag, cells):
    """A square panel bowed into a shallow barrel vault, lowest along its axis, facing down;
    cells x cells quads of UV-space side 1/cells."""
    def point(s, t):
        x, z = (s - 0.5) * size, (t - 0.5) * size
        return add(centre, (x, -sag * (1 - (2 * x / size) ** 2), z))

    def normal(s, t):  # downwards, tilted outwards with the slope
        return (8 * sag * (s - 0.5) / size, -1.0, 0.0)

    mesh = Mesh()
    mesh.add_grid(point, normal, cells, cells)
    return mesh


def tile_emitter():
    """A ceiling light box of 32,768 small triangles, each about 2 x 2 texels of its map."""
    gltf = Gltf("tile-emitter")
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.6,) * 3))
    gltf.mesh("table", box((0.0, 0.375, -0.6), (1.2, 0.75, 0.8), 0.2),
              gltf.material("wood", (0.55, 0.35, 0.2)))
    gltf.mesh("ball", sphere((-1.4, 0.35, 0.3), 0.35),
              gltf.material("red plastic", (0.7, 0.08, 0.05), 0.0, 0.3))
    gltf.mesh("post", cylinder((1.5, 0.0, 0.2), 0.2, 1.2),
              gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.4))
    texture = Texture("light-box.png", 256, 256, light_box_pixel(256))
    panel = light_box((0.0, 2.9, -0.6), 2.4, 0.12, 128)
    gltf.mesh("light box", panel, gltf.emissive_material("light box", texture, 10.0))
    gltf.camera((2.2, 1.5, 4.0), (-0.4, 1.1, -1.0), 0.95)
    return gltf, "Tile emitter", 16
