"""Quaternions, rotations and Euler angles: the one place launchkit's stock nodes, simulator and
tf2 buffer do rotation math (plain math: a state publisher needs a handful each message, and
numpy's call overhead would cost more than the arithmetic).

Quaternions are ``(x, y, z, w)`` as in geometry_msgs; Euler angles are URDF's and ROS's fixed-axis
roll, pitch, yaw (about x, then y, then z).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

Vector = tuple[float, float, float]
Quaternion = tuple[float, float, float, float]  # x, y, z, w as in geometry_msgs


def unit(vector: Iterable[float]) -> Vector:
    """``vector`` scaled to length 1 (a zero vector is returned unchanged)."""
    x, y, z = (float(v) for v in vector)
    norm = math.sqrt(x * x + y * y + z * z) or 1.0
    return (x / norm, y / norm, z / norm)


def axis_angle(axis: Vector, angle: float) -> Quaternion:
    """The rotation by ``angle`` radians about unit vector ``axis``."""
    s = math.sin(angle / 2.0)
    return (axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2.0))


def quaternion_multiply(a: Quaternion, b: Quaternion) -> Quaternion:
    """The rotation ``a`` followed (in the rotated frame) by ``b``: the product ``a * b``."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def conjugate(q: Quaternion) -> Quaternion:
    """The inverse rotation of unit quaternion ``q``."""
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Quaternion, v: Iterable[float]) -> Vector:
    """Vector ``v`` rotated by unit quaternion ``q``."""
    x, y, z, w = q
    vx, vy, vz = (float(c) for c in v)
    # t = 2 q_vec × v ; v' = v + w t + q_vec × t
    tx, ty, tz = 2 * (y * vz - z * vy), 2 * (z * vx - x * vz), 2 * (x * vy - y * vx)
    return (
        vx + w * tx + (y * tz - z * ty),
        vy + w * ty + (z * tx - x * tz),
        vz + w * tz + (x * ty - y * tx),
    )


def rpy_to_quaternion(roll: float, pitch: float, yaw: float) -> Quaternion:
    """URDF's fixed-axis roll, pitch, yaw (about x, then y, then z) as a quaternion."""
    qx = axis_angle((1.0, 0.0, 0.0), roll)
    qy = axis_angle((0.0, 1.0, 0.0), pitch)
    qz = axis_angle((0.0, 0.0, 1.0), yaw)
    return quaternion_multiply(qz, quaternion_multiply(qy, qx))


def quaternion_to_rpy(q: Quaternion) -> Vector:
    """(roll, pitch, yaw) of unit quaternion ``q`` (pitch clamped to ±π/2)."""
    x, y, z, w = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


def yaw_of(q: Quaternion) -> float:
    """Yaw (rad) of ``q``: the heading of a robot on the ground."""
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def quaternion_from_yaw(yaw: float) -> Quaternion:
    """The rotation by ``yaw`` about +z."""
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


def matrix_to_quaternion(m: list[list[float]]) -> Quaternion:
    """A 3x3 rotation matrix as a unit quaternion with ``w >= 0``."""
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0.0:
        s = math.sqrt(trace + 1.0) * 2.0
        q = ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4.0)
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2.0
        q = (s / 4.0, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s)
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2.0
        q = ((m[0][1] + m[1][0]) / s, s / 4.0, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s)
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2.0
        q = ((m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, s / 4.0, (m[1][0] - m[0][1]) / s)
    if q[3] < 0.0:
        q = (-q[0], -q[1], -q[2], -q[3])
    norm = math.sqrt(sum(c * c for c in q))
    return (q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm)
