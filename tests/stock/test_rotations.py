"""The one rotations module: Euler angles, yaw and vector rotation agree with each other."""

from __future__ import annotations

import itertools
import math

import pytest

from launchkit.rotations import (
    conjugate,
    quaternion_from_yaw,
    quaternion_to_rpy,
    rotate,
    rpy_to_quaternion,
    yaw_of,
)

ANGLES = (-2.9, -0.3, 0.0, 1.3, 3.0)
PITCHES = (-1.4, 0.0, 0.7)


@pytest.mark.parametrize(("roll", "pitch", "yaw"), list(itertools.product(ANGLES, PITCHES, ANGLES)))
def test_rpy_round_trip(roll: float, pitch: float, yaw: float) -> None:
    q = rpy_to_quaternion(roll, pitch, yaw)
    assert quaternion_to_rpy(q) == pytest.approx((roll, pitch, yaw), abs=1e-9)
    assert yaw_of(q) == pytest.approx(yaw, abs=1e-9)


@pytest.mark.parametrize("yaw", ANGLES)
def test_yaw_quaternion_is_the_rpy_one(yaw: float) -> None:
    assert quaternion_from_yaw(yaw) == pytest.approx(rpy_to_quaternion(0.0, 0.0, yaw))
    assert yaw_of(quaternion_from_yaw(yaw)) == pytest.approx(yaw)


def test_rotate_and_its_inverse() -> None:
    q = rpy_to_quaternion(0.3, -0.7, 2.1)
    v = (1.0, -2.0, 0.5)
    assert rotate(conjugate(q), rotate(q, v)) == pytest.approx(v)
    assert rotate(quaternion_from_yaw(math.pi / 2), (1.0, 0.0, 0.0)) == pytest.approx(
        (0.0, 1.0, 0.0), abs=1e-12
    )
