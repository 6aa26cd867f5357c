"""Scene floor-lamp (materials): a lamp shade that transmits, KHR_materials_transmission on a
thin, smooth shade around a textured bulb. Most of the room's light passes the shade; the rest
leaves through its open bottom."""
import math

from .gltf import MATERIALS_GENERATOR, Gltf
from .mesh import box, cylinder, frustum, room, sphere
from .texture import Texture

LAMP = (1.0, -1.2)  # where the lamp stands (x, z)


def bulb_glow(width, height):
    """The bulb's emission over its UVs (u around, v from the top): warm white, a brighter band
    round its waist where a filament would be, and a dimmer cap."""
    def pixel(x, y):
        v = (y + 0.5) / height
        band = math.exp(-((v - 0.55) / 0.08) ** 2)
        return tuple(c * (0.45 + 0.55 * band) for c in (1.0, 0.8, 0.55))
    return pixel


def floor_lamp():
    """A room lit by a floor lamp alone: a bulb 0.18 m across (bulb.png, 32 x 16, strength 40)
    1.5 m up, inside a shade (a truncated cone from 0.35 m radius at 1.3 m to 0.22 m at 1.72 m,
    with a top; open below) of smooth, warm, thin glass (base colour (1, 0.85, 0.6), roughness 0,
    transmissionFactor 0.8, double-sided). An armchair-sized block and a ball stand in the room."""
    gltf = Gltf("floor-lamp", MATERIALS_GENERATOR)
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("armchair", box((-1.0, 0.45, -1.6), (1.0, 0.9, 0.9), 0.3), gltf.material("upholstery", (0.3, 0.35, 0.5)))
    gltf.mesh("ball", sphere((0.2, 0.3, -0.6), 0.3, cols=24, rows=12),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    x, z = LAMP
    metal = gltf.material("lamp metal", (0.3, 0.3, 0.3), 1.0, 0.6)
    gltf.mesh("lamp foot", cylinder((x, 0.0, z), 0.2, 0.04, 24), metal)
    gltf.mesh("lamp pole", cylinder((x, 0.04, z), 0.02, 1.37, 12), metal)
    bulb = gltf.material("bulb", (0.02, 0.02, 0.02))
    gltf.set_emission(bulb, gltf.texture_info(Texture("bulb.png", 32, 16, bulb_glow(32, 16))), 40.0)
    gltf.mesh("bulb", sphere((x, 1.5, z), 0.09, cols=24, rows=12), bulb)
    shade = gltf.material("glass shade", (0.95, 0.8, 0.55), 0.0, 0.0, True)
    gltf.set_extension(shade, "KHR_materials_transmission", {"transmissionFactor": 0.8})
    gltf.mesh("shade", frustum((x, 1.3, z), 0.35, 0.22, 0.42), shade)
    gltf.camera((-0.5, 1.5, 3.2), (0.4, 1.0, -1.5), 0.95)
    return gltf, "Floor lamp", 16
