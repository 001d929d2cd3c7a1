"""launchkit: run ROS 2 XML launch files, and the robot they describe, without a ROS install."""

from __future__ import annotations

__version__ = "0.1.0"

__all__ = ["__version__"]
