"""``tf2_geometry_msgs``: applying a TransformStamped to geometry_msgs types, as ROS 2 Jazzy's
Python package does, and registering the stamped ones so ``buffer.transform(msg, frame)`` works.

The maths is Jazzy's: a 4x4 affine of the transform times the object's, with the quaternion read
back from the rotation matrix (``transforms3d``'s ``mat2quat``, so an orientation comes out
normalised with ``w >= 0``); a covariance is rotated block by block (``R C Rᵀ`` for each of its
four 3x3 blocks). A result's header is the transform's (the target frame and the transform's
stamp), the same object, as in tf2_geometry_msgs.

Unlike Jazzy's ``do_transform_vector3``, the transform passed in is left unchanged (Jazzy zeroes
its translation as a side effect).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from transforms3d.quaternions import mat2quat, quat2mat

from launchkit.ros.msgs import get_message
from launchkit.ros.tf2.buffer_interface import ConvertRegistration, TransformRegistration

PointStamped = get_message("geometry_msgs/msg/PointStamped")
Vector3Stamped = get_message("geometry_msgs/msg/Vector3Stamped")
Pose = get_message("geometry_msgs/msg/Pose")
PoseStamped = get_message("geometry_msgs/msg/PoseStamped")
PoseWithCovarianceStamped = get_message("geometry_msgs/msg/PoseWithCovarianceStamped")
PolygonStamped = get_message("geometry_msgs/msg/PolygonStamped")
Point32 = get_message("geometry_msgs/msg/Point32")


def _affine(transform: Any) -> np.ndarray:
    """The 4x4 matrix of a TransformStamped."""
    t, r = transform.transform.translation, transform.transform.rotation
    return _compose((r.w, r.x, r.y, r.z), (t.x, t.y, t.z))


def _compose(wxyz: tuple[float, ...], xyz: tuple[float, ...]) -> np.ndarray:
    affine = np.eye(4)
    affine[:3, :3] = quat2mat(np.asarray(wxyz, dtype=np.float64))
    affine[:3, 3] = xyz
    return affine


def _moved(transform: Any, x: float, y: float, z: float) -> tuple[float, float, float]:
    """Point ``(x, y, z)`` through ``transform``."""
    point = _affine(transform) @ np.array([x, y, z, 1.0])
    return float(point[0]), float(point[1]), float(point[2])


def do_transform_point(point: Any, transform: Any) -> Any:
    """A PointStamped in the transform's target frame."""
    x, y, z = _moved(transform, point.point.x, point.point.y, point.point.z)
    result = PointStamped()
    result.point.x, result.point.y, result.point.z = x, y, z
    result.header = transform.header
    return result


def do_transform_vector3(vector3: Any, transform: Any) -> Any:
    """A Vector3Stamped rotated into the transform's target frame (a direction: the
    translation does not apply)."""
    r = transform.transform.rotation
    rotated = quat2mat(np.array([r.w, r.x, r.y, r.z])) @ np.array(
        [vector3.vector.x, vector3.vector.y, vector3.vector.z]
    )
    result = Vector3Stamped()
    result.vector.x, result.vector.y, result.vector.z = (float(v) for v in rotated)
    result.header = transform.header
    return result


def do_transform_pose(pose: Any, transform: Any) -> Any:
    """A Pose (not stamped) in the transform's target frame."""
    p, q = pose.position, pose.orientation
    moved = _affine(transform) @ _compose((q.w, q.x, q.y, q.z), (p.x, p.y, p.z))
    w, x, y, z = mat2quat(moved[:3, :3])
    result = Pose()
    result.position.x, result.position.y, result.position.z = (float(v) for v in moved[:3, 3])
    result.orientation.x, result.orientation.y = float(x), float(y)
    result.orientation.z, result.orientation.w = float(z), float(w)
    return result


def do_transform_pose_stamped(pose: Any, transform: Any) -> Any:
    """A PoseStamped in the transform's target frame."""
    result = PoseStamped()
    result.pose = do_transform_pose(pose.pose, transform)
    result.header = transform.header
    return result


def transform_covariance(cov_in: Any, transform: Any) -> Any:
    """A 6x6 pose covariance (36 numbers, row-major) rotated into the transform's frame."""
    r = transform.transform.rotation
    rotation = quat2mat(np.array([r.w, r.x, r.y, r.z]))
    both = np.zeros((6, 6))
    both[:3, :3] = rotation
    both[3:, 3:] = rotation
    covariance = np.asarray(cov_in, dtype=np.float64).reshape(6, 6)
    return (both @ covariance @ both.T).reshape(36)


def do_transform_pose_with_covariance_stamped(pose: Any, transform: Any) -> Any:
    """A PoseWithCovarianceStamped in the transform's target frame, covariance rotated."""
    result = PoseWithCovarianceStamped()
    result.pose.pose = do_transform_pose(pose.pose.pose, transform)
    result.pose.covariance = transform_covariance(pose.pose.covariance, transform)
    result.header = transform.header
    return result


def do_transform_polygon_stamped(polygon: Any, transform: Any) -> Any:
    """A PolygonStamped with every point in the transform's target frame."""
    result = PolygonStamped()
    for point in polygon.polygon.points:
        x, y, z = _moved(transform, point.x, point.y, point.z)
        result.polygon.points.append(Point32(x=x, y=y, z=z))
    result.header = transform.header
    return result


def to_msg_msg(msg: Any) -> Any:
    """A message is its own message form."""
    return msg


def from_msg_msg(msg: Any) -> Any:
    """A message is made from its own message form."""
    return msg


for _stamped in (Vector3Stamped, PoseStamped, PointStamped):
    ConvertRegistration().add_to_msg(_stamped, to_msg_msg)
    ConvertRegistration().add_from_msg(_stamped, from_msg_msg)

TransformRegistration().add(PointStamped, do_transform_point)
TransformRegistration().add(Vector3Stamped, do_transform_vector3)
TransformRegistration().add(PoseStamped, do_transform_pose_stamped)
TransformRegistration().add(PoseWithCovarianceStamped, do_transform_pose_with_covariance_stamped)
TransformRegistration().add(PolygonStamped, do_transform_polygon_stamped)
