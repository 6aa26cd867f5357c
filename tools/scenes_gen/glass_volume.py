"""Scene glass-volume (materials): refraction and absorption, KHR_materials_volume with
KHR_materials_ior. A ball of blue-green glass before a wall of coloured stripes shows them
upside down and tinted; a block of amber glass holds a small glowing cube, whose light reaches the
room only through it."""
from .back_lit_room import back_lit_room
from .gltf import MATERIALS_GENERATOR, Gltf
from .mesh import box, sphere
from .texture import Texture

STRIPES = [(1.0, 0.3, 0.2), (1.0, 0.7, 0.2), (0.9, 1.0, 0.3), (0.3, 1.0, 0.5), (0.2, 0.8, 1.0),
           (0.4, 0.4, 1.0), (0.9, 0.4, 1.0), (1.0, 1.0, 1.0)]


def stripes(width, height, border=1):
    """The wall light's emission: eight vertical stripes of colour between thin dark gaps, and a
    dark band across the lower third, so that an image turned upside down shows it."""
    pitch = width // len(STRIPES)

    def pixel(x, y):
        if x % pitch < border or x % pitch >= pitch - border or height * 0.62 < y < height * 0.72:
            return (0.0, 0.0, 0.0)
        return STRIPES[x // pitch]
    return pixel


def glass(gltf, name, ior, colour, distance):
    """Smooth clear glass bounding a volume: transmission 1, `ior`, and Beer-Lambert absorption
    that leaves `colour` after `distance` metres (attenuationColor, attenuationDistance)."""
    material = gltf.material(name, (1.0, 1.0, 1.0), 0.0, 0.0)
    gltf.set_extension(material, "KHR_materials_transmission", {"transmissionFactor": 1.0})
    gltf.set_extension(material, "KHR_materials_ior", {"ior": ior})
    gltf.set_extension(material, "KHR_materials_volume", {"thicknessFactor": 0.5, "attenuationDistance": distance,
                                                           "attenuationColor": list(colour)})
    return material


def glass_volume():
    """A room lit by a 2.4 x 1.2 m light on its back wall (stripes.png, 64 x 32, strength 6).
    Before it, on a pedestal, a ball of glass 1 m across (ior 1.5; attenuationColor (0.45, 0.8,
    0.9) at 0.4 m: blue-green where thick); on the floor to the right a 0.6 m block of glass
    (ior 1.33; amber, (0.95, 0.65, 0.25) at 0.5 m) around a 0.16 m cube emitting warm white
    (strength 6). Both meshes are closed; the light of the cube leaves through the block alone."""
    gltf = Gltf("glass-volume", MATERIALS_GENERATOR)
    back_lit_room(gltf, "striped light", -1.2, 2.3, 2.4, 1.2, Texture("stripes.png", 64, 32, stripes(64, 32)), 6.0)

    gltf.mesh("pedestal", box((-0.7, 0.25, -1.6), (0.4, 0.5, 0.4)), gltf.material("stone", (0.5, 0.48, 0.45)))
    gltf.mesh("glass ball", sphere((-0.7, 1.0, -1.6), 0.5, cols=32, rows=16),
              glass(gltf, "blue-green glass", 1.5, (0.45, 0.8, 0.9), 0.4))
    gltf.mesh("glass block", box((1.1, 0.3, -1.0), (0.6, 0.6, 0.6), 0.5),
              glass(gltf, "amber glass", 1.33, (0.95, 0.65, 0.25), 0.5))
    cube = gltf.material("glowing cube", (0.02, 0.02, 0.02))
    gltf.set_emission(cube, None, 6.0, (1.0, 0.9, 0.75))
    gltf.mesh("glowing cube", box((1.1, 0.3, -1.0), (0.16, 0.16, 0.16), 0.9), cube)
    gltf.camera((0.0, 1.6, 4.2), (0.0, 1.1, -1.5), 0.95)
    return gltf, "Glass volume", 16
