"""Scene night-street: a street at night lit by 60-odd textured emitters."""
import math
import random

from .gltf import Gltf
from .mesh import Mesh, box, cylinder
from .neon import NEON_COLOURS, neon_pixel, word_strokes
from .texture import Atlas
from .vec import axis, mix, mul


SIGN_WORDS = ["BAR", "HOTEL", "PIZZA", "OPEN", "CAFE", "NOODLES", "CLUB", "BOOKS", "RAMEN", "DINER",
              "JAZZ", "TATTOO", "SUSHI", "KEBAB", "RADIO", "WINE"]


def window_pixel(rng, width, height):
    """A lit window seen from the street: a warm or cool interior falling off from a lamp, a few
    dark silhouettes, mullions, and sometimes a half-drawn curtain."""
    warm = rng.random() < 0.7
    glow = (1.0, 0.7, 0.4) if warm else (0.6, 0.8, 1.0)
    lamp_x, lamp_y = rng.uniform(0.2, 0.8), rng.uniform(0.1, 0.4)
    panes = rng.choice([1, 2, 3])
    curtain = rng.random() < 0.4
    shapes = [(rng.uniform(0.1, 0.9), rng.uniform(0.5, 0.9), rng.uniform(0.08, 0.2)) for _ in range(rng.randint(0, 3))]

    def pixel(x, y):
        u, v = (x + 0.5) / width, (y + 0.5) / height
        if min(u, v, 1 - u, 1 - v) < 0.04 or abs((u * panes) % 1.0) < 0.03 * panes:
            return (0.0, 0.0, 0.0)  # frame and mullions
        level = 0.25 + 0.75 * math.exp(-((u - lamp_x) ** 2 + (v - lamp_y) ** 2) / 0.08)
        if curtain and u < 0.35:
            level *= 0.3
        if any(math.hypot(u - cx, (v - cy) * 0.6) < r for cx, cy, r in shapes):
            level *= 0.08
        return mul(glow, level)
    return pixel


def lamp_pixel(size):
    """A street lamp's diffuser seen from below: bright in the middle, falling to zero at the rim."""
    def pixel(x, y):
        r = math.hypot((x + 0.5) / size - 0.5, (y + 0.5) / size - 0.5) * 2
        return mul((1.0, 0.82, 0.55), max(0.0, 1.0 - r * r))
    return pixel


def screen_pixel(rng, width, height, bars):
    """A video screen's frame: a dark ground with bright moving-image shapes: discs, bars and a
    band of large letters' strokes, high contrast."""
    discs = [(rng.uniform(0.1, 0.9), rng.uniform(0.15, 0.85), rng.uniform(0.04, 0.12), rng.choice(NEON_COLOURS))
             for _ in range(6)]
    stripes = [(rng.uniform(0.0, 0.8), rng.uniform(0.05, 0.2), rng.choice(NEON_COLOURS)) for _ in range(bars)]

    def pixel(x, y):
        u, v = (x + 0.5) / width, (y + 0.5) / height
        rgb = mix((0.02, 0.02, 0.06), (0.05, 0.02, 0.1), v)
        for cu, cv, r, colour in discs:
            if math.hypot((u - cu) * width / height, v - cv) < r:
                rgb = colour
        for start, thickness, colour in stripes:
            if start < v < start + thickness and (u * 7) % 1.0 < 0.8:
                rgb = mul(colour, 0.8)
        return rgb
    return pixel


def facade(x, z0, z1, height, facing):
    """A street facade at x from z0 to z1 (z0 > z1), facing +x or -x, with pilasters every 5 m and
    a kerb-high plinth: shadows and edges for the signs to light."""
    mesh = Mesh()
    length = z0 - z1
    wall = Mesh()
    corner = (x, height, z1) if facing > 0 else (x, height, z0)
    edge = axis(2, length) if facing > 0 else axis(2, -length)
    wall.add_quad(corner, edge, axis(1, -height), (facing, 0, 0))
    mesh.extend(wall)
    z = z0 - 2.5
    while z > z1:
        mesh.extend(box((x + facing * 0.15, height / 2, z), (0.3, height, 0.4)))
        z -= 5.0
    return mesh


STREET_END = -86.0  # the street runs from z = 5 (behind the camera) to here


def street_emitters(rng):
    """The street's emitters, by atlas: {atlas name: [(mesh, double_sided)]}, and the atlases."""
    neon = Atlas("street-neon.png", 1024, 1024)      # 16 words of 512 x 128
    windows = Atlas("street-windows.png", 512, 512)  # 16 windows of 128 x 128
    screens = Atlas("street-screens.png", 1024, 512)  # screen, billboard, blades, lamp
    regions = {"word": [], "window": []}
    for k, word in enumerate(SIGN_WORDS):
        x0, y0 = (k % 2) * 512, (k // 2) * 128
        colour = NEON_COLOURS[k % len(NEON_COLOURS)]
        regions["word"].append(neon.paint(x0, y0, 512, 128, neon_pixel(word_strokes(word, 512, 128, colour))))
    for k in range(16):
        regions["window"].append(windows.paint((k % 4) * 128, (k // 4) * 128, 128, 128, window_pixel(rng, 128, 128)))
    screen_uv = screens.paint(0, 0, 512, 288, screen_pixel(rng, 512, 288, 3))
    billboard_uv = screens.paint(512, 0, 512, 256, screen_pixel(rng, 512, 256, 5))
    blade_uv = [screens.paint(512 + 64 * k, 256, 64, 192,
                              neon_pixel(word_strokes(w, 64, 192, NEON_COLOURS[k % 7])))
                for k, w in enumerate(["BAR", "INN", "TAXI", "POOL", "CAFE", "OPEN"][:6])]
    lamp_uv = screens.paint(0, 320, 64, 64, lamp_pixel(64))

    signs, lit_windows, lamps, blades, big = Mesh(), Mesh(), Mesh(), [], Mesh()
    word = 0
    for side in (-1, 1):
        x = side * 6.0
        for k in range(17):
            z = -5.0 * k - 0.3
            uv = regions["word"][word % 16]
            word += 1
            if (k, side) in ((3, -1), (6, 1), (12, -1)):
                # Backlit letters mounted the wrong way round: they face the wall they hang on.
                signs.add_quad((x - side * 0.25, 3.95, z - 3.5 * (side < 0)), axis(2, 3.5 * side * -1 if side < 0 else 3.5),
                               axis(1, -0.7), (side, 0, 0), uv=uv)
                continue
            front = (-side, 0, 0)
            corner = (x - side * 0.05, 3.95, z - (0 if side < 0 else 3.5))
            edge = axis(2, -3.5) if side < 0 else axis(2, 3.5)
            signs.add_quad(corner, edge, axis(1, -0.7), front, uv=uv)
            if rng.random() < 0.6:  # a lit shop window under it
                lit_windows.add_quad((x - side * 0.04, 2.6, z - (0.4 if side < 0 else 3.1)),
                                     axis(2, -2.7) if side < 0 else axis(2, 2.7), axis(1, -2.0), front,
                                     uv=regions["window"][rng.randrange(16)])
            for floor in (6.5, 9.5):  # lit flats upstairs
                if rng.random() < 0.45:
                    wz = z - rng.uniform(0.5, 3.0)
                    lit_windows.add_quad((x - side * 0.04, floor + 1.4, wz + (0 if side < 0 else -1.0)),
                                         axis(2, -1.0) if side < 0 else axis(2, 1.0), axis(1, -1.4), front,
                                         uv=regions["window"][rng.randrange(16)])
        for k in range(9):  # street lamps over the kerbs, facing down
            z = -10.0 * k - 4.0
            lamps.add_quad((x * 0.68 - 0.25, 6.0, z - 0.15), axis(0, 0.5), axis(2, 0.3), (0, -1, 0), uv=lamp_uv)
    for k in range(12):  # blade signs sticking out of the facades, along the street
        side = -1 if k % 2 else 1
        z = -7.0 * k - 2.0
        x = side * (6.0 - 0.2)
        mesh = Mesh()
        inner = (x - side * 0.7, 5.0, z)
        if k % 4 < 2:  # two-sided, seen from both ways along the street
            mesh.add_quad(inner, axis(0, side * 0.6), axis(1, -1.8), (0, 0, 1), uv=blade_uv[k % 6])
            blades.append((mesh, True))
        else:  # one-sided, facing away from the camera, down the street
            mesh.add_quad((inner[0] + side * 0.6, 5.0, z), axis(0, -side * 0.6), axis(1, -1.8), (0, 0, -1),
                          uv=blade_uv[k % 6])
            blades.append((mesh, False))
    # A large video screen on the building closing the street, and billboards high on the facades.
    big.add_quad((-6.0, 10.5, STREET_END + 0.1), axis(0, 12.0), axis(1, -6.75), (0, 0, 1), cols=8, rows=4,
                 uv=screen_uv)
    big.add_quad((5.9, 12.0, -16.0), axis(2, 6.0), axis(1, -3.0), (-1, 0, 0), cols=2, rows=2, uv=billboard_uv)
    big.add_quad((-5.9, 12.0, -64.0), axis(2, -6.0), axis(1, -3.0), (1, 0, 0), cols=2, rows=2, uv=billboard_uv)
    atlases = [neon.texture(), windows.texture(), screens.texture()]
    return {"signs": signs, "windows": lit_windows, "lamps": lamps, "blades": blades, "screens": big}, atlases


def night_street():
    """A street at night lit by 60-odd textured emitters at every distance and orientation:
    neon signs, shop windows, flats upstairs, lamps, blade signs, a billboard and a video screen."""
    rng = random.Random(21)
    gltf = Gltf("night-street")
    brick = gltf.material("brick", (0.35, 0.25, 0.2), 0.0, 0.85)
    for side in (-1, 1):
        gltf.mesh(f"facade {'left' if side < 0 else 'right'}", facade(side * 6.0, 5.0, STREET_END, 12.0, -side), brick)
    end = Mesh()
    end.add_quad((-6.0, 12.0, STREET_END), axis(0, 12.0), axis(1, -12.0), (0, 0, 1))
    gltf.mesh("end of the street", end, brick)
    road, pavement = Mesh(), Mesh()
    length = 5.0 - STREET_END
    road.add_quad((-4.0, 0.0, STREET_END), axis(0, 8.0), axis(2, length), (0, 1, 0))
    for side in (-1, 1):
        x0 = -6.0 if side < 0 else 4.0
        pavement.add_quad((x0, 0.15, STREET_END), axis(0, 2.0), axis(2, length), (0, 1, 0))
        kerb = (-4.0, 0.15, STREET_END) if side < 0 else (4.0, 0.0, STREET_END)
        pavement.add_quad(kerb, axis(1, -0.15) if side < 0 else axis(1, 0.15), axis(2, length), (-side, 0, 0))
    gltf.mesh("wet road", road, gltf.material("wet asphalt", (0.08, 0.08, 0.09), 0.0, 0.12))
    gltf.mesh("pavements", pavement, gltf.material("paving", (0.4, 0.4, 0.38), 0.0, 0.8))
    props = Mesh()
    for k in range(12):
        props.extend(cylinder((-3.8 if k % 2 else 3.8, 0.0, -6.0 * k - 1.0), 0.12, 0.9, 12))
    for side in (-1, 1):
        for k in range(9):
            props.extend(cylinder((side * 4.08, 0.15, -10.0 * k - 4.0), 0.08, 5.9, 8))
    props.extend(box((-2.2, 0.6, -12.0), (1.8, 1.2, 4.2), 0.05))  # a parked van's shape
    gltf.mesh("posts and bollards", props, gltf.material("painted steel", (0.3, 0.32, 0.35), 1.0, 0.45))
    emitters, atlases = street_emitters(rng)
    neon, windows, screens = atlases
    gltf.mesh("neon signs", emitters["signs"], gltf.emissive_material("neon", neon, 60.0))
    gltf.mesh("lit windows", emitters["windows"], gltf.emissive_material("windows", windows, 4.0))
    gltf.mesh("street lamps", emitters["lamps"], gltf.emissive_material("lamps", screens, 400.0))
    for k, (mesh, double_sided) in enumerate(emitters["blades"]):
        material = gltf.emissive_material(f"blade sign {k}", screens, 60.0, double_sided)
        gltf.mesh(f"blade sign {k}", mesh, material, facing_away=not double_sided)
    gltf.mesh("screens", emitters["screens"], gltf.emissive_material("screens", screens, 16.0))
    gltf.camera((1.2, 1.7, 4.0), (-0.6, 3.0, -30.0), 0.85)
    return gltf, "Night street", 16
