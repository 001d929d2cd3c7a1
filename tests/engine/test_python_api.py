"""Parse-level tests of the Python launch API: each class and function a ``*.launch.py`` of
ROS 2 Jazzy imports, evaluated with the ``--print`` recorder (no process starts)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import yaml

from launchkit.errors import LaunchFileError, LaunchkitError
from launchkit.frontend.python.modules import stand_in_modules
from launchkit.packages import PackageIndex, PythonPackage
from tests.conftest import EvaluateXml

HEADER = """\
import os
import sys
from launch import LaunchDescription
from launch.actions import *
from launch.substitutions import *
from launch.conditions import *
from launch_ros.actions import *
from launch_ros.substitutions import *
from launch_ros.parameter_descriptions import ParameterValue, ParameterFile
"""

#: Every name of ``launch.substitutions`` and ``launch_ros.substitutions`` in Jazzy (their
#: ``__init__.py`` files, launch 3.4.3 and launch_ros 0.26.6).
JAZZY_SUBSTITUTIONS = {
    "launch.substitutions": [
        "AllSubstitution", "AndSubstitution", "AnySubstitution", "AnonName", "Command",
        "EqualsSubstitution", "EnvironmentVariable", "FileContent", "FindExecutable",
        "IfElseSubstitution", "LaunchConfiguration", "LaunchLogDir", "LocalSubstitution",
        "NotSubstitution", "NotEqualsSubstitution", "OrSubstitution", "PathJoinSubstitution",
        "PythonExpression", "SubstitutionFailure", "TextSubstitution", "ThisLaunchFile",
        "ThisLaunchFileDir",
    ],
    "launch_ros.substitutions": [
        "ExecutableInPackage", "FindPackage", "FindPackagePrefix", "FindPackageShare", "Parameter",
    ],
}  # fmt: skip


def launch_file(body: str) -> str:
    """A launch file returning ``LaunchDescription([<body>])``."""
    function = "def generate_launch_description():\n    return LaunchDescription([\n"
    return f"{HEADER}\n{function}{body}\n    ])\n"


@pytest.fixture
def demo(tmp_path: Path) -> PackageIndex:
    """A package index with one Python package ``demo`` (executable ``talker``)."""
    share = tmp_path / "demo_share"
    share.mkdir()
    installed = dict(PackageIndex(ament_prefix_path="").python_packages())
    installed["demo"] = PythonPackage("demo", share, {"talker": "demo.talker"})
    return PackageIndex(ament_prefix_path="", python_packages=installed)


def ros_args(cmd: list[str]) -> list[str]:
    """What follows the last ``--ros-args``."""
    return cmd[len(cmd) - cmd[::-1].index("--ros-args") :]


def params_of(cmd: list[str]) -> dict[str, object]:
    """The parameters the ``--params-file`` files of a command line give, merged."""
    merged: dict[str, object] = {}
    args = ros_args(cmd)
    for i, arg in enumerate(args):
        if arg == "--params-file":
            document = yaml.safe_load(Path(args[i + 1]).read_text())
            merged.update(document["/**"]["ros__parameters"])
    return merged


# -- the modules -------------------------------------------------------------------------------


def test_every_jazzy_substitution_is_provided() -> None:
    modules = stand_in_modules()
    missing = [
        f"{module}.{name}"
        for module, names in JAZZY_SUBSTITUTIONS.items()
        for name in names
        if name not in vars(modules[module])
    ]
    assert missing == []


def test_the_ways_of_importing(evaluate_xml: EvaluateXml) -> None:
    code = """
import ament_index_python.packages
import launch.actions as actions
from ament_index_python import get_package_share_directory
from launch import LaunchDescription


def generate_launch_description():
    share = ament_index_python.packages.get_package_share_directory('robot_wheel')
    return LaunchDescription([
        actions.LogInfo(msg=share),
        actions.LogInfo(msg=get_package_share_directory('robot_wheel')),
    ])
"""
    share = str(PackageIndex().share_dir("robot_wheel"))
    assert evaluate_xml(code, name="imports.launch.py").messages() == [share, share]


@pytest.mark.parametrize(
    ("code", "name", "line"),
    [
        ("from launch.actions import LogInfo, NoSuchAction\n", "launch.actions.NoSuchAction", 1),
        ("import launch_ros.actions\n\nlaunch_ros.actions.Nope()\n", "launch_ros.actions.Nope", 3),
        ("import launch\nlaunch.substitutions.Bogus\n", "launch.substitutions.Bogus", 2),
    ],
)  # fmt: skip
def test_a_missing_name_is_named_with_its_line(
    evaluate_xml: EvaluateXml, code: str, name: str, line: int
) -> None:
    with pytest.raises(LaunchFileError, match=rf"{name} is not provided by launchkit") as caught:
        evaluate_xml(code + "def generate_launch_description():\n    pass\n", name="m.launch.py")
    assert caught.value.location is not None and caught.value.location.line == line


# -- substitutions -----------------------------------------------------------------------------


def test_path_join_starts_over_at_an_absolute_part(evaluate_xml: EvaluateXml) -> None:
    body = """
        LogInfo(msg=PathJoinSubstitution(['a', 'b', 'c.yaml'])),
        LogInfo(msg=PathJoinSubstitution(['a', '/etc', 'c.yaml'])),
        LogInfo(msg=PathJoinSubstitution(['a', ''])),
        LogInfo(msg=PathJoinSubstitution(
            [EnvironmentVariable('BASE'), ['x_', LaunchConfiguration('n')]])),
    """
    result = evaluate_xml(launch_file(body), {"n": "7"}, env={"BASE": "/opt"}, name="p.launch.py")
    assert result.messages() == ["a/b/c.yaml", "/etc/c.yaml", "a/", "/opt/x_7"]


def test_comparisons_and_choices(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    (tmp_path / "motto.txt").write_text("keep going\n")
    body = f"""
        LogInfo(msg=NotEqualsSubstitution(LaunchConfiguration('a'), 'x')),
        LogInfo(msg=NotEqualsSubstitution('1.0', 1)),
        LogInfo(msg=EqualsSubstitution(True, 'true')),
        LogInfo(msg=IfElseSubstitution(LaunchConfiguration('flag'), 'on', 'off')),
        LogInfo(msg=AllSubstitution('true', '1', LaunchConfiguration('flag'))),
        LogInfo(msg=AnySubstitution('false', '0', LaunchConfiguration('flag'))),
        LogInfo(msg=FileContent(['{tmp_path}/', 'motto.txt'])),
        LogInfo(msg=TextSubstitution(text='plain')),
    """
    result = evaluate_xml(launch_file(body), {"a": "y", "flag": "no"}, name="c.launch.py")
    assert result.messages() == [
        "true", "false", "true", "off", "false", "false", "keep going\n", "plain",
    ]  # fmt: skip


def test_log_dir_file_and_anonymous_names(evaluate_xml: EvaluateXml, tmp_path: Path) -> None:
    body = """
        LogInfo(msg=LaunchLogDir()),
        LogInfo(msg=ThisLaunchFile()),
        LogInfo(msg=ThisLaunchFileDir()),
        LogInfo(msg=AnonName('talker')),
        LogInfo(msg=AnonName('talker')),
        LogInfo(msg=FindExecutable(name='sh')),
        LogInfo(msg=PythonExpression(['2 * ', LaunchConfiguration('n')])),
    """
    logs = evaluate_xml(launch_file(body), {"n": "21"}, name="l.launch.py").messages()
    assert logs[:3] == [str(tmp_path / "log"), str(tmp_path / "l.launch.py"), str(tmp_path)]
    assert logs[3].startswith("talker_") and logs[3] == logs[4]
    assert logs[5] == "/usr/bin/sh" or logs[5] == "/bin/sh"
    assert logs[6] == "42"


def test_launch_ros_substitutions(evaluate_xml: EvaluateXml, demo: PackageIndex) -> None:
    body = """
        SetParameter(name='robot', value='wheel'),
        LogInfo(msg=FindPackageShare('demo')),
        LogInfo(msg=FindPackagePrefix('demo')),
        LogInfo(msg=ExecutableInPackage('talker', 'demo')),
        LogInfo(msg=Parameter('robot')),
        LogInfo(msg=FindPackageShare('robot_wheel').find('robot_wheel')),
    """
    code = launch_file(body).replace(
        "from launch_ros.parameter_descriptions", "from launch_ros.substitutions import Parameter\n"
        "from launch_ros.parameter_descriptions",
    )  # fmt: skip
    logs = evaluate_xml(code, name="r.launch.py", packages=demo).messages()
    share = str(demo.share_dir("demo"))
    assert logs[:2] == [share, share]
    assert logs[2] == f"{sys.executable} -m demo.talker"  # a Python package runs python -m
    assert logs[3:] == ["wheel", str(PackageIndex().share_dir("robot_wheel"))]


def test_a_custom_substitution_class(evaluate_xml: EvaluateXml) -> None:
    code = """
from launch import LaunchDescription, Substitution
from launch.actions import LogInfo


class Upper(Substitution):
    def __init__(self, text):
        super().__init__()
        self.text = text

    def perform(self, context):
        return context.launch_configurations['who'].upper() + self.text


def generate_launch_description():
    return LaunchDescription([LogInfo(msg=['hello ', Upper('!')])])
"""
    assert evaluate_xml(code, {"who": "ada"}, name="u.launch.py").messages() == ["hello ADA!"]


# -- actions -----------------------------------------------------------------------------------


def test_group_launch_configurations(evaluate_xml: EvaluateXml) -> None:
    body = """
        SetLaunchConfiguration('outer', 'o'),
        GroupAction([LogInfo(msg=[LaunchConfiguration('g'), LaunchConfiguration('outer')])],
                    launch_configurations={'g': 'G'}),
        GroupAction(
            [LogInfo(msg=[LaunchConfiguration('g'), LaunchConfiguration('outer', default='-')])],
            forwarding=False, launch_configurations={'g': 'H'}),
        LogInfo(msg=LaunchConfiguration('g', default='unset')),
    """
    assert evaluate_xml(launch_file(body), name="g.launch.py").messages() == [
        "Go", "H-", "unset",
    ]  # fmt: skip


def test_push_pop_and_unset_configurations(evaluate_xml: EvaluateXml) -> None:
    body = """
        SetLaunchConfiguration('a', '1'),
        PushLaunchConfigurations(),
        SetLaunchConfiguration('a', '2'),
        LogInfo(msg=LaunchConfiguration('a')),
        PopLaunchConfigurations(),
        LogInfo(msg=LaunchConfiguration('a')),
        UnsetLaunchConfiguration('a'),
        LogInfo(msg=LaunchConfiguration('a', default='gone')),
        PushEnvironment(),
        SetEnvironmentVariable('E', 'x'),
        PopEnvironment(),
        LogInfo(msg=EnvironmentVariable('E', default_value='no E')),
    """
    assert evaluate_xml(launch_file(body), name="pp.launch.py").messages() == [
        "2", "1", "gone", "no E",
    ]  # fmt: skip


def test_execute_process_env_is_the_whole_environment(evaluate_xml: EvaluateXml) -> None:
    body = """
        ExecuteProcess(cmd=['env'], name='clean', env={'ONLY': '1'}, additional_env={'MORE': '2'}),
        ExecuteProcess(cmd=['env'], name='inherits', additional_env={'MORE': '2'}),
    """
    result = evaluate_xml(launch_file(body), env={"PATH": "/bin", "KEEP": "k"}, name="e.launch.py")
    assert result.process("clean").env == {"ONLY": "1", "MORE": "2", "PYTHONUNBUFFERED": "1"}
    assert result.process("inherits").env["KEEP"] == "k"


def test_execute_process_words_are_argv_items(evaluate_xml: EvaluateXml) -> None:
    body = """
        ExecuteProcess(cmd=['printf', "it's %s", '', LaunchConfiguration('w')], name='p'),
        ExecuteProcess(cmd=['echo', 'a  b', LaunchConfiguration('w')], shell=True, name='s'),
    """
    result = evaluate_xml(launch_file(body), {"w": "two words"}, name="w.launch.py")
    assert result.process("p").cmd == ["printf", "it's %s", "", "two words"]
    assert result.process("s").cmd == ["/bin/sh", "-c", "echo a  b two words"]


def test_a_program_called_by_bare_name_runs_the_stand_in(evaluate_xml: EvaluateXml) -> None:
    body = """
        ExecuteProcess(cmd=['gazebo', '--verbose', '-s', 'libgazebo_ros_init.so'], output='screen'),
        ExecuteProcess(cmd=['gzclient']),
    """
    result = evaluate_xml(launch_file(body), env={"PATH": "/nonexistent"}, name="gz.launch.py")
    server, client = result.processes
    assert server.cmd == [
        sys.executable, "-m", "launchkit.stock.gazebo_ros.gzserver", "--verbose", "-s",
        "libgazebo_ros_init.so",
    ]  # fmt: skip
    assert server.name == "gazebo" and server.is_node
    assert client.cmd == [sys.executable, "-m", "launchkit.stock.gazebo_ros.gzclient"]
    assert result.messages()[0] == (
        "'gazebo' is not installed: running launchkit's stand-in from package 'gazebo_ros' "
        "in its place"
    )


def test_ros_scope_actions_reach_the_node(
    evaluate_xml: EvaluateXml, demo: PackageIndex, tmp_path: Path
) -> None:
    params = tmp_path / "all.yaml"
    params.write_text("/**:\n  ros__parameters:\n    g: 2\n")
    body = f"""
        GroupAction([
            PushRosNamespace('robot1'),
            SetRemap(src='scan', dst='base_scan'),
            SetParametersFromFile('{params}'),
            SetUseSimTime(True),
            Node(package='demo', executable='talker', name='t', namespace='sub'),
        ]),
        Node(package='demo', executable='talker', name='u'),
    """
    inside, outside = evaluate_xml(launch_file(body), name="s.launch.py", packages=demo).processes
    args = ros_args(inside.cmd)
    assert "__ns:=/robot1/sub" in args and "scan:=base_scan" in args and str(params) in args
    assert "use_sim_time" not in " ".join(args)  # Jazzy's SetUseSimTime is the launch's clock
    assert "__ns:=/robot1/sub" not in ros_args(outside.cmd)


def test_parameter_typing_follows_launch_ros(
    evaluate_xml: EvaluateXml, demo: PackageIndex, tmp_path: Path
) -> None:
    with_substs = tmp_path / "substs.yaml"
    with_substs.write_text("/**:\n  ros__parameters:\n    who: $(var who)\n")
    body = f"""
        Node(package='demo', executable='talker', parameters=[{{
            'as_text': '5',
            'number': 5,
            'ratio': 0.5,
            'flag': LaunchConfiguration('flag'),
            'forced': ParameterValue(LaunchConfiguration('n'), value_type=str),
            'joined': ['a', LaunchConfiguration('n')],
            'names': [['x', LaunchConfiguration('n')], ['y']],
            'floats': [1, 2.5],
            'nested': {{'inner': True}},
        }}, ParameterFile('{with_substs}', allow_substs=True)]),
    """
    spec = evaluate_xml(
        launch_file(body), {"flag": "true", "n": "7", "who": "me"}, name="t.launch.py",
        packages=demo,
    ).processes[0]  # fmt: skip
    assert params_of(spec.cmd) == {
        "as_text": "5", "number": 5, "ratio": 0.5, "flag": True, "forced": "7", "joined": "a7",
        "names": ["x7", "y"], "floats": [1.0, 2.5], "nested.inner": True, "who": "me",
    }  # fmt: skip


def test_opaque_function_builds_actions_when_reached(
    evaluate_xml: EvaluateXml, demo: PackageIndex
) -> None:
    code = f"""{HEADER}

def launch_setup(context, prefix, *, suffix):
    robot = LaunchConfiguration('robot').perform(context)
    count = int(context.launch_configurations['count'])
    return [LogInfo(msg=f'{{prefix}}{{robot}}{{suffix}}')] + [
        Node(package='demo', executable='talker', name=f'{{robot}}_{{i}}') for i in range(count)
    ]


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('robot', default_value='r'),
        SetLaunchConfiguration('count', '2'),
        OpaqueFunction(function=launch_setup, args=['<'], kwargs={{'suffix': '>'}}),
    ])
"""
    result = evaluate_xml(code, {"robot": "bot"}, name="o.launch.py", packages=demo)
    assert result.messages() == ["<bot>"]
    assert [ros_args(p.cmd)[1] for p in result.processes] == ["__node:=bot_0", "__node:=bot_1"]
    assert result.processes[0].location is not None
    first = "    return [LogInfo(msg=f'{prefix}{robot}{suffix}')] + ["
    built_at = code.splitlines().index(first) + 2
    assert result.processes[0].location.line == built_at  # the line in launch_setup


def test_opaque_function_failure_names_function_file_and_line(
    evaluate_xml: EvaluateXml,
) -> None:
    code = (
        "from launch import LaunchDescription\n"
        "from launch.actions import OpaqueFunction\n"
        "\n"
        "def setup(context):\n"
        "    table = {}\n"
        "    return table['robot']\n"
        "\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([OpaqueFunction(function=setup)])\n"
    )
    with pytest.raises(LaunchkitError) as caught:
        evaluate_xml(code, name="bad.launch.py")
    assert caught.value.message == "OpaqueFunction setup() raised KeyError: 'robot'"
    assert caught.value.location is not None
    assert caught.value.location.file.endswith("bad.launch.py")
    assert caught.value.location.line == 6


def test_event_handlers_show_what_they_would_do(evaluate_xml: EvaluateXml) -> None:
    code = f"""{HEADER}
from launch.event_handlers import OnProcessExit, OnShutdown
from launch.events import Shutdown as ShutdownEvent


def generate_launch_description():
    first = ExecuteProcess(cmd=['true'], name='first')
    return LaunchDescription([
        first,
        RegisterEventHandler(OnProcessExit(target_action=first, on_exit=[
            LogInfo(msg=['first exited with ', LocalSubstitution('event.returncode')]),
            ExecuteProcess(cmd=['true'], name='second'),
            EmitEvent(event=ShutdownEvent(reason='done')),
        ])),
        RegisterEventHandler(OnShutdown(on_shutdown=lambda event, context: None)),
    ])
"""
    result = evaluate_xml(code, name="h.launch.py")
    kinds = [(item.kind, item.text) for item in result.items]
    assert kinds[1:] == [
        ("handler", "OnProcessExit(target_action=first)"),
        ("handler", "OnShutdown"),
    ]
    assert [p.name for p in result.processes] == ["first", "second"]
    assert result.messages() == ["first exited with <event.returncode>"]
    assert result.items[1].inner[-1].kind == "shutdown"


def test_event_handler_arguments_are_checked(evaluate_xml: EvaluateXml) -> None:
    code = f"""{HEADER}
from launch.event_handlers import OnProcessExit


def generate_launch_description():
    return LaunchDescription([
        RegisterEventHandler(OnProcessExit(on_start=[LogInfo(msg='x')])),
    ])
"""
    with pytest.raises(LaunchFileError, match="OnProcessExit got on_start") as caught:
        evaluate_xml(code, name="ha.launch.py")
    line = next(i for i, text in enumerate(code.splitlines(), 1) if "on_start=" in text)
    assert caught.value.location is not None and caught.value.location.line == line


def test_composable_nodes_and_lifecycle_nodes_in_print(
    evaluate_xml: EvaluateXml, demo: PackageIndex
) -> None:
    code = f"""{HEADER}
from launch_ros.descriptions import ComposableNode


def generate_launch_description():
    container = ComposableNodeContainer(
        name='my_container', namespace='', package='rclcpp_components',
        executable='component_container',
        composable_node_descriptions=[
            ComposableNode(package='composition', plugin='composition::Talker', name='talker',
                           parameters=[{{'rate': 2}}]),
        ])
    return LaunchDescription([
        PushRosNamespace('robot'),
        container,
        LoadComposableNodes(target_container='my_container', composable_node_descriptions=[
            ComposableNode(package='composition', plugin='composition::Listener',
                           namespace='ears', condition=IfCondition('false')),
            ComposableNode(package='composition', plugin='composition::Listener'),
        ]),
        LifecycleNode(package='demo', executable='talker', name='lc', namespace=''),
    ])
"""
    result = evaluate_xml(code, name="comp.launch.py", packages=demo)
    container, lifecycle = result.processes
    assert ros_args(container.cmd)[:4] == ["-r", "__node:=my_container", "-r", "__ns:=/robot"]
    assert result.messages() == [
        "load composition::Talker (composition) as /robot/talker into /robot/my_container",
        "load composition::Listener (composition) as its default name into /my_container",
    ]
    assert "__node:=lc" in ros_args(lifecycle.cmd)


def test_xml_composition_tags(evaluate_xml: EvaluateXml) -> None:
    xml = """<launch>
      <node_container pkg="rclcpp_components" exec="component_container" name="box" namespace="">
        <composable_node pkg="composition" plugin="composition::Talker" name="talker">
          <param name="rate" value="2"/>
          <remap from="chatter" to="/news"/>
          <extra_arg name="use_intra_process_comms" value="true"/>
        </composable_node>
      </node_container>
      <load_composable_node target="/box">
        <composable_node pkg="composition" plugin="composition::Listener" name="l" if="false"/>
      </load_composable_node>
    </launch>"""
    result = evaluate_xml(xml)
    assert [p.name for p in result.processes] == ["component_container"]
    assert result.messages() == ["load composition::Talker (composition) as /talker into /box"]
    bad = xml.replace('name="rate"', 'nam="rate"')
    with pytest.raises(LaunchFileError, match="nam"):
        evaluate_xml(bad)


def test_lifecycle_transition_arguments_are_checked(evaluate_xml: EvaluateXml) -> None:
    code = f"""{HEADER}


def generate_launch_description():
    return LaunchDescription([LifecycleTransition(lifecycle_node_names=['a'], transition_ids=[])])
"""
    with pytest.raises(LaunchFileError, match="LifecycleTransition needs"):
        evaluate_xml(code, name="lt.launch.py")
