"""``sensor_msgs_py.point_cloud2``: :mod:`launchkit.ros.point_cloud2`."""

from launchkit.ros.point_cloud2 import (
    DATATYPES,
    create_cloud,
    create_cloud_xyz32,
    dtype_from_fields,
    read_points,
    read_points_list,
    read_points_numpy,
)

__all__ = [
    "DATATYPES",
    "create_cloud",
    "create_cloud_xyz32",
    "dtype_from_fields",
    "read_points",
    "read_points_list",
    "read_points_numpy",
]
