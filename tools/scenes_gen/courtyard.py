"""Scene courtyard: an open yard under a low sun, with a street lamp, a porch spot and a neon
sign: punctual lights (KHR_lights_punctual) beside an emissive texture."""
from .gltf import Gltf
from .mesh import Mesh, box, sphere
from .neon import neon_pixel
from .neon_sign import neon_strokes
from .texture import Texture
from .vec import axis

LUMENS_PER_WATT = 683  # the file's candela and lux, as Blender's glTF importer reads them


def courtyard():
    """A 16 x 16 m yard before a wall: the sun (1,500 lux) lights it from the left, a lamp post's
    bulb and a spot over a door light the wall, and the neon sign of neon-sign hangs on it."""
    gltf = Gltf("courtyard")
    ground = Mesh()
    ground.add_quad((-8.0, 0.0, 8.0), axis(0, 16.0), axis(2, -16.0), (0, 1, 0))
    gltf.mesh("ground", ground, gltf.material("paving", (0.45, 0.43, 0.4)))
    wall = Mesh()
    wall.add_quad((-8.0, 0.0, -3.0), axis(0, 16.0), axis(1, 4.0), (0, 0, 1))
    gltf.mesh("wall", wall, gltf.material("render", (0.7, 0.66, 0.6)))
    crates = box((-2.2, 0.45, -0.8), (0.9, 0.9, 0.9), 0.4)
    crates.extend(box((-1.3, 0.3, 0.3), (0.6, 0.6, 0.6), -0.3))
    gltf.mesh("crates", crates, gltf.material("wood", (0.55, 0.4, 0.25)))
    gltf.mesh("ball", sphere((1.2, 0.5, 0.6), 0.5), gltf.material("blue paint", (0.1, 0.2, 0.6)))
    gltf.mesh("post", box((2.6, 1.4, -2.2), (0.12, 2.8, 0.12)), gltf.material("iron", (0.1, 0.1, 0.1)))
    texture = Texture("neon.png", 1024, 256, neon_pixel(neon_strokes()))
    sign = Mesh()  # 2.4 x 0.6 m, 2 cm before the wall, facing the yard (+z)
    sign.add_quad((-1.2, 3.2, -2.98), axis(0, 2.4), axis(1, -0.6), (0, 0, 1))  # from its top-left corner
    gltf.mesh("neon sign", sign, gltf.emissive_material("neon", texture, 30.0))
    gltf.punctual_light("sun", "directional", 1500.0, (1.0, 0.92, 0.8), direction=(0.55, -0.45, -0.7))
    gltf.punctual_light("lamp", "point", 6.0 * LUMENS_PER_WATT, (1.0, 0.8, 0.55), position=(2.6, 2.9, -2.0))
    gltf.punctual_light("porch", "spot", 15.0 * LUMENS_PER_WATT, (0.8, 0.9, 1.0), position=(-3.5, 3.4, -2.4),
                        direction=(0.2, -1.0, 0.25), cones=(0.3, 0.6))
    gltf.camera((0.5, 1.8, 7.5), (-0.2, 1.1, -1.5), 0.7)
    return gltf, "Courtyard", 16
