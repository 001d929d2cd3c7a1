"""The QoS of turtlesim's topics (``cmd_vel``, ``pose``, ``color_sensor``), on both ends: keep
the last 7, reliable, as Jazzy's ``turtlesim::topic_qos()``."""

from __future__ import annotations

import launchkit.ros as ros

TOPIC_QOS = ros.QoSProfile(depth=7, reliability=ros.ReliabilityPolicy.RELIABLE)
