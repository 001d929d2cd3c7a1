"""``sensor_msgs_py`` on launchkit: ROS 2's pure-Python sensor_msgs helpers (not on PyPI)."""
