"""A bridge between launchkit's ROS graph (Zenoh, rmw_zenoh's format) and a ROS 2 DDS graph
through the real rclpy: topics and services both ways, bytes passed through untouched.

Module map: ``_rclpy`` (import with clear errors, types, QoS), ``graph_view`` (both graphs in
one shape), ``plan`` (what to bridge: pure), ``echo_guard`` (no echo loops), ``topic_route`` and
``service_route`` (one bridged name each), ``bridge`` (the process: nodes, threads, reconcile),
``cli`` (``launchkit bridge``). It is also the package ``launchkit_bridge`` with the executable
``bridge``, for launch files (``<node pkg="launchkit_bridge" exec="bridge"/>``).
"""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="launchkit_bridge",
    share=Path(__file__).resolve().parent,
    executables={"bridge": "launchkit.bridge"},
)

__all__ = ["PACKAGE"]
