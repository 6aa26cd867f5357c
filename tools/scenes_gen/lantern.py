"""Scene lantern: a ball lantern pierced with bright dots, hanging in a room."""
import math
import random

from .gltf import Gltf
from .mesh import box, cylinder, room, sphere, sphere_direction
from .texture import Texture
from .vec import add, dot, mul, smoothstep


def lantern_pixels(width, height, dots=90, radius=0.05, seed=5):
    """Round dots, scattered evenly over the sphere (a jittered Fibonacci lattice), on black: a
    bright core with a soft rim, each dot warm, cool or amber white and some dimmer. Returns
    pixel(x, y) over a map rasterised dot by dot (each touches only the texels near it)."""
    rng = random.Random(seed)
    texels = [[(0.0, 0.0, 0.0)] * width for _ in range(height)]
    golden = math.pi * (3 - math.sqrt(5))
    for k in range(dots):
        y = 1 - 2 * (k + 0.5 + rng.uniform(-0.3, 0.3)) / dots
        phi = golden * k + rng.uniform(-0.2, 0.2)
        r = math.sqrt(max(1 - y * y, 0.0))
        centre = (r * math.sin(phi), y, r * math.cos(phi))
        colour = mul(rng.choice([(1.0, 0.85, 0.6), (0.75, 0.85, 1.0), (1.0, 0.6, 0.25)]),
                     rng.choice([1.0, 1.0, 0.5, 0.25]))
        theta = math.acos(max(-1.0, min(1.0, centre[1])))
        t0 = max(int((theta - radius) / math.pi * height) - 1, 0)
        t1 = min(int((theta + radius) / math.pi * height) + 2, height)
        for j in range(t0, t1):
            for i in range(width):
                d = sphere_direction((i + 0.5) / width, (j + 0.5) / height)
                angle = math.acos(max(-1.0, min(1.0, dot(d, centre))))
                if angle < radius:
                    weight = 1.0 - smoothstep(0.6 * radius, radius, angle)
                    texels[j][i] = add(texels[j][i], mul(colour, weight))
    return lambda x, y: tuple(min(c, 1.0) for c in texels[y][x])


def lantern():
    """A ball lantern pierced with sparse bright dots, hanging in the middle of a room: its
    lights face every way, so from any point of the room about half of them face away."""
    gltf = Gltf("lantern")
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("table", box((-0.9, 0.375, -1.2), (1.2, 0.75, 0.8), 0.3),
              gltf.material("wood", (0.55, 0.35, 0.2)))
    gltf.mesh("ball", sphere((1.3, 0.4, 0.2), 0.4),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("post", cylinder((1.2, 0.0, -1.7), 0.2, 1.4),
              gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.4))
    texture = Texture("lantern.png", 512, 256, lantern_pixels(512, 256))
    ball = sphere((0.0, 1.9, -0.6), 0.4, cols=48, rows=24)
    gltf.mesh("lantern", ball, gltf.emissive_material("lantern", texture, 250.0))
    gltf.camera((2.3, 1.5, 4.1), (-0.3, 1.3, -1.0), 0.9)
    return gltf, "Lantern", 16
