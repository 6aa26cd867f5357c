"""The room of the material scenes that show one surface feature each against a light: 6 x 6 m,
4.5 m high, plaster, lit by a textured panel on its back wall."""
from .mesh import Mesh, room
from .vec import axis


def back_lit_room(gltf, light_name, left, top, width, height, texture, strength):
    """The room and its light: a `width` x `height` m panel 2 cm before the back wall, its top-left
    corner at (`left`, `top`), facing the room, emitting `texture` at `strength` over a near-black
    base colour."""
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.65,) * 3))
    light = Mesh()
    light.add_quad((left, top, -2.98), axis(0, width), axis(1, -height), (0, 0, 1))
    material = gltf.material(light_name, (0.02, 0.02, 0.02))
    gltf.set_emission(material, gltf.texture_info(texture), strength)
    gltf.mesh(light_name, light, material)
