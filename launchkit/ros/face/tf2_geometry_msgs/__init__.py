"""``tf2_geometry_msgs`` on launchkit: importing it registers the geometry_msgs types with
``Buffer.transform`` (:mod:`launchkit.ros.tf2.tf2_geometry_msgs`)."""

from .tf2_geometry_msgs import *  # noqa: F403 - the names of its module, as in ROS 2
