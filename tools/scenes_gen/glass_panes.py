"""Scene glass-panes (materials): thin transmission, KHR_materials_transmission. Two light boxes on
a wall, the same emissive texture in each, light the room through their front panes: a smooth
pane of pale green glass, through which the texture shows sharp and which lets light straight
through, and a frosted one (rough), which blurs it."""
from .gltf import MATERIALS_GENERATOR, Gltf
from .mesh import Mesh, box, room, sphere
from .texture import Texture
from .vec import axis

BOX_W, BOX_H, BOX_D = 1.2, 0.9, 0.25  # a light box's opening and depth (m)
CELLS = [[(1.0, 0.55, 0.2), (1.0, 0.9, 0.6), (0.4, 0.7, 1.0), (1.0, 0.35, 0.3)],
         [(0.5, 1.0, 0.6), (1.0, 0.8, 0.3), (0.9, 0.5, 1.0), (0.6, 0.85, 1.0)],
         [(1.0, 0.95, 0.85), (0.3, 0.8, 0.9), (1.0, 0.6, 0.5), (0.7, 1.0, 0.4)]]


def light_cells(width, height, border=2):
    """The light boxes' emission: 4 x 3 cells of coloured light between dark bars, each cell
    brightest in its middle, so that blur through a rough pane shows at a glance."""
    rows, cols = len(CELLS), len(CELLS[0])
    cw, ch = width // cols, height // rows

    def pixel(x, y):
        i, j = x % cw, y % ch
        if min(i, j) < border or i >= cw - border or j >= ch - border:
            return (0.0, 0.0, 0.0)
        u, v = (i + 0.5) / cw - 0.5, (j + 0.5) / ch - 0.5
        fall = 1.0 - 0.6 * (u * u + v * v) * 2.0
        return tuple(c * fall for c in CELLS[y // ch][x // cw])
    return pixel


def light_box(gltf, name, centre, emission, pane_material, sides_material):
    """A light box on the back wall: its emitter at the wall facing the room, four opaque sides,
    and a pane over its opening, BOX_D before the wall: all its light leaves through the pane."""
    x, y, z = centre  # the middle of the emitter
    left, top = x - BOX_W / 2, y + BOX_H / 2
    panel = Mesh()
    panel.add_quad((left, top, z), axis(0, BOX_W), axis(1, -BOX_H), (0, 0, 1))
    glow = gltf.material(name + " light", (0.02, 0.02, 0.02))
    gltf.set_emission(glow, emission, 8.0)
    gltf.mesh(name + " light", panel, glow)
    sides = Mesh()
    for corner, edge, normal in (((left, top, z), axis(0, BOX_W), (0, -1, 0)),  # top, facing in
                                 ((left, top - BOX_H, z), axis(0, BOX_W), (0, 1, 0)),
                                 ((left, top, z), axis(1, -BOX_H), (1, 0, 0)),
                                 ((left + BOX_W, top, z), axis(1, -BOX_H), (-1, 0, 0))):
        sides.add_quad(corner, edge, axis(2, BOX_D), normal)
    gltf.mesh(name + " sides", sides, sides_material)
    pane = Mesh()
    pane.add_quad((left, top, z + BOX_D), axis(0, BOX_W), axis(1, -BOX_H), (0, 0, 1))
    gltf.mesh(name + " pane", pane, pane_material)


def glass_panes():
    """A room lit by two light boxes (1.2 x 0.9 m openings, 0.25 m deep) on its back wall, each
    emitting light-cells.png (64 x 48) at strength 8 through its front pane: on the left a smooth
    pane of pale green glass (transmission 1, roughness 0: straight through), on the right a
    frosted pane (transmission 1, roughness 0.5). The boxes' sides are opaque: all the light
    passes a pane."""
    gltf = Gltf("glass-panes", MATERIALS_GENERATOR)
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("ball", sphere((-0.9, 0.4, -0.6), 0.4, cols=24, rows=12),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("block", box((1.0, 0.3, -0.9), (0.6, 0.6, 0.6), 0.4), gltf.material("clay", (0.6, 0.45, 0.35)))

    cells = gltf.texture_info(Texture("light-cells.png", 64, 48, light_cells(64, 48)))
    sides = gltf.material("light box", (0.1, 0.1, 0.1))
    clear = gltf.material("clear glass", (0.8, 0.95, 0.85), 0.0, 0.0, True)
    gltf.set_extension(clear, "KHR_materials_transmission", {"transmissionFactor": 1.0})
    light_box(gltf, "clear", (-1.2, 1.9, -2.98), cells, clear, sides)
    frosted = gltf.material("frosted glass", (0.95, 0.95, 0.95), 0.0, 0.5, True)
    gltf.set_extension(frosted, "KHR_materials_transmission", {"transmissionFactor": 1.0})
    light_box(gltf, "frosted", (1.2, 1.9, -2.98), cells, frosted, sides)
    gltf.camera((0.0, 1.6, 4.2), (0.0, 1.4, -1.5), 0.95)
    return gltf, "Glass panes", 16
