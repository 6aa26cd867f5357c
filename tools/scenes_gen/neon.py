"""Neon tubes painted into textures: shapes given by their distance, a stroke font, colours."""
import math

from .vec import add, mul


def segment(ax, ay, bx, by):
    """Distance to segment a-b, and its bounding box (x0, y0, x1, y1)."""
    def distance(x, y):
        dx, dy = bx - ax, by - ay
        t = min(max(((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy), 0.0), 1.0)
        return math.hypot(x - ax - t * dx, y - ay - t * dy)
    return distance, (min(ax, bx), min(ay, by), max(ax, bx), max(ay, by))


def arc(cx, cy, r, start, end):
    """Distance to the circular arc from angle `start` to `end` (degrees, y down, increasing)."""
    a0, a1 = math.radians(start), math.radians(end)

    def distance(x, y):
        if (math.atan2(y - cy, x - cx) - a0) % (2 * math.pi) <= a1 - a0:
            return abs(math.hypot(x - cx, y - cy) - r)
        return min(math.hypot(x - cx - r * math.cos(a), y - cy - r * math.sin(a))
                   for a in (a0, a1))
    return distance, (cx - r, cy - r, cx + r, cy + r)


def wave(x0, x1, y0, amplitude, period):
    """Vertical distance to a sine wave of whole periods: near enough for gentle slopes."""
    def distance(x, y):
        if x < x0 or x > x1:
            return math.hypot(min(abs(x - x0), abs(x - x1)), y - y0)
        return abs(y - y0 - amplitude * math.sin(2 * math.pi * (x - x0) / period))
    return distance, (x0, y0 - amplitude, x1, y0 + amplitude)


NEON_CORE, NEON_GLOW, NEON_REACH = 2.5, 4.0, 12.0  # texels: tube radius, halo width, cut-off


def neon_pixel(strokes):
    """Bright tubes, each in a soft halo that is exactly zero beyond NEON_REACH texels: most of
    the sign is black, as a density map that rewards sampling by texel."""
    def pixel(x, y):
        x, y = x + 0.5, y + 0.5
        rgb = (0.0, 0.0, 0.0)
        for (distance, (x0, y0, x1, y1)), color in strokes:
            if x0 - NEON_REACH < x < x1 + NEON_REACH and y0 - NEON_REACH < y < y1 + NEON_REACH:
                d = distance(x, y)
                if d < NEON_REACH:
                    halo = 0.3 * math.exp(-((d - NEON_CORE) / NEON_GLOW) ** 2)
                    rgb = add(rgb, mul(color, 1.0 if d < NEON_CORE else halo))
        return rgb
    return pixel


# A stroke font on a 2 x 4 lattice (x right, y down): each letter a few segments, as a neon sign
# bends its tubes.
STROKES = {
    "A": [(0, 4, 1, 0), (1, 0, 2, 4), (0.5, 2.5, 1.5, 2.5)], "B": [(0, 0, 0, 4), (0, 0, 1.6, 0.6), (1.6, 0.6, 0, 2), (0, 2, 2, 3), (2, 3, 0, 4)],
    "C": [(2, 0, 0, 0), (0, 0, 0, 4), (0, 4, 2, 4)], "D": [(0, 0, 0, 4), (0, 0, 2, 1), (2, 1, 2, 3), (2, 3, 0, 4)],
    "E": [(2, 0, 0, 0), (0, 0, 0, 4), (0, 4, 2, 4), (0, 2, 1.5, 2)], "F": [(2, 0, 0, 0), (0, 0, 0, 4), (0, 2, 1.5, 2)],
    "H": [(0, 0, 0, 4), (2, 0, 2, 4), (0, 2, 2, 2)], "I": [(1, 0, 1, 4), (0.3, 0, 1.7, 0), (0.3, 4, 1.7, 4)],
    "K": [(0, 0, 0, 4), (2, 0, 0, 2), (0, 2, 2, 4)], "L": [(0, 0, 0, 4), (0, 4, 2, 4)],
    "M": [(0, 4, 0, 0), (0, 0, 1, 2), (1, 2, 2, 0), (2, 0, 2, 4)], "N": [(0, 4, 0, 0), (0, 0, 2, 4), (2, 4, 2, 0)],
    "O": [(0, 0, 2, 0), (2, 0, 2, 4), (2, 4, 0, 4), (0, 4, 0, 0)], "P": [(0, 4, 0, 0), (0, 0, 2, 0), (2, 0, 2, 2), (2, 2, 0, 2)],
    "R": [(0, 4, 0, 0), (0, 0, 2, 0), (2, 0, 2, 2), (2, 2, 0, 2), (0.8, 2, 2, 4)], "S": [(2, 0, 0, 0), (0, 0, 0, 2), (0, 2, 2, 2), (2, 2, 2, 4), (2, 4, 0, 4)],
    "T": [(0, 0, 2, 0), (1, 0, 1, 4)], "U": [(0, 0, 0, 4), (0, 4, 2, 4), (2, 4, 2, 0)],
    "V": [(0, 0, 1, 4), (1, 4, 2, 0)], "W": [(0, 0, 0.5, 4), (0.5, 4, 1, 2), (1, 2, 1.5, 4), (1.5, 4, 2, 0)],
    "Y": [(0, 0, 1, 2), (2, 0, 1, 2), (1, 2, 1, 4)], "Z": [(0, 0, 2, 0), (2, 0, 0, 4), (0, 4, 2, 4)],
    "G": [(2, 0, 0, 0), (0, 0, 0, 4), (0, 4, 2, 4), (2, 4, 2, 2), (2, 2, 1, 2)], "J": [(2, 0, 2, 4), (2, 4, 0, 4), (0, 4, 0, 3)],
    "X": [(0, 0, 2, 4), (2, 0, 0, 4)],
}
# The tube colours that lettered signs take in turn.
NEON_COLOURS = [(0.1, 0.8, 1.0), (1.0, 0.1, 0.6), (1.0, 0.85, 0.1), (0.2, 1.0, 0.3), (1.0, 0.45, 0.05),
                (0.6, 0.3, 1.0), (1.0, 0.15, 0.1)]


def word_strokes(word, width, height, colour):
    """The word centred in a width x height region, as neon_pixel's (shape, colour) pairs."""
    size = min(height * 0.62 / 4, width * 0.9 / (3 * len(word)))  # texels per lattice step
    left, top = (width - (3 * len(word) - 1) * size) / 2, (height - 4 * size) / 2
    strokes = []
    for k, letter in enumerate(word):
        x = left + 3 * k * size
        for ax, ay, bx, by in STROKES[letter]:
            strokes.append((segment(x + ax * size, top + ay * size, x + bx * size, top + by * size), colour))
    return strokes
