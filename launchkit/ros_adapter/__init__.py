"""The launcher's own ROS node (launch_ros's ``launch_ros_<pid>``): it loads components into
containers and drives lifecycle nodes for the launch's actions, implementing
:class:`launchkit.description.ros_link.RosLink` over :mod:`launchkit.ros`."""

from __future__ import annotations

from launchkit.ros_adapter.adapter import RosAdapter

__all__ = ["RosAdapter"]
