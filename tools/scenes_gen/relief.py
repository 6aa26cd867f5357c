"""Tangent-space normal maps from height fields: stone blocks for a wall, cobbles for a floor."""
import math
import random

from .texture import Texture
from .vec import normalize


def normal_map(name, width, height, relief):
    """A tileable normal map (linear data) of the height field relief(x, y), in texels and
    periodic over the image: the normal of each texel's slope by central differences across the
    wrap-around, +x right and +y up the image (glTF's convention: green up), as (n + 1) / 2."""
    h = [[relief(x, y) for x in range(width)] for y in range(height)]

    def pixel(x, y):
        dx = (h[y][(x + 1) % width] - h[y][x - 1]) / 2
        dy = (h[(y + 1) % height][x] - h[y - 1][x]) / 2  # down the image
        n = normalize((-dx, dy, 1.0))
        return tuple((c + 1) / 2 for c in n)
    return Texture(name, width, height, pixel, data=True)


def stone_blocks(size, courses=8, per_course=2, joint=4.0, bevel=6.0, seed=3):
    """Blocks in running bond, `courses` rows of `per_course` each across a square tile of `size`
    texels: a recessed joint `joint` texels wide, edges bevelled at 45 degrees over `bevel`
    texels, and each face tilted a little its own way (seeded), so that a low sun picks them out."""
    rng = random.Random(seed)
    rise, run = size / courses, size / per_course
    tilts = [(rng.uniform(-0.06, 0.06), rng.uniform(-0.06, 0.06)) for _ in range(courses * per_course)]

    def relief(x, y):
        x, y = x + 0.5, y + 0.5
        row = int(y // rise)
        shifted = (x + (run / 2 if row % 2 else 0.0)) % size
        col = int(shifted // run)
        # Distance from the block's edge, inwards; the joint is half on each side.
        edge = min(shifted - col * run, (col + 1) * run - shifted, y - row * rise, (row + 1) * rise - y) - joint / 2
        if edge <= 0:
            return 0.0
        tx, ty = tilts[row * per_course + col]
        return min(edge, bevel) + tx * (shifted - (col + 0.5) * run) + ty * (y - (row + 0.5) * rise)
    return relief


def cobbles(size, cells=4, seed=8):
    """Round cobbles on a square tile of `size` texels, cells x cells of them, each a paraboloid
    dome whose flank meets the ground at 45 degrees, a little off its cell's centre (seeded) but
    within it, so that the tile repeats without a seam."""
    rng = random.Random(seed)
    pitch = size / cells
    radius = 0.4 * pitch
    centres = [((i + 0.5) * pitch + rng.uniform(-0.08, 0.08) * pitch,
                (j + 0.5) * pitch + rng.uniform(-0.08, 0.08) * pitch)
               for j in range(cells) for i in range(cells)]

    def relief(x, y):
        cx, cy = centres[int((y + 0.5) // pitch) * cells + int((x + 0.5) // pitch)]
        d2 = ((x + 0.5 - cx) ** 2 + (y + 0.5 - cy) ** 2) / radius ** 2
        return radius / 2 * (1 - d2) if d2 < 1 else 0.0  # slope 1 at the rim
    return relief


def slope_degrees(texture):
    """The steepest tilt of a normal map, in degrees: how much relief it carries."""
    return max(math.degrees(math.acos(2 * px[2] / 255 - 1)) for row in texture.rows for px in row)
