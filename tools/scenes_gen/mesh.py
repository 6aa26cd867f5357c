"""Triangle meshes in world space, and the shapes the scenes are built from."""
import math

from .vec import add, axis, cross, dot, mul, normalize, rotate_y, sub


class Mesh:
    """One glTF primitive's worth of triangles: positions, unit normals, UVs, indices; and, where
    a scene gives them, a second UV set (TEXCOORD_1) and tangents (TANGENT)."""

    def __init__(self):
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []
        self.uvs1, self.tangents = [], []

    def add_grid(self, point, normal, cols, rows, uv=(0.0, 0.0, 1.0, 1.0), uv1=None):
        """A patch of cols x rows quads of point(s, t), s and t in [0, 1], with UV (s, t) mapped
        onto the rectangle uv = (u0, v0, u1, v1) of the texture (all of it by default), and onto
        `uv1` in TEXCOORD_1 if given (then every patch of the mesh must give one).

        The normals decide which side is the front: each triangle is wound counter-clockwise as
        seen from the side its normals point to (glTF's front face), whatever the parametrization.
        Triangles that collapse (at a sphere's poles, a disk's centre) are left out.
        """
        base = len(self.positions)
        for j in range(rows + 1):
            for i in range(cols + 1):
                s, t = i / cols, j / rows
                self.positions.append(point(s, t))
                self.normals.append(normalize(normal(s, t)))
                self.uvs.append((uv[0] + s * (uv[2] - uv[0]), uv[1] + t * (uv[3] - uv[1])))
                if uv1 is not None:
                    self.uvs1.append((uv1[0] + s * (uv1[2] - uv1[0]), uv1[1] + t * (uv1[3] - uv1[1])))
        for j in range(rows):
            for i in range(cols):
                a = base + j * (cols + 1) + i
                b, c, d = a + 1, a + cols + 1, a + cols + 2
                self._add_triangle(a, c, d)
                self._add_triangle(a, d, b)

    def _add_triangle(self, a, b, c):
        p = self.positions
        face = cross(sub(p[b], p[a]), sub(p[c], p[a]))
        if dot(face, face) < 1e-16:
            return  # degenerate: no area to shade or sample
        if dot(face, add(add(self.normals[a], self.normals[b]), self.normals[c])) < 0:
            b, c = c, b  # wind it counter-clockwise around its normals
        self.indices += [a, b, c]

    def add_quad(self, corner, edge_s, edge_t, normal, cols=1, rows=1, uv=(0.0, 0.0, 1.0, 1.0), uv1=None):
        """A flat parallelogram corner + s edge_s + t edge_t facing `normal`; UV (u0, v0) at
        `corner`, which is the image's top-left as seen from the front when edge_s points right
        and edge_t down."""
        self.add_grid(lambda s, t: add(add(corner, mul(edge_s, s)), mul(edge_t, t)),
                      lambda s, t: normal, cols, rows, uv, uv1)

    def extend(self, other):
        """Appends another mesh's triangles."""
        base = len(self.positions)
        self.positions += other.positions
        self.normals += other.normals
        self.uvs += other.uvs
        self.uvs1 += other.uvs1
        self.tangents += other.tangents
        self.indices += [base + i for i in other.indices]

    def add_tangents(self):
        """TANGENT for every vertex, from the UVs: xyz along dP/du made square to the normal,
        w the handedness, +1 where cross(normal, xyz) points to decreasing v (up the image, glTF's
        UV origin being its top-left) and -1 where the UVs are mirrored. The frame MikkTSpace
        gives on flat patches with Blender's flipped V, which is what glTF's exporters write."""
        du_sum = [(0.0, 0.0, 0.0)] * len(self.positions)
        dv_sum = list(du_sum)
        for k in range(0, len(self.indices), 3):
            a, b, c = self.indices[k:k + 3]
            e1, e2 = sub(self.positions[b], self.positions[a]), sub(self.positions[c], self.positions[a])
            (u1, v1), (u2, v2) = sub(self.uvs[b], self.uvs[a]), sub(self.uvs[c], self.uvs[a])
            r = 1.0 / (u1 * v2 - u2 * v1)
            dpdu, dpdv = mul(sub(mul(e1, v2), mul(e2, v1)), r), mul(sub(mul(e2, u1), mul(e1, u2)), r)
            for i in (a, b, c):
                du_sum[i], dv_sum[i] = add(du_sum[i], dpdu), add(dv_sum[i], dpdv)
        self.tangents = []
        for n, dpdu, dpdv in zip(self.normals, du_sum, dv_sum):
            t = normalize(sub(dpdu, mul(n, dot(n, dpdu))))
            self.tangents.append(t + (1.0 if dot(cross(n, t), dpdv) < 0 else -1.0,))


def room(x0, x1, height, z0, z1):
    """Floor, ceiling, back wall (at z0) and side walls facing inwards; open at z1, behind the
    camera, so that every view from inside meets a surface."""
    mesh = Mesh()
    width, depth = axis(0, x1 - x0), axis(2, z1 - z0)
    down = axis(1, -height)
    mesh.add_quad((x0, 0, z0), width, depth, (0, 1, 0))
    mesh.add_quad((x0, height, z0), width, depth, (0, -1, 0))
    mesh.add_quad((x0, height, z0), width, down, (0, 0, 1))
    mesh.add_quad((x0, height, z1), mul(depth, -1), down, (1, 0, 0))
    mesh.add_quad((x1, height, z0), depth, down, (-1, 0, 0))
    return mesh


def wall_with_opening(x0, x1, height, z, opening):
    """A wall at z from x0 to x1, facing +z, with a rectangular hole `opening` = (left, bottom,
    right, top): four quads around it, meeting the hole's edges exactly. What hangs in the hole
    has nothing but the black sky behind it."""
    left, bottom, right, top = opening
    mesh = Mesh()
    for a, b, c, d in ((x0, left, 0.0, height), (right, x1, 0.0, height),
                       (left, right, 0.0, bottom), (left, right, top, height)):
        mesh.add_quad((a, d, z), axis(0, b - a), axis(1, c - d), (0, 0, 1))
    return mesh


def room_with_window(x0, x1, height, z0, z1, opening):
    """room()'s floor, ceiling and side walls, and a back wall (at z0) with the hole `opening`
    (left, bottom, right, top) through to the black sky."""
    mesh = Mesh()
    width, depth = axis(0, x1 - x0), axis(2, z1 - z0)
    down = axis(1, -height)
    mesh.add_quad((x0, 0, z0), width, depth, (0, 1, 0))
    mesh.add_quad((x0, height, z0), width, depth, (0, -1, 0))
    mesh.add_quad((x0, height, z1), mul(depth, -1), down, (1, 0, 0))
    mesh.add_quad((x1, height, z0), depth, down, (-1, 0, 0))
    mesh.extend(wall_with_opening(x0, x1, height, z0, opening))
    return mesh


def box(center, size, yaw=0.0):
    """A box of `size` standing at `center`, turned by `yaw` about +y; flat-shaded, 12 triangles."""
    mesh = Mesh()
    for k in range(3):
        u, v = [axis(i, size[i]) for i in range(3) if i != k]
        for sign in (-1, 1):
            n = axis(k, sign)
            corner = add(mul(n, size[k] / 2), mul(add(u, v), -0.5))  # relative to the centre
            mesh.add_quad(add(center, rotate_y(corner, yaw)), rotate_y(u, yaw), rotate_y(v, yaw),
                          rotate_y(n, yaw))
    return mesh


def sphere_direction(s, t):
    """The unit direction of UV (s, t) on sphere(): s around +y from +z, t from the north pole."""
    theta, phi = math.pi * t, 2 * math.pi * s
    return (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))


def sphere(center, radius, cols=12, rows=8):
    """A UV sphere, smooth-shaded, low-poly by default; UV (s, t) as sphere_direction()."""
    mesh = Mesh()
    mesh.add_grid(lambda s, t: add(center, mul(sphere_direction(s, t), radius)), sphere_direction,
                  cols, rows)
    return mesh


def cylinder(base, radius, height, segments=16):
    """An upright closed cylinder: smooth side, flat caps."""
    def ring(s):
        return (math.sin(2 * math.pi * s), 0.0, math.cos(2 * math.pi * s))

    mesh = Mesh()
    mesh.add_grid(lambda s, t: add(base, add(mul(ring(s), radius), (0, height * (1 - t), 0))),
                  lambda s, t: ring(s), segments, 1)
    for y, n in ((height, (0, 1, 0)), (0.0, (0, -1, 0))):  # t runs from the centre to the rim
        mesh.add_grid(lambda s, t, y=y: add(base, add(mul(ring(s), radius * t), (0, y, 0))),
                      lambda s, t, n=n: n, segments, 1)
    return mesh


def frustum(base, bottom_radius, top_radius, height, segments=24, top=True):
    """An upright truncated cone, open at the bottom (a lamp shade): its smooth side facing out,
    and a flat top facing up unless not `top`. One surface, no thickness: a thin shade."""
    def ring(s):
        return (math.sin(2 * math.pi * s), 0.0, math.cos(2 * math.pi * s))

    slope = (bottom_radius - top_radius) / height  # the side's normal leans up by this much
    mesh = Mesh()
    mesh.add_grid(lambda s, t: add(base, add(mul(ring(s), top_radius + (bottom_radius - top_radius) * t),
                                             (0, height * (1 - t), 0))),
                  lambda s, t: add(ring(s), (0, slope, 0)), segments, 1)
    if top:
        mesh.add_grid(lambda s, t: add(base, add(mul(ring(s), top_radius * t), (0, height, 0))),
                      lambda s, t: (0, 1, 0), segments, 1)
    return mesh


def ellipsoid(center, radii, cols=24, rows=12):
    """A sphere() stretched along the axes by `radii`, smooth-shaded (a cushion, a pebble)."""
    mesh = Mesh()
    mesh.add_grid(lambda s, t: add(center, tuple(r * c for r, c in zip(radii, sphere_direction(s, t)))),
                  lambda s, t: tuple(c / r for r, c in zip(radii, sphere_direction(s, t))), cols, rows)
    return mesh
