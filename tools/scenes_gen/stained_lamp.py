"""Scene stained-lamp (materials): coverage that cuts emitters and shadows, glTF's alphaMode MASK.
A leaded window of coloured light whose missing panes are cut out by the base colour's alpha,
and a lamp whose perforated bottom (MASK, its own cutoff) throws a pattern of spots."""
import math
import random

from .gltf import MATERIALS_GENERATOR, REPEAT, Gltf
from .mesh import Mesh, box, room_with_window, sphere
from .texture import Texture
from .vec import axis, mul

WINDOW = (-1.0, 0.8, 1.0, 2.3)  # the hole in the back wall: left, bottom, right, top (m)
GLASS = [(0.9, 0.15, 0.1), (0.15, 0.35, 1.0), (1.0, 0.75, 0.1), (0.2, 0.8, 0.3), (0.6, 0.2, 0.9)]


def leaded_glass(width, height, pitch=32, lead=3.0, frame=6.0, missing=0.2, seed=21):
    """The window's texels as (base colour with alpha, emission): diamond panes of coloured
    glass between dark lead cames, in a lead frame. Each pane is opaque glass (alpha 0.55 to 1:
    kept whole by a cutoff of 0.5) or, about one in five, missing (alpha 0 to 0.45: cut out), and a
    missing pane's emission is bright white, so that a renderer that ignored the cut would show
    it lit. Returns base(x, y) -> RGBA and emission(x, y) -> RGB."""
    rng = random.Random(seed)
    panes = {}
    for a in range(0, (width + height) // pitch + 2):
        for b in range(-height // pitch - 1, width // pitch + 2):
            panes[a, b] = (rng.random() < missing, rng.choice(GLASS), rng.uniform(0.55, 1.0), rng.uniform(0.0, 0.45))

    def texel(x, y):
        """(kind, pane) of texel (x, y): "lead", or a pane's entry."""
        x, y = x + 0.5, y + 0.5
        p, q = (x + y) / pitch, (x - y) / pitch
        to_lead = min(p % 1, 1 - p % 1, q % 1, 1 - q % 1) * pitch / math.sqrt(2)
        if to_lead < lead / 2 or min(x, y, width - x, height - y) < frame:
            return None
        return panes[math.floor(p), math.floor(q)]

    def base(x, y):
        pane = texel(x, y)
        if pane is None:
            return (0.05, 0.05, 0.05, 1.0)
        gone, colour, kept_alpha, cut_alpha = pane
        return mul(colour, 0.3) + (cut_alpha if gone else kept_alpha,)

    def emission(x, y):
        pane = texel(x, y)
        if pane is None:
            return (0.0, 0.0, 0.0)
        gone, colour, _, _ = pane
        return (1.0, 1.0, 1.0) if gone else colour
    return base, emission


def grille_cell(size, cutoff=0.3, hole=11.0):
    """One cell of the lamp's perforated plate, RGBA: dark bronze whose alpha grows linearly from
    0 at the cell's centre through `cutoff` at `hole` texels (the hole's edge) to 0.6 in its
    corners. Cut at the cutoff, the plate is opaque with crisp holes; blended, it would be a
    see-through plate of soft blots."""
    def pixel(x, y):
        d = math.hypot(x + 0.5 - size / 2, y + 0.5 - size / 2)
        return (0.25, 0.17, 0.09, min(cutoff * d / hole, 1.0))
    return pixel


def lamp_shade(centre, size, height):
    """An open-bottomed box (four sides and a top) over the lamp: its light leaves through the
    plate beneath alone."""
    shade = box((centre[0], centre[1] + height / 2, centre[2]), (size, height, size))
    keep = [k for k in range(0, len(shade.indices), 3)  # every face but the bottom one
            if not all(shade.normals[i][1] < -0.5 for i in shade.indices[k:k + 3])]
    shade.indices = [i for k in keep for i in shade.indices[k:k + 3]]
    return shade


def stained_lamp():
    """A room lit by a leaded window (2.0 x 1.5 m, MASK with glTF's default cutoff, emission
    from its own texture) through the black night behind it, and by a point light in a lamp
    whose 1 m square bottom is a plate pierced by 8 x 8 round holes (MASK at 0.3, one cell's
    texture repeated by KHR_texture_transform): patterned light on the floor and the right wall."""
    gltf = Gltf("stained-lamp", MATERIALS_GENERATOR)
    gltf.mesh("room", room_with_window(-3.0, 3.0, 3.0, -3.0, 4.5, WINDOW), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("ball", sphere((-1.4, 0.4, -0.6), 0.4, cols=24, rows=12),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("block", box((0.9, 0.3, 0.6), (0.6, 0.6, 0.6), 0.4), gltf.material("clay", (0.6, 0.45, 0.35)))

    base, emission = leaded_glass(256, 192)
    window = Mesh()  # in the hole of the back wall, facing the room (+z)
    window.add_quad((WINDOW[0], WINDOW[3], -3.0), axis(0, WINDOW[2] - WINDOW[0]), axis(1, WINDOW[1] - WINDOW[3]),
                    (0, 0, 1))
    glass = gltf.material("stained glass", (1.0, 1.0, 1.0))
    gltf.set_alpha(glass, "MASK", texture=gltf.texture_info(Texture("stained-glass.png", 256, 192, base)))
    gltf.set_emission(glass, gltf.texture_info(Texture("stained-glass-emission.png", 256, 192, emission)), 6.0)
    gltf.mesh("window", window, glass)

    lamp = (1.5, 1.9, 0.0)  # the centre of the plate
    gltf.mesh("lamp shade", lamp_shade(lamp, 1.0, 0.8), gltf.material("bronze", (0.25, 0.17, 0.09), 0.0, 0.6, True))
    plate = Mesh()  # facing down, its UV's top-left at the far left corner
    plate.add_quad((lamp[0] - 0.5, lamp[1], lamp[2] - 0.5), axis(0, 1.0), axis(2, 1.0), (0, -1, 0))
    perforated = gltf.material("perforated bronze", (1.0, 1.0, 1.0), 0.0, 0.6, True)
    cell = gltf.texture_info(Texture("grille-cell.png", 32, 32, grille_cell(32)), REPEAT,
                             transform={"scale": [8.0, 8.0]})
    gltf.set_alpha(perforated, "MASK", texture=cell, cutoff=0.3)
    gltf.mesh("lamp plate", plate, perforated)
    gltf.punctual_light("lamp", "point", 12.0 * 683, (1.0, 0.85, 0.65), position=(lamp[0], 2.5, lamp[2]),
                        required=False)
    gltf.camera((-0.4, 1.7, 4.2), (0.4, 1.1, -1.5), 0.95)
    return gltf, "Stained lamp", 16

