"""Scene coated-panel (materials): a clear coat, KHR_materials_clearcoat. Two identical light
panels, the right one under a coat that reflects the room and dims its own light towards grazing
angles; three red balls without a coat, under a smooth and under a rough one; and a block
whose coat comes in stripes from a texture."""
import math

from .gltf import MATERIALS_GENERATOR, REPEAT, Gltf
from .mesh import Mesh, box, room, sphere
from .texture import Texture
from .vec import axis


def sunburst(width, height):
    """The panels' emission: warm rays from the middle on a dim blue ground."""
    def pixel(x, y):
        u, v = (x + 0.5) / width - 0.5, (y + 0.5) / height - 0.5
        ray = math.cos(12 * math.atan2(v, u)) > 0.3
        r = math.hypot(u, v * height / width)
        return (1.0, 0.75, 0.35) if ray and r < 0.45 else (0.15, 0.2, 0.45)
    return pixel


def coat_stripes(width, height):
    """clearcoatTexture (linear data, read in R): stripes of full coat and none."""
    def pixel(x, y):
        return (1.0, 1.0, 1.0) if (x // 8) % 2 == 0 else (0.0, 0.0, 0.0)
    return pixel


def coated_panel():
    """A room lit by two 1.2 x 0.8 m panels on its back wall emitting sunburst.png (64 x 48,
    strength 10): the left bare, the right under a clearcoat (factor 1, roughness 0). On the floor,
    three red balls (base colour (0.6, 0.05, 0.04), roughness 0.7): bare, coated smooth (roughness
    0) and coated rough (0.35); and a dark blue block whose coat (roughness 0.05) follows
    coat-stripes.png (16 x 16: stripes of 1 and 0, REPEAT four times along each face)."""
    gltf = Gltf("coated-panel", MATERIALS_GENERATOR)
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.65,) * 3))
    burst = gltf.texture_info(Texture("sunburst.png", 64, 48, sunburst(64, 48)))
    for name, x, coat in (("bare panel", -1.4, None), ("coated panel", 0.2, {"clearcoatFactor": 1.0})):
        panel = Mesh()  # 2 cm before the back wall, facing the room
        panel.add_quad((x, 2.3, -2.98), axis(0, 1.2), axis(1, -0.8), (0, 0, 1))
        material = gltf.material(name, (0.02, 0.02, 0.02), 0.0, 0.5)
        gltf.set_emission(material, burst, 10.0)
        if coat:
            gltf.set_extension(material, "KHR_materials_clearcoat", coat)
        gltf.mesh(name, panel, material)
    red = (0.6, 0.05, 0.04)
    for k, coat in enumerate((None, {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.0},
                              {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.35})):
        material = gltf.material(("bare red", "coated red", "rough-coated red")[k], red, 0.0, 0.7)
        if coat:
            gltf.set_extension(material, "KHR_materials_clearcoat", coat)
        gltf.mesh(gltf.doc["materials"][material]["name"], sphere((-2.0 + 0.9 * k, 0.35, -1.0), 0.35, 32, 16),
                  material)
    striped = gltf.material("striped coat", (0.05, 0.1, 0.3), 0.0, 0.6)
    stripes = gltf.texture_info(Texture("coat-stripes.png", 16, 16, coat_stripes(16, 16), data=True), REPEAT,
                                transform={"scale": [4.0, 4.0]})
    gltf.set_extension(striped, "KHR_materials_clearcoat", {"clearcoatFactor": 1.0, "clearcoatTexture": stripes,
                                                            "clearcoatRoughnessFactor": 0.05})
    gltf.mesh("striped block", box((1.4, 0.4, -1.0), (0.8, 0.8, 0.8), 0.6), striped)
    gltf.camera((0.0, 1.6, 4.2), (0.0, 1.2, -1.5), 0.95)
    return gltf, "Coated panel", 16
