"""Parse-level tests of the ROS tags: <node> command lines follow ROS 2's conventions."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import yaml

from launchkit.errors import LaunchFileError
from launchkit.packages import PackageIndex
from tests.conftest import EvaluateXml
from tests.engine.conftest import params_file, ros_args


def params_files(cmd: list[str]) -> list[dict[str, object]]:
    """The YAML content of every ``--params-file`` on the command line."""
    args = ros_args(cmd)
    return [
        yaml.safe_load(Path(args[i + 1]).read_text())
        for i, arg in enumerate(args)
        if arg == "--params-file"
    ]


def test_node_command_line(evaluate_xml: EvaluateXml, packages: PackageIndex) -> None:
    xml = """<launch>
      <node pkg="demo" exec="talker" name="chatter" namespace="robot" args="--flag 'a b'"
            output="screen" respawn="true">
        <remap from="cmd_vel" to="/robot/cmd_vel"/>
        <env name="EXTRA" value="1"/>
      </node>
    </launch>"""
    spec = evaluate_xml(xml, packages=packages).processes[0]
    assert spec.cmd[:5] == [sys.executable, "-m", "demo.talker", "--flag", "a b"]
    assert ros_args(spec.cmd) == [
        "-r",
        "__node:=chatter",
        "-r",
        "__ns:=/robot",
        "-r",
        "cmd_vel:=/robot/cmd_vel",
    ]
    assert spec.is_node and spec.respawn and spec.output == "screen"
    assert spec.env["EXTRA"] == "1"
    assert spec.name == "talker"


def test_node_label_is_exec_name(evaluate_xml: EvaluateXml, packages: PackageIndex) -> None:
    xml = '<launch><node pkg="demo" exec="talker" exec_name="speaker"/></launch>'
    spec = evaluate_xml(xml, packages=packages).processes[0]
    assert spec.name == "speaker"
    assert spec.cmd[3:] == ["--ros-args"]  # launch_ros always opens its own section


def test_node_ros_args_attribute(evaluate_xml: EvaluateXml, packages: PackageIndex) -> None:
    xml = '<launch><node pkg="demo" exec="talker" ros_args="--log-level debug"/></launch>'
    spec = evaluate_xml(xml, packages=packages).processes[0]
    assert spec.cmd[3:] == ["--ros-args", "--log-level", "debug", "--ros-args"]


def test_each_param_becomes_a_ros_params_file(
    evaluate_xml: EvaluateXml, packages: PackageIndex
) -> None:
    xml = """<launch>
      <node pkg="demo" exec="talker" name="n">
        <param name="rate" value="10"/>
        <param name="scale" value="0.5"/>
        <param name="enabled" value="true"/>
        <param name="label" value="10" type="str"/>
        <param name="list" value="[1, 2, 3]"/>
        <param name="words" value="a;b" value-sep=";"/>
        <param name="wheel">
          <param name="radius" value="0.1"/>
        </param>
      </node>
    </launch>"""
    spec = evaluate_xml(xml, packages=packages).processes[0]
    # one file per <param>, in document order, nested names dotted: as launch_ros writes them
    assert params_files(spec.cmd) == [
        {"/**": {"ros__parameters": values}}
        for values in (
            {"rate": 10},
            {"scale": 0.5},
            {"enabled": True},
            {"label": "10"},
            {"list": [1, 2, 3]},
            {"words": ["a", "b"]},
            {"wheel.radius": 0.1},
        )
    ]


def test_parameters_keep_launch_ros_order_and_precedence(
    evaluate_xml: EvaluateXml, packages: PackageIndex, tmp_path: Path
) -> None:
    from launchkit.ros.arguments import parse_ros_args
    from launchkit.ros.params import overrides_for

    params_file(tmp_path / "rate.yaml", "rate: 5.0", "n: 1")
    params_file(tmp_path / "global.yaml", "g: 0", "n: 0")
    xml = f"""<launch>
      <arg name="rate" default="1.0"/>
      <set_parameter name="g" value="1"/>
      <set_parameters_from_file filename="{tmp_path}/global.yaml"/>
      <set_parameter name="h" value="two"/>
      <node pkg="demo" exec="talker" name="n" namespace="ns" ros_args="--log-level warn">
        <param from="{tmp_path}/rate.yaml"/>
        <param name="rate" value="$(var rate)"/>
      </node>
    </launch>"""
    spec = evaluate_xml(xml, {"rate": "7.0"}, packages=packages).processes[0]
    generated = spec.cmd[-1]
    # launch_ros jazzy's sequence (checked with the real stack, ros2 launch):
    assert spec.cmd[3:] == [
        "--ros-args",
        "--log-level",
        "warn",
        "--ros-args",
        "-r",
        "__node:=n",
        "-r",
        "__ns:=/ns",
        "-p",
        "g:=1",
        "--params-file",
        f"{tmp_path}/global.yaml",
        "-p",
        "h:=two",
        "--params-file",
        f"{tmp_path}/rate.yaml",
        "--params-file",
        generated,
    ]
    assert yaml.safe_load(Path(generated).read_text()) == {
        "/ns/n": {"ros__parameters": {"rate": 7.0}}
    }
    # what the node then sees: the launch argument, given after the YAML file, wins
    seen = overrides_for(parse_ros_args(spec.cmd), "n", "/ns/n")
    assert seen == {"g": 0, "n": 1, "h": "two", "rate": 7.0}  # global.yaml came after g:=1


def test_param_from_yaml_file(
    evaluate_xml: EvaluateXml, packages: PackageIndex, tmp_path: Path
) -> None:
    params = params_file(tmp_path / "params.yaml", "a: 1")
    xml = f'<launch><node pkg="demo" exec="talker"><param from="{params}"/></node></launch>'
    spec = evaluate_xml(xml, packages=packages).processes[0]
    args = ros_args(spec.cmd)
    assert args[args.index("--params-file") + 1] == str(params)


def test_push_ros_namespace_both_spellings_and_scoping(
    evaluate_xml: EvaluateXml, packages: PackageIndex
) -> None:
    xml = """<launch>
      <group>
        <push_ros_namespace namespace="outer"/>
        <group>
          <push-ros-namespace namespace="inner"/>
          <node pkg="demo" exec="talker" exec_name="deep"/>
        </group>
        <node pkg="demo" exec="talker" exec_name="mid" namespace="rel"/>
        <node pkg="demo" exec="talker" exec_name="abs" namespace="/abs"/>
      </group>
      <node pkg="demo" exec="talker" exec_name="top"/>
    </launch>"""
    result = evaluate_xml(xml, packages=packages)
    assert "__ns:=/outer/inner" in ros_args(result.process("deep").cmd)
    assert "__ns:=/outer/rel" in ros_args(result.process("mid").cmd)
    assert "__ns:=/abs" in ros_args(result.process("abs").cmd)
    assert result.process("top").cmd[3:] == ["--ros-args"]


def test_set_parameter_set_remap_and_use_sim_time(
    evaluate_xml: EvaluateXml, packages: PackageIndex
) -> None:
    xml = """<launch>
      <group>
        <set_parameter name="use_sim_time" value="false"/>
        <set_use_sim_time value="true"/>
        <set_parameter name="robot" value="wheel"/>
        <set_remap from="scan" to="/base_scan"/>
        <node pkg="demo" exec="talker" exec_name="inside"/>
      </group>
      <node pkg="demo" exec="talker" exec_name="outside"/>
    </launch>"""
    result = evaluate_xml(xml, packages=packages)
    inside = result.process("inside").cmd
    # as ros2 launch writes global parameters (True, not true); <set_use_sim_time>, which
    # Jazzy cannot run, is one more for the nodes
    assert ros_args(inside) == [
        "-p", "use_sim_time:=False", "-p", "use_sim_time:=True", "-p", "robot:=wheel",
        "-r", "scan:=/base_scan",
    ]  # fmt: skip
    assert result.process("outside").cmd[3:] == ["--ros-args"]


def test_set_parameters_from_file(
    evaluate_xml: EvaluateXml, packages: PackageIndex, tmp_path: Path
) -> None:
    params = params_file(tmp_path / "global.yaml", "g: 2")
    xml = f"""<launch>
      <set_parameters_from_file filename="{params}"/>
      <node pkg="demo" exec="talker"/>
    </launch>"""
    spec = evaluate_xml(xml, packages=packages).processes[0]
    assert str(params) in ros_args(spec.cmd)


def test_unknown_executable_names_the_known_ones(
    evaluate_xml: EvaluateXml, packages: PackageIndex
) -> None:
    with pytest.raises(Exception, match="executable 'listener' not found") as caught:
        evaluate_xml('<launch><node pkg="demo" exec="listener"/></launch>', packages=packages)
    assert "talker" in caught.value.format()  # type: ignore[attr-defined]


def test_param_needs_name_or_from(evaluate_xml: EvaluateXml, packages: PackageIndex) -> None:
    with pytest.raises(LaunchFileError, match="'name' or 'from'"):
        evaluate_xml(
            '<launch><node pkg="demo" exec="talker"><param value="1"/></node></launch>',
            packages=packages,
        )


def test_a_param_value_that_is_not_yaml_says_to_pass_it_as_text(
    evaluate_xml: EvaluateXml, packages: PackageIndex
) -> None:
    xml = """<launch><node pkg="demo" exec="talker">
      <param name="description" value="a: b: c"/>
    </node></launch>"""
    with pytest.raises(Exception, match="is not valid YAML") as caught:
        evaluate_xml(xml, packages=packages)
    assert caught.value.format().endswith(  # type: ignore[attr-defined]
        """error: parameter value 'a: b: c' is not valid YAML (expected a YAML value, or """
        """type="str" to pass it as text)"""
    )
    text = xml.replace('value="a: b: c"', 'value="a: b: c" type="str"')
    (spec,) = evaluate_xml(text, packages=packages).processes
    assert params_files(spec.cmd) == [{"/**": {"ros__parameters": {"description": "a: b: c"}}}]
