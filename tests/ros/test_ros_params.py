"""Parameters from params files (ROS format), -p overrides, declared types."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.errors import UserError
from launchkit.ros.arguments import parse_ros_args
from launchkit.ros.node_params import InvalidParameterTypeException, ParameterStore
from launchkit.ros.params import Parameter, ParameterType, load_params_file, overrides_for


def test_params_file_patterns(tmp_path: Path) -> None:
    path = tmp_path / "p.yaml"
    path.write_text(
        "/**:\n  ros__parameters:\n    rate: 10\n    nested: {a: 1}\n"
        "/robot/driver:\n  ros__parameters:\n    rate: 20\n"
        "other:\n  ros__parameters:\n    rate: 30\n"
        "/**/driver:\n  ros__parameters:\n    wheel: 0.5\n"
    )
    assert load_params_file(path, "/robot/driver") == {"rate": 20, "nested.a": 1, "wheel": 0.5}
    assert load_params_file(path, "/other") == {"rate": 30, "nested.a": 1}
    assert load_params_file(path, "/driver") == {"rate": 10, "nested.a": 1, "wheel": 0.5}


def test_command_line_order(tmp_path: Path) -> None:
    path = tmp_path / "p.yaml"
    path.write_text("/**:\n  ros__parameters:\n    rate: 10\n    name: x\n")
    args = parse_ros_args(
        [
            "--ros-args",
            "-p",
            "rate:=5",
            "--params-file",
            str(path),
            "-p",
            "flag:=true",
            "-p",
            "list:=[1, 2]",
            "-p",
            "other:name:=ignored",
        ]
    )
    assert overrides_for(args, "node", "/node") == {
        "rate": 10,
        "name": "x",
        "flag": True,
        "list": [1, 2],
    }


def test_bad_params_file(tmp_path: Path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text("/**:\n  rate: 1\n")
    with pytest.raises(UserError):
        load_params_file(path, "/n")
    with pytest.raises(UserError):
        load_params_file(tmp_path / "missing.yaml", "/n")


def test_declared_type_is_enforced() -> None:
    store = ParameterStore({"rate": "fast"}, allow_undeclared=False)
    with pytest.raises(InvalidParameterTypeException):
        store.declare("rate", 10)
    store = ParameterStore({"gain": 2}, allow_undeclared=False)
    assert store.declare("gain", 1.0).value == 2.0
    result = store.set_atomically([Parameter("gain", value="x")])
    assert not result.successful and "DOUBLE" in result.reason
    assert store.set_atomically([Parameter("gain", value=3.5)]).successful
    assert store.get("gain").type_ == ParameterType.DOUBLE
