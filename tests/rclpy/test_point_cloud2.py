"""sensor_msgs_py.point_cloud2 on launchkit (ROS 2's package is not on PyPI): clouds made from
NumPy arrays, sent over the transport, and read back as Jazzy's package reads them."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest
from rclpy_runs import LAUNCHKIT, Runs

from launchkit.ros.msgs import get_message
from launchkit.ros.point_cloud2 import create_cloud, dtype_from_fields, read_points

PointField = get_message("sensor_msgs/msg/PointField")
Header = get_message("std_msgs/msg/Header")

Make = Callable[[str], Runs]


def test_a_cloud_crosses_the_transport_and_reads_back(runs: Make) -> None:
    status, out, err = runs(LAUNCHKIT).start("pointcloud.py").finish()
    assert status == 0, err
    assert out.splitlines() == [
        "2 1 16 32 32",
        "[Point(x=1.5, z=-3.25)]",
        "[[1.5, 2.0, -3.25, 0.5]]",
        "['x', 'y', 'z'] 12 [0.0, 1.0, 2.0]",
    ]


def test_an_organized_cloud_keeps_its_rows_and_mixed_fields_keep_their_offsets() -> None:
    fields = [
        PointField(name="x", offset=0, datatype=PointField.FLOAT64, count=1),
        PointField(name="ring", offset=8, datatype=PointField.UINT16, count=1),
    ]
    dtype = dtype_from_fields(fields, point_step=16)
    assert dtype.itemsize == 16 and dtype.fields is not None and dtype.fields["ring"][1] == 8
    grid = np.zeros((2, 3), dtype=dtype)
    grid["x"] = [[0, 1, 2], [3, 4, 5]]
    grid["ring"] = [[0, 0, 0], [1, 1, 1]]
    cloud = create_cloud(Header(), fields, grid, point_step=16)
    assert (cloud.height, cloud.width, cloud.point_step, cloud.row_step) == (3, 2, 16, 32)
    back = read_points(cloud, reshape_organized_cloud=True)
    assert back.shape == (3, 2) and back.reshape(-1).tolist() == grid.reshape(-1).tolist()
    assert read_points(cloud, field_names=["ring"], uvs=[(1, 2)]).tolist() == [(1,)]


def test_an_unstructured_array_needs_fields_of_one_type() -> None:
    fields = [
        PointField(name="x", offset=0, datatype=PointField.FLOAT32, count=1),
        PointField(name="i", offset=4, datatype=PointField.UINT8, count=1),
    ]
    with pytest.raises(ValueError, match="one datatype"):
        create_cloud(Header(), fields, np.zeros((2, 2), dtype=np.float32))
