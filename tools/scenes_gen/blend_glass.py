"""Scene blend-glass (materials): partial coverage, glTF's alphaMode BLEND. A tinted pane of
alpha 0.5 under a ceiling light passes half of its light, and a window of eight emitting cells
fades from 1/8 to full coverage, read from a second UV set."""
from .gltf import MATERIALS_GENERATOR, Gltf
from .mesh import Mesh, box, room_with_window
from .texture import Texture
from .vec import axis, smoothstep

WINDOW = (-2.6, 1.2, -0.2, 1.8)  # the hole in the back wall: left, bottom, right, top (m)
CELLS = [(1.0, 0.3, 0.2), (1.0, 0.55, 0.15), (0.95, 0.85, 0.2), (0.4, 0.95, 0.3),
         (0.2, 0.9, 0.8), (0.25, 0.55, 1.0), (0.55, 0.35, 1.0), (0.95, 0.35, 0.85)]


def light_panel(size):
    """The ceiling light's map: white, falling off a little towards the rim."""
    def pixel(x, y):
        r = max(abs(x + 0.5 - size / 2), abs(y + 0.5 - size / 2)) / (size / 2)
        return (1.0 - 0.4 * smoothstep(0.6, 1.0, r),) * 3
    return pixel


def fading_cells(width, height, border=2):
    """The fading window's two maps, eight cells across between dark mullions: emission(x, y),
    each cell its own hue, read through TEXCOORD_0; and coverage(x, y), RGBA, dark with cell k
    (from the left as seen) of alpha (k + 1) / 8, stored right to left: TEXCOORD_1 runs its u
    from 1 to 0 across the window, so a renderer that read it at TEXCOORD_0 shows the fade
    reversed."""
    pitch = width // len(CELLS)

    def mullion(x, y):
        return x % pitch < border or x % pitch >= pitch - border or y < border or y >= height - border

    def emission(x, y):
        return (0.0, 0.0, 0.0) if mullion(x, y) else CELLS[x // pitch]

    def coverage(x, y):
        k = len(CELLS) - 1 - x // pitch  # the cell of the window this texel lands on
        return (0.03, 0.03, 0.03, 1.0 if mullion(x, y) else (k + 1) / len(CELLS))
    return emission, coverage


def blend_glass():
    """A room lit by a 1.2 m square ceiling light, with a 1.4 m square pane of blue glass
    (BLEND, baseColorFactor alpha 0.5, two-sided) 0.9 m above the floor under it, and a 2.4 x
    0.6 m window of eight coloured cells in the back wall whose coverage steps from 1/8 to 8/8
    (BLEND, baseColorTexture alpha at TEXCOORD_1): its emission and its light fade with it."""
    gltf = Gltf("blend-glass", MATERIALS_GENERATOR)
    gltf.mesh("room", room_with_window(-3.0, 3.0, 3.0, -3.0, 4.5, WINDOW), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("block", box((-1.4, 0.25, -0.2), (0.5, 0.5, 0.5), 0.5), gltf.material("clay", (0.6, 0.45, 0.35)))

    light = Mesh()  # 2 cm under the ceiling, facing down
    light.add_quad((0.2, 2.98, -1.4), axis(0, 1.2), axis(2, 1.2), (0, -1, 0))
    panel = gltf.material("light panel", (0.02, 0.02, 0.02))
    gltf.set_emission(panel, gltf.texture_info(Texture("light-panel.png", 32, 32, light_panel(32))), 5.0)
    gltf.mesh("ceiling light", light, panel)

    pane = Mesh()  # horizontal, under the light
    pane.add_quad((0.1, 0.9, -1.5), axis(0, 1.4), axis(2, 1.4), (0, 1, 0))
    glass = gltf.material("blue glass", (0.25, 0.55, 0.9), 0.0, 0.5, True)
    gltf.set_alpha(glass, "BLEND", alpha=0.5)
    gltf.mesh("glass pane", pane, glass)

    emission, coverage = fading_cells(256, 64)
    window = Mesh()  # in the hole of the back wall, facing the room (+z); TEXCOORD_1 mirrored in u
    window.add_quad((WINDOW[0], WINDOW[3], -3.0), axis(0, WINDOW[2] - WINDOW[0]), axis(1, WINDOW[1] - WINDOW[3]),
                    (0, 0, 1), uv1=(1.0, 0.0, 0.0, 1.0))
    cells = gltf.material("fading cells", (1.0, 1.0, 1.0))
    gltf.set_alpha(cells, "BLEND", texture=gltf.texture_info(Texture("fade-coverage.png", 256, 64, coverage),
                                                             tex_coord=1))
    gltf.set_emission(cells, gltf.texture_info(Texture("fade-emission.png", 256, 64, emission)), 8.0)
    gltf.mesh("fading window", window, cells)
    gltf.camera((-0.6, 2.4, 4.2), (0.2, 0.9, -1.2), 0.95)
    return gltf, "Blend glass", 16
