"""The rotation conventions tf2's buffer has, beyond plain quaternion algebra
(:mod:`launchkit.rotations`).

tf2 keeps a transform's rotation as a 3x3 matrix (``tf2::Transform``'s basis) and reads a
quaternion back from it, on the way in (``setTransform``) and on the way out (a lookup's result).
So what it hands back is normalised, and its sign is the matrix's (``Matrix3x3::getRotation``),
not necessarily the one that was sent: ``(0, 0, 0, -1)`` comes back as ``(0, 0, 0, 1)``.
Interpolation between two stamps is linear for translations and tf2's slerp for rotations.
"""

from __future__ import annotations

import math

from launchkit.rotations import Quaternion, Vector

Matrix = tuple[Vector, Vector, Vector]


def to_matrix(q: Quaternion) -> Matrix:
    """The rotation matrix of ``q``, scaled by ``2 / |q|^2`` as tf2 does (so any non-zero
    quaternion gives a rotation; a zero one gives NaNs)."""
    x, y, z, w = q
    d = x * x + y * y + z * z + w * w
    s = 2.0 / d if d != 0.0 else math.nan
    xs, ys, zs = x * s, y * s, z * s
    wx, wy, wz = w * xs, w * ys, w * zs
    xx, xy, xz = x * xs, x * ys, x * zs
    yy, yz, zz = y * ys, y * zs, z * zs
    return (
        (1.0 - (yy + zz), xy - wz, xz + wy),
        (xy + wz, 1.0 - (xx + zz), yz - wx),
        (xz - wy, yz + wx, 1.0 - (xx + yy)),
    )


def from_matrix(m: Matrix) -> Quaternion:
    """The quaternion tf2 reads from rotation matrix ``m`` (``Matrix3x3::getRotation``): ``w``
    positive when the trace is, else the largest diagonal term's component positive."""
    trace = m[0][0] + m[1][1] + m[2][2]
    q = [0.0, 0.0, 0.0, 0.0]
    if trace > 0.0:
        s = math.sqrt(trace + 1.0)
        q[3] = s * 0.5
        s = 0.5 / s
        q[0] = (m[2][1] - m[1][2]) * s
        q[1] = (m[0][2] - m[2][0]) * s
        q[2] = (m[1][0] - m[0][1]) * s
    else:
        if m[0][0] < m[1][1]:
            i = 2 if m[1][1] < m[2][2] else 1
        else:
            i = 2 if m[0][0] < m[2][2] else 0
        j, k = (i + 1) % 3, (i + 2) % 3
        s = _sqrt(m[i][i] - m[j][j] - m[k][k] + 1.0)
        q[i] = s * 0.5
        s = 0.5 / s if s != 0.0 else math.nan
        q[3] = (m[k][j] - m[j][k]) * s
        q[j] = (m[j][i] + m[i][j]) * s
        q[k] = (m[k][i] + m[i][k]) * s
    return (q[0], q[1], q[2], q[3])


def _sqrt(value: float) -> float:
    # C's sqrt: NaN for a negative or NaN argument rather than an exception
    return math.sqrt(value) if value >= 0.0 else math.nan


def as_stored(q: Quaternion) -> Quaternion:
    """``q`` as tf2 holds it: through its rotation matrix and back."""
    return from_matrix(to_matrix(q))


def lerp(a: Vector, b: Vector, ratio: float) -> Vector:
    """The point ``ratio`` of the way from ``a`` to ``b``."""
    rest = 1.0 - ratio
    return (
        rest * a[0] + ratio * b[0],
        rest * a[1] + ratio * b[1],
        rest * a[2] + ratio * b[2],
    )


def slerp(a: Quaternion, b: Quaternion, ratio: float) -> Quaternion:
    """tf2's spherical interpolation from ``a`` (ratio 0) to ``b`` (ratio 1), along the
    shorter arc."""
    dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    norms = math.sqrt(sum(c * c for c in a) * sum(c * c for c in b))
    cosine = abs(dot) / norms
    half_angle = math.acos(min(1.0, cosine))
    if half_angle == 0.0:
        return a
    d = 1.0 / math.sin(half_angle)
    s0 = math.sin((1.0 - ratio) * half_angle)
    s1 = math.sin(ratio * half_angle)
    if dot < 0.0:
        s1 = -s1
    return (
        (a[0] * s0 + b[0] * s1) * d,
        (a[1] * s0 + b[1] * s1) * d,
        (a[2] * s0 + b[2] * s1) * d,
        (a[3] * s0 + b[3] * s1) * d,
    )
