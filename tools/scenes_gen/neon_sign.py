"""Scene neon-sign: a room lit only by a neon sign on a wall."""
from .gltf import Gltf
from .mesh import Mesh, box, cylinder, room, sphere
from .neon import arc, neon_pixel, segment, wave
from .texture import Texture
from .vec import axis


def neon_strokes():
    """(shape, linear RGB) pairs: the word TRS, a ring around a bolt, an arrow, a wavy line."""
    cyan, pink, yellow = (0.1, 0.8, 1.0), (1.0, 0.1, 0.6), (1.0, 0.85, 0.1)
    green, orange = (0.2, 1.0, 0.3), (1.0, 0.45, 0.05)
    letters = [segment(80, 50, 220, 50), segment(150, 50, 150, 190),  # T
               segment(265, 50, 265, 190), segment(265, 50, 300, 50),  # R
               segment(265, 130, 300, 130), arc(300, 90, 40, -90, 90),
               segment(300, 130, 350, 190),
               arc(430, 85, 35, 90, 340), arc(430, 155, 35, -90, 160)]  # S
    bolt = [(625, 70), (660, 118), (622, 128), (658, 175)]
    arrow = [((770, 120), (960, 120)), ((960, 120), (920, 88)), ((960, 120), (920, 152))]
    return ([(shape, cyan) for shape in letters] + [(arc(640, 120, 70, 0, 360), pink)]
            + [(segment(*a, *b), yellow) for a, b in zip(bolt, bolt[1:])]
            + [(segment(*a, *b), green) for a, b in arrow]
            + [(wave(70, 950, 228, 7, 110), orange)])


def neon_sign():
    """The README demo: a room with a few objects, lit only by a neon sign on a wall."""
    gltf = Gltf("neon-sign")
    gltf.mesh("room", room(-3.0, 3.0, 3.2, -2.5, 4.5), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("crate", box((0.6, 0.35, -1.6), (0.7, 0.7, 0.7), 0.35),
              gltf.material("crate", (0.7, 0.55, 0.4)))
    gltf.mesh("ball", sphere((1.5, 0.45, 0.4), 0.45),
              gltf.material("red plastic", (0.7, 0.08, 0.05), 0.0, 0.3))
    gltf.mesh("post", cylinder((-0.3, 0.0, -0.2), 0.25, 1.1),
              gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.4))
    texture = Texture("neon.png", 1024, 256, neon_pixel(neon_strokes()))
    sign = Mesh()  # 3.2 x 0.8 m, 2 cm off the right-hand wall, facing into the room (-x)
    sign.add_quad((2.98, 2.45, -1.9), axis(2, 3.2), axis(1, -0.8), (-1, 0, 0))
    gltf.mesh("neon sign", sign, gltf.emissive_material("neon", texture, 100.0))
    gltf.camera((-2.3, 1.6, 3.9), (1.2, 1.1, -1.0), 0.75)
    return gltf, "Neon sign", 16
