"""Vectors as tuples, rotations as quaternions, and the float32 rounding of the glTF buffer."""
import math
import struct


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def mul(a, k):
    return tuple(x * k for x in a)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    return mul(a, 1.0 / math.sqrt(dot(a, a)))


def mix(a, b, t):
    return tuple(x + (y - x) * t for x, y in zip(a, b))


def rotate_y(v, angle):
    c, s = math.cos(angle), math.sin(angle)
    return (c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2])


def axis(k, length=1.0):
    """The k-th coordinate axis (0: x, 1: y, 2: z), scaled."""
    return tuple(length if i == k else 0.0 for i in range(3))


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3 - 2 * t)


def f32(x):
    """x as the buffer stores it, so that accessor min/max can match the bytes exactly."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def short_f32(x):
    """The shortest decimal that reads back as float32 x: readable bounds that still match."""
    x = f32(x)
    for digits in range(1, 10):
        candidate = float(f"{x:.{digits}g}")
        if f32(candidate) == x:
            return candidate
    return x


def quaternion(x_axis, y_axis, z_axis):
    """The unit quaternion [x, y, z, w] of the rotation matrix with these columns."""
    m = [[x_axis[r], y_axis[r], z_axis[r]] for r in range(3)]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2 * math.sqrt(1 + trace)
        q = ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4)
    else:  # w is small: divide by the largest diagonal term's instead, for stability
        i = max(range(3), key=lambda k: m[k][k])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
        q = [0.0] * 4
        q[i], q[j], q[k] = s / 4, (m[j][i] + m[i][j]) / s, (m[k][i] + m[i][k]) / s
        q[3] = (m[k][j] - m[j][k]) / s
    return normalize(q)


def look_at(eye, target):
    """The rotation [x, y, z, w] that turns a glTF camera (looking down its local -z, +y up) at
    `target` from `eye`, keeping +y up."""
    forward = normalize(sub(target, eye))
    right = normalize(cross(forward, (0, 1, 0)))
    return quaternion(right, cross(right, forward), mul(forward, -1))
