"""``static_transform_publisher`` from a launch file, as ROS 2 launch files use it: the stock
``tf2_ros`` package is found, the node takes the launch file's name, and the transform reaches
a listener."""

from __future__ import annotations

import math
from typing import Any

import pytest

import launchkit.ros as ros
from launchkit.ros.clock import Duration, Time
from launchkit.ros.tf2 import Buffer, TransformListener
from tests.tf2.transforms import rotation, translation


def test_a_launch_files_static_transform_reaches_a_listener(launch: Any) -> None:
    handle = launch("launch/static_tf.launch.xml")
    publisher = handle.process("static_transform_publisher")
    publisher.wait_output("from 'base_link' to 'lidar'", timeout=60)
    assert any("[lidar_mount]: Spinning until stopped" in line for line in publisher.output)

    context = ros.Context(router=handle.router)
    context.init([], handle.domain_id)
    node = ros.Node("tf_probe", context=context)
    buffer = Buffer()
    listener = TransformListener(buffer, node, spin_thread=True)
    try:
        found = buffer.lookup_transform("base_link", "lidar", Time(), Duration(seconds=60))
    finally:
        del listener
        node.destroy_node()
        context.shutdown()
    assert translation(found) == pytest.approx((0.2, 0.0, 0.3))
    assert rotation(found) == pytest.approx((0.0, 0.0, math.sin(3.14159265 / 2), 1.8e-9), abs=1e-8)
    handle.stop().assert_exit_codes({"static_transform_publisher": 0})
