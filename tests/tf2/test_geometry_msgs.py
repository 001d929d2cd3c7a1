"""tf2_geometry_msgs' ``do_transform_*`` against hand-worked results, and ``Buffer.transform``
through the registrations importing it makes."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from launchkit.ros.clock import Time
from launchkit.ros.msgs import get_message
from launchkit.ros.tf2 import Buffer, TypeException, convert
from launchkit.ros.tf2 import tf2_geometry_msgs as tgm
from tests.tf2.transforms import stamped, yaw

S = math.sqrt(0.5)
# map -> base: base is at (1, 2, 0) in map, turned 90° left
TURNED = stamped("map", "base", 7, xyz=(1.0, 2.0, 0.0), q=yaw(math.pi / 2))


def message(name: str) -> Any:
    return get_message(f"geometry_msgs/msg/{name}")()


def test_a_point_moves_with_the_whole_transform() -> None:
    point = message("PointStamped")
    point.point.x, point.point.y, point.point.z = 1.0, 0.0, 3.0
    moved = tgm.do_transform_point(point, TURNED)
    # (1, 0) turned 90° is (0, 1); plus (1, 2)
    assert (moved.point.x, moved.point.y, moved.point.z) == pytest.approx((1.0, 3.0, 3.0))
    assert moved.header is TURNED.header  # the target frame and the transform's stamp


def test_a_vector_only_turns() -> None:
    vector = message("Vector3Stamped")
    vector.vector.x = 2.0
    turned = tgm.do_transform_vector3(vector, TURNED)
    assert (turned.vector.x, turned.vector.y, turned.vector.z) == pytest.approx((0.0, 2.0, 0.0))
    # the transform given is not changed (Jazzy's zeroes its translation)
    assert TURNED.transform.translation.x == 1.0


def test_a_pose_moves_and_turns() -> None:
    pose = message("Pose")
    pose.position.x = 1.0
    pose.orientation.z, pose.orientation.w = S, S
    moved = tgm.do_transform_pose(pose, TURNED)
    assert type(moved).__name__ == "Pose"
    assert (moved.position.x, moved.position.y) == pytest.approx((1.0, 3.0))
    # 90° + 90° = 180°: (0, 0, 1, 0), w made non-negative
    o = moved.orientation
    assert (o.x, o.y, abs(o.z), o.w) == pytest.approx((0.0, 0.0, 1.0, 0.0), abs=1e-12)
    stamped_pose = message("PoseStamped")
    stamped_pose.pose = pose
    result = tgm.do_transform_pose_stamped(stamped_pose, TURNED)
    assert result.pose.position.y == pytest.approx(3.0) and result.header.frame_id == "map"


def test_a_covariance_turns_with_the_pose() -> None:
    pose = message("PoseWithCovarianceStamped")
    pose.pose.covariance = np.diag([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]).reshape(36)
    pose.pose.covariance[1] = pose.pose.covariance[6] = 0.5
    moved = tgm.do_transform_pose_with_covariance_stamped(pose, TURNED)
    expected = np.diag([2.0, 1.0, 3.0, 5.0, 4.0, 6.0])
    # x-y correlation of +0.5 becomes -0.5 once x and y trade places with a sign: x' = -y, y' = x
    expected[0, 1] = expected[1, 0] = -0.5
    assert np.allclose(np.asarray(moved.pose.covariance).reshape(6, 6), expected)
    assert moved.pose.pose.position.x == pytest.approx(1.0)


def test_a_polygon_moves_point_by_point() -> None:
    polygon = message("PolygonStamped")
    for x, y in ((0.0, 0.0), (1.0, 0.0)):
        polygon.polygon.points.append(get_message("geometry_msgs/msg/Point32")(x=x, y=y, z=0.0))
    moved = tgm.do_transform_polygon_stamped(polygon, TURNED)
    moved_xy = [c for p in moved.polygon.points for c in (p.x, p.y)]
    assert moved_xy == pytest.approx([1.0, 2.0, 1.0, 3.0])


def test_buffer_transform_uses_the_registered_functions() -> None:
    buffer = Buffer()
    buffer.set_transform(TURNED, "test")
    point = message("PointStamped")
    point.header.frame_id = "base"
    point.header.stamp = Time(seconds=7).to_msg()
    point.point.x = 1.0
    in_map = buffer.transform(point, "map")
    assert (in_map.point.x, in_map.point.y) == pytest.approx((1.0, 3.0))
    assert in_map.header.frame_id == "map" and in_map.header.stamp.sec == 7
    # the same through the conversions it registers
    assert convert(in_map, type(in_map)) == in_map
    with pytest.raises(TypeException) as caught:
        buffer.transform(message("Point"), "map")
    assert caught.value.errstr == (f"Type {type(message('Point'))} is not loaded or supported")
