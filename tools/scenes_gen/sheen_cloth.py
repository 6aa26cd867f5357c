"""Scene sheen-cloth (materials): fabric's grazing sheen, KHR_materials_sheen. A folded curtain
and two cushions lit from the side: dark dyed cloth whose sheen colour and roughness show at the
folds and the silhouettes."""
import math

from .gltf import MATERIALS_GENERATOR, Gltf
from .mesh import Mesh, ellipsoid, room
from .texture import Texture
from .vec import axis, normalize, smoothstep


def window_glow(width, height):
    """The side light's emission: warm, brightest in its middle."""
    def pixel(x, y):
        r = max(abs((x + 0.5) / width * 2 - 1), abs((y + 0.5) / height * 2 - 1))
        return tuple(c * (1.0 - 0.5 * smoothstep(0.5, 1.0, r)) for c in (1.0, 0.85, 0.65))
    return pixel


def curtain(left, right, top, bottom, z, depth=0.08, folds=7):
    """A curtain hanging in folds: z + depth sin(2 pi folds s) across, facing +z."""
    width, height = right - left, top - bottom
    k = 2 * math.pi * folds

    def point(s, t):
        return (left + width * s, top - height * t, z + depth * math.sin(k * s))

    def normal(s, t):
        return normalize((-depth * k * math.cos(k * s) / width, 0.0, 1.0))
    mesh = Mesh()
    mesh.add_grid(point, normal, folds * 8, 1)
    return mesh


def cloth(gltf, name, base, sheen, roughness):
    material = gltf.material(name, base, 0.0, 0.8, True)
    gltf.set_extension(material, "KHR_materials_sheen", {"sheenColorFactor": list(sheen),
                                                         "sheenRoughnessFactor": roughness})
    return material


def sheen_cloth():
    """A room lit by a 1.0 x 1.6 m light on its left wall (window-glow.png, 32 x 32, strength 10),
    low and grazing. A 3.6 x 2.6 m curtain of seven folds, 0.16 m deep, before the back wall: dark
    red (base colour (0.2, 0.02, 0.03)), sheen colour (1, 0.55, 0.6) at sheen roughness 0.4. Two
    cushions on the floor: deep blue (0.02, 0.03, 0.12) with a broad bluish sheen (0.5, 0.6, 1.0;
    roughness 0.8), and moss green (0.05, 0.12, 0.04) with a tight pale one (0.8, 0.9, 0.6;
    roughness 0.25)."""
    gltf = Gltf("sheen-cloth", MATERIALS_GENERATOR)
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.65,) * 3))
    light = Mesh()  # 2 cm off the left wall, facing into the room
    light.add_quad((-2.98, 2.0, -1.6), axis(2, 1.0), axis(1, -1.6), (1, 0, 0))
    glow = gltf.material("side light", (0.02, 0.02, 0.02))
    gltf.set_emission(glow, gltf.texture_info(Texture("window-glow.png", 32, 32, window_glow(32, 32))), 10.0)
    gltf.mesh("side light", light, glow)
    gltf.mesh("curtain", curtain(-1.8, 1.8, 2.8, 0.2, -2.6),
              cloth(gltf, "red velvet", (0.2, 0.02, 0.03), (1.0, 0.55, 0.6), 0.4))
    gltf.mesh("blue cushion", ellipsoid((-0.6, 0.2, -1.0), (0.45, 0.2, 0.45), 32, 16),
              cloth(gltf, "blue velvet", (0.02, 0.03, 0.12), (0.5, 0.6, 1.0), 0.8))
    gltf.mesh("green cushion", ellipsoid((0.7, 0.2, -0.6), (0.45, 0.2, 0.45), 32, 16),
              cloth(gltf, "green satin", (0.05, 0.12, 0.04), (0.8, 0.9, 0.6), 0.25))
    gltf.camera((0.6, 1.5, 4.0), (-0.2, 1.0, -1.5), 0.95)
    return gltf, "Sheen cloth", 16
