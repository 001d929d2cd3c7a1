"""Parse-level tests of YAML launch files, one or more per tag: inline YAML in, recorded actions
out. The spelling and the typing of values are ROS's (``launch_yaml``, Jazzy); the expected
values were checked against the real Jazzy launch stack."""

from __future__ import annotations

import itertools
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml

from launchkit.errors import LaunchArgumentError, LaunchFileError
from launchkit.frontend.launch_loader import LaunchLoader
from launchkit.packages import PackageIndex
from tests.conftest import Evaluated, EvaluateXml
from tests.engine.conftest import params_file, ros_args


@pytest.fixture
def evaluate_yaml(evaluate_xml: EvaluateXml) -> EvaluateXml:
    """``evaluate_xml`` for a ``test.launch.yaml`` file."""

    def evaluate(text: str, *args: Any, **kwargs: Any) -> Evaluated:
        kwargs.setdefault("name", "test.launch.yaml")
        return evaluate_xml(text, *args, **kwargs)

    return evaluate


def node_parameters(cmd: list[str]) -> dict[str, Any]:
    """Every parameter a node's command line sets (params files and ``-p``), dotted names."""
    args = ros_args(cmd)
    found: dict[str, Any] = {}

    def flatten(values: dict[str, Any], prefix: str) -> None:
        for key, value in values.items():
            if isinstance(value, dict):
                flatten(value, f"{prefix}{key}.")
            else:
                found[prefix + key] = value

    for flag, value in itertools.pairwise(args):
        if flag == "--params-file":
            for node in yaml.safe_load(Path(value).read_text()).values():
                flatten(node["ros__parameters"], "")
        elif flag == "-p":
            name, _, text = value.partition(":=")
            found[name] = yaml.safe_load(text)
    return found


# -- the root ------------------------------------------------------------------------------------


def test_launch_is_a_list_of_actions(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- log: {message: first}
- log:
    message: second
"""
    assert evaluate_yaml(text).messages() == ["first", "second"]


def test_launch_as_a_mapping_with_children_and_deprecated(tmp_path: Path) -> None:
    path = tmp_path / "old.launch.yaml"
    path.write_text(
        "launch:\n  deprecated: use the other file\n  children:\n  - log: {message: hi}\n"
    )
    description = LaunchLoader().load(path)
    assert description.deprecated == "use the other file"
    assert [type(a).__name__ for a in description.actions] == ["Log"]


# -- launch tags ---------------------------------------------------------------------------------


def test_arg_with_default_description_and_choices(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- arg:
    name: mode
    default: fast
    description: how fast
    choice: [{value: fast}, {value: slow}]
- log: {message: $(var mode)}
"""
    assert evaluate_yaml(text).messages() == ["fast"]
    assert evaluate_yaml(text, {"mode": "slow"}).messages() == ["slow"]
    with pytest.raises(LaunchArgumentError, match=r"'medium'.*fast.*slow"):
        evaluate_yaml(text, {"mode": "medium"})


def test_arg_without_default_is_required(evaluate_yaml: EvaluateXml) -> None:
    with pytest.raises(LaunchArgumentError, match="'needed'"):
        evaluate_yaml("launch:\n- arg: {name: needed}\n")


def test_let_and_substitutions_in_values(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- let: {name: x, value: '1'}
- let: {name: y, value: $(var x)2}
- log: {message: "$(var y) $(eval '2*3') $(env HOME_FOR_TEST) \\\\$(var x)"}
"""
    result = evaluate_yaml(text, env={"HOME_FOR_TEST": "/h"})
    assert result.messages() == ["12 6 /h $(var x)"]


def test_group_as_a_list_and_as_a_mapping(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- let: {name: x, value: outer}
- group:
  - let: {name: x, value: inner}
  - set_env: {name: ONLY_INSIDE, value: '1'}
  - log: {message: "in:$(var x):$(env ONLY_INSIDE '-')"}
- log: {message: "out:$(var x):$(env ONLY_INSIDE '-')"}
- group:
    scoped: false
    children:
    - let: {name: x, value: leaked}
- log: {message: $(var x)}
"""
    assert evaluate_yaml(text).messages() == ["in:inner:1", "out:outer:-", "leaked"]


def test_group_forwarding_false_with_keep(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- let: {name: a, value: A}
- let: {name: b, value: B}
- set_env: {name: OUTER, value: set}
- group:
    forwarding: false
    keep:
    - {name: a, value: $(var a)}
    children:
    - log: {message: "$(var a) $(var b 'no b') $(env OUTER 'no OUTER')"}
"""
    assert evaluate_yaml(text).messages() == ["A no b no OUTER"]


def test_reset_with_keep(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- let: {name: a, value: A}
- let: {name: b, value: B}
- reset:
    keep: [{name: a, value: $(var a)}]
- log: {message: "$(var a) $(var b 'gone')"}
"""
    assert evaluate_yaml(text).messages() == ["A gone"]


def test_if_and_unless(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- arg: {name: enabled, default: 'true'}
- log: {message: shown, if: $(var enabled)}
- log: {message: hidden, unless: $(var enabled)}
- group:
    if: 'false'
    children:
    - log: {message: never}
"""
    assert evaluate_yaml(text).messages() == ["shown"]


def test_include_yaml_and_xml_with_args(evaluate_yaml: EvaluateXml, tmp_path: Path) -> None:
    (tmp_path / "child.launch.yaml").write_text(
        "launch:\n- arg: {name: who}\n- let: {name: leaked, value: 'yes'}\n"
        "- log: {message: yaml child $(var who)}\n"
    )
    (tmp_path / "child.launch.xml").write_text(
        '<launch><arg name="who"/><log message="xml child $(var who)"/></launch>'
    )
    text = """
launch:
- include:
    file: $(dirname)/child.launch.yaml
    arg: [{name: who, value: one}]
- include:
    file: $(dirname)/child.launch.xml
    arg:
    - name: who
      value: two
- log: {message: "include is not scoped: $(var leaked)"}
"""
    assert evaluate_yaml(text).messages() == [
        "yaml child one",
        "xml child two",
        "include is not scoped: yes",
    ]


def test_xml_includes_yaml(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    (tmp_path / "child.launch.yaml").write_text(
        "launch:\n- arg: {name: who}\n- log: {message: hello $(var who)}\n"
    )
    xml = """<launch>
      <include file="$(dirname)/child.launch.yaml"><arg name="who" value="xml"/></include>
    </launch>"""
    assert evaluate_xml(xml).messages() == ["hello xml"]


def test_executable_with_every_key(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- executable:
    cmd: echo 'a b' c
    cwd: /tmp
    name: speaker
    shell: false
    output: screen
    emulate_tty: true
    sigterm_timeout: 1.5
    sigkill_timeout: 2.0
    respawn: 'true'
    respawn_delay: 0.5
    respawn_max_retries: 3
    launch-prefix: nice -n 5
    on_exit: shutdown
    env:
    - {name: EXTRA, value: '1'}
    - {name: OTHER, value: $(var x 'dflt')}
"""
    spec = evaluate_yaml(text).process("speaker")
    assert spec.cmd == ["nice", "-n", "5", "echo", "a b", "c"]
    assert spec.cwd == "/tmp" and spec.output == "screen" and spec.emulate_tty
    assert (spec.sigterm_timeout, spec.sigkill_timeout) == (1.5, 2.0)
    assert spec.respawn and spec.respawn_delay == 0.5 and spec.respawn_max_retries == 3
    assert spec.on_exit_shutdown
    assert spec.env["EXTRA"] == "1" and spec.env["OTHER"] == "dflt"


def test_timer_with_float_or_text_period(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- timer:
    period: 2.5
    cancel_on_shutdown: false
    children:
    - log: {message: later}
- let: {name: p, value: '0.5'}
- timer: {period: $(var p), children: [{log: {message: sooner}}]}
"""
    result = evaluate_yaml(text)
    timers = [item for item in result.items if item.kind == "timer"]
    assert [t.delay for t in timers] == [2.5, 0.5]
    assert result.messages() == ["later", "sooner"]


def test_environment_tags(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- set_env: {name: A, value: a}
- append_env: {name: A, value: b}
- append_env: {name: A, value: z, prepend: true, separator: ','}
- unset_env: {name: GONE}
- log: {message: "$(env A) $(env GONE 'unset')"}
- reset_env: {}
- log: {message: "$(env A 'reset') $(env GONE)"}
"""
    result = evaluate_yaml(text, env={"GONE": "back", "PATH": "/bin"})
    assert result.messages() == ["z,a:b unset", "reset back"]


def test_log_and_shutdown(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- log: {message: bye, level: WARNING}
- shutdown: {reason: done here}
"""
    result = evaluate_yaml(text)
    assert result.logs[0].startswith("[WARNING]")
    assert [(item.kind, item.text) for item in result.items][1] == ("shutdown", "done here")


# -- launch_ros tags -----------------------------------------------------------------------------


def test_node_with_every_key(evaluate_yaml: EvaluateXml, packages: PackageIndex) -> None:
    text = """
launch:
- node:
    pkg: demo
    exec: talker
    name: chatter
    namespace: robot
    args: --flag 'a b'
    ros_args: --log-level debug
    output: screen
    remap:
    - {from: cmd_vel, to: /robot/cmd_vel}
    env:
    - {name: EXTRA, value: '1'}
"""
    spec = evaluate_yaml(text, packages=packages).processes[0]
    assert spec.cmd[:5] == [sys.executable, "-m", "demo.talker", "--flag", "a b"]
    args = ros_args(spec.cmd)
    assert args[:2] == ["--log-level", "debug"]
    assert "__node:=chatter" in args and "__ns:=/robot" in args
    assert "cmd_vel:=/robot/cmd_vel" in args
    assert spec.is_node and spec.output == "screen" and spec.env["EXTRA"] == "1"


def test_node_exec_name(evaluate_yaml: EvaluateXml, packages: PackageIndex) -> None:
    text = "launch:\n- node: {pkg: demo, exec: talker, exec_name: speaker}\n"
    assert evaluate_yaml(text, packages=packages).processes[0].name == "speaker"


def test_param_values_keep_their_yaml_types(
    evaluate_yaml: EvaluateXml, packages: PackageIndex
) -> None:
    # The typing ROS gives each spelling (observed with the real Jazzy stack): a quoted string
    # without substitutions stays a string; with substitutions it is typed by YAML's rules.
    text = """
launch:
- let: {name: rate, value: '1.5'}
- node:
    pkg: demo
    exec: talker
    param:
    - {name: f, value: 1.5}
    - {name: i, value: 3}
    - {name: b, value: true}
    - {name: s, value: '1.5'}
    - {name: sb, value: 'true'}
    - {name: subst, value: $(var rate)}
    - {name: l, value: [1, 2, 3]}
    - {name: ls, value: [a, '1']}
    - {name: empty, value: []}
    - {name: li, type: list_of_int, value: [1, 2]}
    - {name: lf, type: list_of_float, value: [1.0, 2.5]}
    - {name: fl, type: float, value: 2.0}
    - {name: t, type: str, value: '7'}
    - {name: yam, type: yaml, value: '{a: 1}'}
    - {name: ti, type: int, value: $(var count 4)}
    - name: wheel
      param:
      - {name: radius, value: 0.1}
      - {name: side, param: [{name: name, value: left}]}
"""
    spec = evaluate_yaml(text, packages=packages).processes[0]
    assert node_parameters(spec.cmd) == {
        "f": 1.5,
        "i": 3,
        "b": True,
        "s": "1.5",
        "sb": "true",
        "subst": 1.5,
        "l": [1, 2, 3],
        "ls": ["a", "1"],
        "empty": [],
        "li": [1, 2],
        "lf": [1.0, 2.5],
        "fl": 2.0,
        "t": "7",
        "yam": "{a: 1}",
        "ti": 4,
        "wheel.radius": 0.1,
        "wheel.side.name": "left",
    }


def test_list_items_with_substitutions_are_typed_when_performed(
    evaluate_yaml: EvaluateXml, packages: PackageIndex
) -> None:
    text = """
launch:
- let: {name: a, value: x}
- let: {name: n, value: '2'}
- node:
    pkg: demo
    exec: talker
    param:
    - {name: words, value: [$(var a), 'b, c']}
    - {name: numbers, value: [1, $(var n)]}
"""
    spec = evaluate_yaml(text, packages=packages).processes[0]
    params = node_parameters(spec.cmd)
    assert params["words"] == ["x", "b, c"]
    assert params["numbers"] == [1, 2]


def test_param_from_file(
    evaluate_yaml: EvaluateXml, packages: PackageIndex, tmp_path: Path
) -> None:
    params = params_file(tmp_path / "params.yaml", "a: $(var v)")
    text = f"""
launch:
- let: {{name: v, value: '5'}}
- node:
    pkg: demo
    exec: talker
    param:
    - {{from: {params}}}
    - {{from: {params}, allow_substs: true}}
"""
    spec = evaluate_yaml(text, packages=packages).processes[0]
    args = ros_args(spec.cmd)
    files = [args[i + 1] for i, arg in enumerate(args) if arg == "--params-file"]
    assert files[0] == str(params)
    assert yaml.safe_load(Path(files[1]).read_text()) == {"/**": {"ros__parameters": {"a": 5}}}


def test_ros_scope_tags(evaluate_yaml: EvaluateXml, packages: PackageIndex, tmp_path: Path) -> None:
    params = params_file(tmp_path / "global.yaml", "g: 2")
    text = f"""
launch:
- group:
  - push_ros_namespace: {{namespace: outer}}
  - push-ros-namespace: {{namespace: inner}}
  - set_parameter: {{name: robot, value: wheel}}
  - set_parameters_from_file: {{filename: {params}}}
  - set_remap: {{from: scan, to: /base_scan}}
  - set_use_sim_time: {{value: 'true'}}
  - node: {{pkg: demo, exec: talker, exec_name: inside}}
- node: {{pkg: demo, exec: talker, exec_name: outside}}
"""
    result = evaluate_yaml(text, packages=packages)
    inside = result.process("inside").cmd
    args = ros_args(inside)
    assert "__ns:=/outer/inner" in args and "scan:=/base_scan" in args
    assert str(params) in args
    parameters = node_parameters(inside)
    assert parameters["robot"] == "wheel" and parameters["use_sim_time"] is True
    assert result.process("outside").cmd[3:] == ["--ros-args"]  # always, as launch_ros writes it


# -- YAML itself ---------------------------------------------------------------------------------


def test_anchors_aliases_and_merge_keys(evaluate_yaml: EvaluateXml) -> None:
    text = """
launch:
- executable: &base {cmd: 'true', name: first, output: screen}
- executable: {<<: *base, name: second}
- executable:
    <<: *base
    env: &env [{name: E, value: '1'}]
    name: third
- group:
  - executable: {cmd: 'true', name: fourth, env: *env}
"""
    result = evaluate_yaml(text)
    assert [p.name for p in result.processes] == ["first", "second", "third", "fourth"]
    assert all(p.output == "screen" for p in result.processes[:3])
    assert result.process("fourth").env["E"] == "1"


def test_launch_extension_is_read_as_yaml_when_it_is_not_xml(evaluate_xml: EvaluateXml) -> None:
    # ROS tries a *.launch file with every frontend; launchkit looks at its first character.
    assert evaluate_xml("launch:\n- log: {message: yaml}\n", name="x.launch").messages() == ["yaml"]
    assert evaluate_xml('<launch><log message="xml"/></launch>', name="y.launch").messages() == [
        "xml"
    ]


def test_errors_name_the_key_with_its_line_and_column(evaluate_yaml: EvaluateXml) -> None:
    text = "launch:\n- log:\n    message: hi\n    colour: red\n"
    with pytest.raises(LaunchFileError) as caught:
        evaluate_yaml(text)
    error = caught.value
    assert (error.location.line, error.location.col) == (4, 5)  # type: ignore[union-attr]
    assert error.message == "unknown key 'colour' on 'log'"
    assert error.expected == "one of: if, level, message, unless"
