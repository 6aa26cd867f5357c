"""Triangle meshes in world space, and the shapes the scenes are built from."""
import math

from .vec import add, axis, cross, dot, mul, normalize, rotate_y, sub


class Mesh:
    """One glTF primitive's worth of triangles: positions, unit normals, UVs, indices."""

    def __init__(self):
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []

    def add_grid(self, point, normal, cols, rows, uv=(0.0, 0.0, 1.0, 1.0)):
        """A patch of cols x rows quads of point(s, t), s and t in [0, 1], with UV (s, t) mapped
        onto the rectangle uv = (u0, v0, u1, v1) of the texture (all of it by default).

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

    def add_quad(self, corner, edge_s, edge_t, normal, cols=1, rows=1, uv=(0.0, 0.0, 1.0, 1.0)):
        """A flat parallelogram corner + s edge_s + t edge_t facing `normal`; UV (u0, v0) at
        `corner`, which is the image's top-left as seen from the front when edge_s points right
        and edge_t down."""
        self.add_grid(lambda s, t: add(add(corner, mul(edge_s, s)), mul(edge_t, t)),
                      lambda s, t: normal, cols, rows, uv)

    def extend(self, other):
        """Appends another mesh's triangles."""
        base = len(self.positions)
        self.positions += other.positions
        self.normals += other.normals
        self.uvs += other.uvs
        self.indices += [base + i for i in other.indices]


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
