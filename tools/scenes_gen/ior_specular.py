"""Scene ior-specular (materials): the dielectric layer's strength and colour, KHR_materials_ior
and KHR_materials_specular. A row of dark glossy balls that differ only there, before a striped
light: from faint to strong reflections, one weakened, one tinted."""
from .back_lit_room import back_lit_room
from .gltf import MATERIALS_GENERATOR, Gltf
from .mesh import sphere
from .texture import Texture
from .vec import smoothstep

# (name, KHR_materials_ior, KHR_materials_specular) of the balls, left to right.
BALLS = [("ior 1.2", {"ior": 1.2}, None),
         ("ior 1.5", None, None),
         ("ior 2.4", {"ior": 2.4}, None),
         ("specular 0.3", None, {"specularFactor": 0.3}),
         ("specular colour", None, {"specularColorFactor": [3.0, 1.5, 0.5]})]


def light_strip(width, height):
    """The light behind the balls: white bands on black, fading towards the ends, so that every
    ball mirrors the same bright lines."""
    def pixel(x, y):
        band = (y // 4) % 2 == 0 and 2 <= y < height - 2
        fade = 1.0 - 0.5 * smoothstep(0.6, 1.0, abs((x + 0.5) / width * 2 - 1))
        return (fade,) * 3 if band else (0.0, 0.0, 0.0)
    return pixel


def ior_specular():
    """Five balls 0.6 m across in a row on the floor, near-black (base colour 0.04) and glossy
    (roughness 0.2), before a 4.4 x 0.8 m light of horizontal bands on the back wall
    (light-strip.png, 64 x 32, strength 6): ior 1.2, 1.5 (no extension: glTF's default), 2.4
    (KHR_materials_ior); specularFactor 0.3; specularColorFactor (3, 1.5, 0.5), a warm
    reflection beyond the ior's (KHR_materials_specular)."""
    gltf = Gltf("ior-specular", MATERIALS_GENERATOR)
    back_lit_room(gltf, "light strip", -2.2, 2.2, 4.4, 0.8, Texture("light-strip.png", 64, 32, light_strip(64, 32)), 6.0)
    for k, (name, ior, specular) in enumerate(BALLS):
        material = gltf.material(name, (0.04, 0.04, 0.04), 0.0, 0.2)
        if ior is not None:
            gltf.set_extension(material, "KHR_materials_ior", ior)
        if specular is not None:
            gltf.set_extension(material, "KHR_materials_specular", specular)
        gltf.mesh(name, sphere((-2.0 + 1.0 * k, 0.3, -1.2), 0.3, cols=32, rows=16), material)
    gltf.camera((0.0, 1.4, 3.2), (0.0, 0.6, -1.2), 0.8)
    return gltf, "IOR and specular", 16
