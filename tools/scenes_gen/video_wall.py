"""Scene video-wall: an LED wall playing a clip, and a blinking "on air" sign."""
import math

from .gltf import Gltf
from .mesh import Mesh, box, cylinder, room, sphere
from .neon import NEON_COLOURS, neon_pixel, word_strokes
from .texture import Texture
from .vec import add, axis


CLIP_FRAMES, CLIP_WIDTH, CLIP_HEIGHT = 48, 320, 180  # two seconds at 24 frames per second


def clip_frame(k, banner, banner_width):
    """Frame k of the wall's clip: on a dark ground, a banner of neon words scrolling right to
    left, two bright discs on Lissajous paths and a bar sweeping down: high contrast, moving."""
    t = k / CLIP_FRAMES
    shift = int(t * banner_width)
    discs = [((0.5 + 0.4 * math.sin(2 * math.pi * (t + p)), 0.3 + 0.2 * math.sin(4 * math.pi * (t + p) + 1.0)),
              0.12, colour) for p, colour in ((0.0, (1.0, 0.3, 0.1)), (0.3, (0.2, 0.6, 1.0)))]
    bar = (t * 1.3) % 1.3 - 0.15

    def pixel(x, y):
        u, v = (x + 0.5) / CLIP_WIDTH, (y + 0.5) / CLIP_HEIGHT
        rgb = (0.002, 0.002, 0.005)  # an LED wall's black is not quite black
        if abs(v - bar) < 0.03:
            rgb = (0.6, 0.6, 0.7)
        for (cu, cv), r, colour in discs:
            if math.hypot((u - cu) * CLIP_WIDTH / CLIP_HEIGHT, v - cv) < r:
                rgb = colour
        if 0.62 <= v < 0.92:  # the banner's band
            lit = banner[int((v - 0.62) / 0.30 * len(banner))][(x + shift) % banner_width]
            rgb = add(rgb, lit)
        return tuple(min(c, 1.0) for c in rgb)
    return pixel


def video_wall():
    """An LED wall playing a two-second clip lights a room with a glossy floor, beside a small
    "on air" sign that blinks: emission that changes every frame."""
    gltf = Gltf("video-wall")
    gltf.mesh("room", room(-3.5, 3.5, 3.2, -2.5, 5.0), gltf.material("plaster", (0.6,) * 3))
    gltf.mesh("floor", box((0.0, -0.01, 1.0), (7.0, 0.02, 7.0)),
              gltf.material("polished concrete", (0.35, 0.35, 0.36), 0.0, 0.15))
    gltf.mesh("ball", sphere((-1.3, 0.45, 0.8), 0.45), gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("block", box((1.1, 0.35, 0.3), (0.7, 0.7, 0.7), 0.5), gltf.material("clay", (0.6, 0.45, 0.35)))
    gltf.mesh("post", cylinder((0.2, 0.0, 1.6), 0.18, 1.2), gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.35))
    # The banner's words, painted once and scrolled: 3 words of neon strokes, 960 x 54 texels.
    banner_width, banner_height = 960, 54
    words = [neon_pixel(word_strokes(word, 320, banner_height, NEON_COLOURS[i]))
             for i, word in enumerate(["LIVE", "NEWS", "TRS"])]
    banner = [[words[x // 320](x % 320, y) for x in range(banner_width)] for y in range(banner_height)]
    frames = [Texture(f"frame {k}", CLIP_WIDTH, CLIP_HEIGHT, clip_frame(k, banner, banner_width))
              for k in range(CLIP_FRAMES)]
    clip = Texture("video-wall.png", CLIP_WIDTH, CLIP_HEIGHT, clip_frame(0, banner, banner_width), frames,
                   "clip/wall.%04d.png")
    wall = Mesh()  # 4.8 x 2.7 m on the back wall, 2 triangles, facing the room (+z)
    wall.add_quad((-2.4, 2.95, -2.49), axis(0, 4.8), axis(1, -2.7), (0, 0, 1))
    gltf.mesh("LED wall", wall, gltf.emissive_material("LED wall", clip, 8.0))
    sign_texture = Texture("on-air.png", 128, 32, neon_pixel(word_strokes("ONAIR", 128, 32, (1.0, 0.1, 0.1))))
    sign = Mesh()  # on the right-hand wall, facing the room (-x)
    sign.add_quad((3.49, 2.9, -1.6), axis(2, 1.2), axis(1, -0.3), (-1, 0, 0))
    on_air = gltf.emissive_material("on air", sign_texture, 40.0)
    gltf.mesh("on air sign", sign, on_air)
    gltf.animate_emissive_strength(on_air, [0.0, 0.5, 1.0, 1.5], [40.0, 0.0, 40.0, 0.0])
    gltf.camera((2.4, 1.6, 4.6), (-0.5, 1.2, -1.5), 0.85)
    return gltf, "Video wall", 16
