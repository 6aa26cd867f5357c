"""Scene atlas-sign (materials): emission read through KHR_texture_transform, TEXCOORD_1 and a
MIRRORED_REPEAT sampler. Two signs pick their tiles out of one atlas, one of them stored turned
a quarter turn; a strip repeats a chevron mirrored, from UVs beyond [0, 1]."""
import math

from .gltf import MATERIALS_GENERATOR, MIRRORED_REPEAT, Gltf
from .mesh import Mesh, box, room, sphere
from .neon import neon_pixel, segment, word_strokes
from .texture import Atlas, Texture
from .vec import axis, smoothstep

SIGN_W, SIGN_H = 256, 64  # the turned tiles, in texels as the sign shows them
CYAN, PINK, GREEN = (0.1, 0.8, 1.0), (1.0, 0.1, 0.6), (0.2, 1.0, 0.3)


def word_and_arrow(word, colour):
    """A SIGN_W x SIGN_H sign: the word, then an arrow pointing right (which way it points tells
    a quarter turn from three quarters, and a mirror image from the sign)."""
    strokes = word_strokes(word, 170, SIGN_H, colour)
    strokes += [(segment(*a, *b), GREEN) for a, b in (((185, 32), (240, 32)), ((240, 32), (222, 16)),
                                                      ((240, 32), (222, 48)))]
    return neon_pixel(strokes)


def turned(pixel):
    """A SIGN_W x SIGN_H image stored a quarter turn round, SIGN_H wide and SIGN_W tall, as
    atlases pack tall and wide tiles: the sign's top edge along the tile's left edge, its left
    end at the bottom. KHR_texture_transform's rotation pi/2 turns it back (turned_transform)."""
    return lambda x, y: pixel(SIGN_W - 1 - y, x)


def turned_transform(u0, v0, du, dv):
    """KHR_texture_transform that shows the turned() tile at UV rectangle (u0, v0) + (du, dv) of
    the atlas upright on a quad whose UVs span [0, 1]: with rotation r = pi/2 the extension maps
    (u, v) to (sy v + ox, -sx u + oy), so the quad's u runs up the tile and its v across it."""
    return {"offset": [u0, v0 + dv], "rotation": round(math.pi / 2, 7), "scale": [dv, du]}


def glow(x, y):
    """The atlas's filler: a broad orange glow, much brighter than the signs, so that a sign
    that picked the wrong part of the atlas would light the room orange."""
    r = math.hypot((x + 0.5 - 64) / 64, (y + 0.5 - 96) / 96)
    return tuple(c * (1.0 - smoothstep(0.8, 1.0, r)) for c in (1.0, 0.5, 0.1))


def chevron(size):
    """The strip's chevron, pointing right and brightening towards its tip, on black: a mirrored
    copy points left."""
    def pixel(x, y):
        u, v = (x + 0.5) / size, abs((y + 0.5) / size - 0.5)
        inside = abs(u - 0.75 + v) < 0.16
        return tuple(c * (0.2 + 0.8 * u) for c in (0.7, 0.3, 1.0)) if inside else (0.0, 0.0, 0.0)
    return pixel


def atlas_sign():
    """A room lit by three emitters. On the back wall, a 2.4 x 0.6 m sign, TRS and an arrow,
    whose emissiveTexture is the turned tile of a 256 x 256 atlas at texCoord 1, through
    KHR_texture_transform (offset, rotation pi/2, scale); its TEXCOORD_0 would pick the tile
    beside it (OPEN, in pink). On the left wall, a 0.8 x 0.4 m EXIT sign from the atlas's top-left
    tile, scaled by the transform, whose texCoord 1 is the transform's own (its textureInfo says
    0, which would show the ends of the turned tiles). On the right wall, a 2.4 x 0.6 m strip of a chevron
    (64 x 64) with u from -1 to 3 and a MIRRORED_REPEAT sampler: left, right, left, right."""
    gltf = Gltf("atlas-sign", MATERIALS_GENERATOR)
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -3.0, 4.5), gltf.material("plaster", (0.65,) * 3))
    gltf.mesh("ball", sphere((-0.9, 0.45, -0.7), 0.45, cols=24, rows=12),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("block", box((1.0, 0.35, -1.2), (0.7, 0.7, 0.7), 0.5), gltf.material("clay", (0.6, 0.45, 0.35)))

    atlas = Atlas("atlas.png", 256, 256)
    exit_tile = atlas.paint(0, 0, 128, 64, neon_pixel(word_strokes("EXIT", 128, 64, GREEN)))
    atlas.paint(0, 64, 128, 192, glow)
    trs_tile = atlas.paint(128, 0, SIGN_H, SIGN_W, turned(word_and_arrow("TRS", CYAN)))
    atlas.paint(192, 0, SIGN_H, SIGN_W, turned(word_and_arrow("OPEN", PINK)))
    atlas = atlas.texture()

    def rectangle(tile):
        return tile[0], tile[1], tile[2] - tile[0], tile[3] - tile[1]

    sign = Mesh()  # 2 cm before the back wall, facing the room; TEXCOORD_0 one tile-width off
    sign.add_quad((-1.2, 2.5, -2.98), axis(0, 2.4), axis(1, -0.6), (0, 0, 1), uv=(0.0, 1.0, 1.0, 2.0),
                  uv1=(0.0, 0.0, 1.0, 1.0))
    trs = gltf.material("TRS sign", (0.02, 0.02, 0.02))
    gltf.set_emission(trs, gltf.texture_info(atlas, tex_coord=1, transform=turned_transform(*rectangle(trs_tile))),
                      40.0)
    gltf.mesh("TRS sign", sign, trs)

    exit_sign = Mesh()  # 2 cm off the left-hand wall, facing into the room (+x)
    exit_sign.add_quad((-2.98, 2.4, -1.2), axis(2, -0.8), axis(1, -0.4), (1, 0, 0), uv=(1.0, 0.0, 2.0, 1.0),
                       uv1=(0.0, 0.0, 1.0, 1.0))
    u0, v0, du, dv = rectangle(exit_tile)
    green = gltf.material("EXIT sign", (0.02, 0.02, 0.02))
    gltf.set_emission(green, gltf.texture_info(atlas, transform={"offset": [u0, v0], "scale": [du, dv], "texCoord": 1}),
                      30.0)
    gltf.mesh("EXIT sign", exit_sign, green)

    strip = Mesh()  # 2 cm off the right-hand wall, facing into the room (-x)
    strip.add_quad((2.98, 2.3, -2.6), axis(2, 2.4), axis(1, -0.6), (-1, 0, 0), uv=(-1.0, 0.0, 3.0, 1.0))
    violet = gltf.material("chevron strip", (0.02, 0.02, 0.02))
    gltf.set_emission(violet, gltf.texture_info(Texture("chevron.png", 64, 64, chevron(64)), MIRRORED_REPEAT), 12.0)
    gltf.mesh("chevron strip", strip, violet)
    gltf.camera((0.0, 1.6, 4.2), (0.0, 1.5, -1.5), 0.95)
    return gltf, "Atlas sign", 16
