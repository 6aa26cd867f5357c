"""Scene gradient-screen: a big screen showing a smooth sunset."""
import math

from .gltf import Gltf
from .mesh import Mesh, box, cylinder, room, sphere
from .texture import Texture
from .vec import add, axis, mix, mul, smoothstep


def blob(u, v, cu, cv, ru, rv):
    """A Gaussian bump centred at (cu, cv) with radii (ru, rv)."""
    return math.exp(-(((u - cu) / ru) ** 2 + ((v - cv) / rv) ** 2))


def sunset_pixel(width, height):
    """A sky from deep blue to orange over a dark sea, two soft clouds and a low sun with its
    glitter path: smooth everywhere, and no texel is zero."""
    horizon, sun_u, sun_v = 0.68, 0.55, 0.58

    def pixel(x, y):
        u, v = (x + 0.5) / width, (y + 0.5) / height
        if v >= horizon:  # the sea: dim, darker towards the viewer, lit under the sun
            rgb = mix((0.35, 0.12, 0.08), (0.03, 0.04, 0.12), smoothstep(horizon, 1.0, v))
            return add(rgb, mul((0.5, 0.25, 0.075), blob(u, v, sun_u, horizon, 0.04, 0.3)))
        sky = mix((0.05, 0.08, 0.35), (0.9, 0.35, 0.1), smoothstep(0.0, horizon, v) ** 1.5)
        cloud = 0.6 * (blob(u, v, 0.25, 0.3, 0.18, 0.05) + blob(u, v, 0.75, 0.2, 0.22, 0.04))
        rgb = mix(sky, (0.35, 0.15, 0.25), min(cloud, 1.0))
        glow = blob(u, v, sun_u, sun_v, 0.12, 0.2) + 0.3 * blob(u, v, sun_u, 0.6, 0.4, 0.35)
        disc = 1.0 - smoothstep(0.06, 0.075, math.hypot((u - sun_u) * width / height, v - sun_v))
        rgb = add(rgb, add(mul((0.5, 0.275, 0.1), glow), mul((1.0, 0.85, 0.55), disc)))
        return tuple(min(c, 1.0) for c in rgb)
    return pixel


def gradient_screen():
    """A big screen showing a smooth sunset: every texel lit, low contrast, a broad emitter."""
    gltf = Gltf("gradient-screen")
    gltf.mesh("room", room(-3.0, 3.0, 3.0, -2.5, 4.5), gltf.material("plaster", (0.7,) * 3))
    black = gltf.material("black plastic", (0.03, 0.03, 0.03), 0.0, 0.4)
    gltf.mesh("bezel", box((0.0, 1.35, -1.55), (3.3, 1.9, 0.08)), black)
    gltf.mesh("stand", box((0.0, 0.2, -1.55), (1.2, 0.4, 0.5)), black)
    gltf.mesh("ball", sphere((-0.7, 0.4, 0.2), 0.4),
              gltf.material("white plastic", (0.8, 0.8, 0.8), 0.0, 0.3))
    gltf.mesh("block", box((0.8, 0.3, 0.6), (0.6, 0.6, 0.6), -0.4),
              gltf.material("clay", (0.6, 0.45, 0.35)))
    gltf.mesh("post", cylinder((1.6, 0.0, -0.3), 0.2, 0.8),
              gltf.material("brushed steel", (0.8, 0.8, 0.82), 1.0, 0.4))
    texture = Texture("sunset.png", 512, 288, sunset_pixel(512, 288))
    screen = Mesh()  # 3.2 x 1.8 m, 1 mm in front of its bezel, facing the room (+z)
    screen.add_quad((-1.6, 2.25, -1.509), axis(0, 3.2), axis(1, -1.8), (0, 0, 1))
    gltf.mesh("screen", screen, gltf.emissive_material("screen", texture, 5.0))
    gltf.camera((2.0, 1.4, 4.0), (-0.1, 0.9, -1.0), 0.8)
    return gltf, "Gradient screen", 16
