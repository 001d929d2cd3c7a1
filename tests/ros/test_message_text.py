"""Messages as ros2 prints them (launchkit.ros.message_text): rosidl's repr, compared with the
real rosidl classes of the ros-jazzy wheels where they are installed, and rosidl_runtime_py's
YAML and CSV, whatever container a message holds its arrays in."""

from __future__ import annotations

import array
import importlib
from typing import Any

import numpy as np
import pytest

from launchkit.ros.message_data import fields_of
from launchkit.ros.message_text import short_repr, to_csv, to_yaml, value_text
from launchkit.ros.msgs import get_message

CASES: list[tuple[str, dict[str, Any]]] = [
    ("std_msgs/msg/String", {"data": "it's"}),
    ("std_msgs/msg/Empty", {}),
    ("std_msgs/msg/Byte", {}),
    ("std_msgs/msg/Char", {}),
    ("geometry_msgs/msg/Twist", {}),
    ("sensor_msgs/msg/Imu", {}),
    ("sensor_msgs/msg/JointState", {"name": ["a", "b"], "position": [1.0, 2.5]}),
    ("std_msgs/msg/Float32MultiArray", {"data": [0.1, 0.2]}),
    ("unique_identifier_msgs/msg/UUID", {}),
    ("rcl_interfaces/msg/Log", {"name": "n", "msg": "héllo", "level": 20}),
    (
        "rcl_interfaces/msg/ParameterValue",
        {
            "integer_array_value": [1, 2],
            "bool_array_value": [True],
            "double_array_value": [0.5],
            "string_array_value": ["a"],
        },
    ),
]


def real_class(type_name: str) -> Any:
    package, _, name = type_name.split("/")
    try:
        return getattr(importlib.import_module(f"{package}.msg"), name)
    except ImportError:
        pytest.skip(f"the real {package} (ros-jazzy wheels) is not installed here")


@pytest.mark.parametrize(("type_name", "values"), CASES, ids=[c[0] for c in CASES])
def test_repr_is_rosidls(type_name: str, values: dict[str, Any]) -> None:
    ours = get_message(type_name)(**values)
    assert short_repr(ours) == repr(real_class(type_name)(**values))


@pytest.mark.parametrize(
    "positions",
    [[1.0, 2.5], array.array("d", [1.0, 2.5]), np.array([1.0, 2.5])],
    ids=["list", "array.array", "numpy"],
)
def test_the_text_does_not_depend_on_the_container(positions: Any) -> None:
    msg = get_message("sensor_msgs/msg/JointState")(name=["a", "b"], position=positions)
    assert short_repr(msg).endswith("name=['a', 'b'], position=[1.0, 2.5], velocity=[], effort=[])")
    assert to_yaml(msg) == (
        "header:\n  stamp:\n    sec: 0\n    nanosec: 0\n  frame_id: ''\n"
        "name:\n- a\n- b\nposition:\n- 1.0\n- 2.5\nvelocity: []\neffort: []\n"
    )
    assert to_csv(msg) == "0,0,,a,b,1.0,2.5,,"
    field = dict(fields_of("sensor_msgs/msg/JointState"))["position"]
    # what `topic echo --field position` prints: str() of what rosidl holds
    assert value_text(positions, field) == "array('d', [1.0, 2.5])"


def test_yaml_options_as_rosidl_runtime_py() -> None:
    imu = get_message("sensor_msgs/msg/Imu")()
    no_arr = to_yaml(imu, no_arr=True)
    assert "orientation_covariance: '<array type: double[9]>'\n" in no_arr
    flow = to_yaml(get_message("geometry_msgs/msg/Vector3")(x=1.0), flow_style=True)
    assert flow == "{x: 1.0, y: 0.0, z: 0.0}\n"
    long = get_message("std_msgs/msg/String")(data="x" * 130)
    assert to_yaml(long) == f"data: {'x' * 128}...\n"
    assert to_yaml(long, None) == f"data: {'x' * 130}\n"
    assert to_yaml(long, no_str=True) == "data: '<string length: <130>>'\n"
    many = get_message("std_msgs/msg/Float64MultiArray")(data=list(range(5)))
    assert to_yaml(many, 2).endswith("data:\n- 0.0\n- 1.0\n- '...'\n")
    assert to_csv(many, 2).endswith(",0.0,1.0,...")
    assert to_yaml(get_message("std_msgs/msg/Empty")()) == "{}\n"
    assert to_yaml(get_message("std_msgs/msg/Byte")(data=65)) == "data: A\n"
