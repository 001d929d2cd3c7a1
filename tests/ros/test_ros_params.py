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
    store = ParameterStore({"gain": 2.0}, allow_undeclared=False)
    assert store.declare("gain", 1.0).value == 2.0
    result = store.set_atomically([Parameter("gain", value="x")])
    assert not result.successful and "DOUBLE" in result.reason
    assert store.set_atomically([Parameter("gain", value=3.5)]).successful
    assert store.get("gain").type_ == ParameterType.DOUBLE


def _our_verdicts() -> tuple[str, str, str]:
    """What launchkit says to an integer for a double, declared and set (as rclpy, below)."""
    store = ParameterStore({"gain": 2, "gains": [1, 2]}, allow_undeclared=False)
    said = []
    for name, default in (("gain", 1.0), ("gains", [1.0])):
        with pytest.raises(InvalidParameterTypeException) as caught:
            store.declare(name, default)
        said.append(str(caught.value))
    store = ParameterStore({}, allow_undeclared=False)
    store.declare("gain", 1.0)
    return said[0], said[1], store.set_atomically([Parameter("gain", value=3)]).reason


def test_an_integer_is_not_a_double() -> None:
    assert _our_verdicts() == (
        "Trying to set parameter 'gain' to '2' of type 'INTEGER', expecting type 'DOUBLE': gain",
        "Trying to set parameter 'gains' to '[1, 2]' of type 'INTEGER_ARRAY', expecting type "
        "'DOUBLE_ARRAY': gains",
        "Wrong parameter type, expected 'Type.DOUBLE' got 'Type.INTEGER'",
    )


# rclpy's type support imports lark, which imports the deprecated sre_parse
@pytest.mark.filterwarnings("ignore:module 'sre_.*' is deprecated:DeprecationWarning")
def test_an_integer_is_not_a_double_for_the_real_rclpy_either(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    rclpy = pytest.importorskip("rclpy", reason="the real rclpy needs CPython 3.11 on Linux")
    from rclpy.exceptions import InvalidParameterTypeException as RclpyTypeError
    from rclpy.parameter import Parameter as RclpyParameter

    from launchkit.testing._isolation import domain_id

    monkeypatch.setenv("ROS_DOMAIN_ID", str(domain_id()))
    context = rclpy.Context()
    rclpy.init(args=[], context=context)
    try:
        args = ["--ros-args", "-p", "gain:=2", "-p", "gains:=[1, 2]"]
        node = rclpy.create_node("n", context=context, cli_args=args)
        said = []
        for name, default in (("gain", 1.0), ("gains", [1.0])):
            with pytest.raises(RclpyTypeError) as caught:
                node.declare_parameter(name, default)
            said.append(str(caught.value))
        fresh = rclpy.create_node("m", context=context)
        fresh.declare_parameter("gain", 1.0)
        (result,) = fresh.set_parameters([RclpyParameter("gain", value=3)])
        assert (said[0], said[1], result.reason) == _our_verdicts()
    finally:
        rclpy.shutdown(context=context)
