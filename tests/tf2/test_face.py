"""The face packages ``tf2_ros``, ``tf2_geometry_msgs`` and ``tf2_py``: a process with the face
folder on its PYTHONPATH imports them as ROS 2 code does, and gets launchkit's tf2."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import launchkit.ros

FACE = Path(launchkit.ros.__file__).resolve().parent / "face"

PROGRAM = """
import tf2_ros, tf2_py
from tf2_ros.buffer import Buffer
from tf2_ros.buffer_interface import TransformRegistration
from tf2_ros.transform_listener import TransformListener
from tf2_ros.transform_broadcaster import TransformBroadcaster
from tf2_ros.static_transform_broadcaster import StaticTransformBroadcaster
import launchkit.ros.tf2 as tf2
from launchkit.ros.msgs.geometry_msgs.msg import PointStamped

assert tf2_ros.Buffer is Buffer is tf2.Buffer and tf2_ros.BufferCore is tf2_py.BufferCore
assert TransformListener is tf2.TransformListener
assert TransformBroadcaster is tf2.TransformBroadcaster
assert StaticTransformBroadcaster is tf2.StaticTransformBroadcaster
assert tf2_ros.LookupException is tf2_py.LookupException is tf2.LookupException
try:
    TransformRegistration().get(PointStamped)
except tf2_ros.TypeException:
    print("not registered before tf2_geometry_msgs")
import tf2_geometry_msgs
from tf2_geometry_msgs.tf2_geometry_msgs import do_transform_point
assert tf2_geometry_msgs.do_transform_point is do_transform_point
assert TransformRegistration().get(PointStamped) is do_transform_point
print("registered by tf2_geometry_msgs")
"""


def test_the_face_packages_are_launchkits_tf2() -> None:
    path = os.pathsep.join([str(FACE), os.environ.get("PYTHONPATH", "")])
    result = subprocess.run(
        [sys.executable, "-c", PROGRAM],
        capture_output=True,
        text=True,
        timeout=120,
        env={**os.environ, "PYTHONPATH": path},
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == [
        "not registered before tf2_geometry_msgs",
        "registered by tf2_geometry_msgs",
    ]
