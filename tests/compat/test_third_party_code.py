"""Third-party launch code written against ROS's ``launch`` API runs as under Jazzy: a
``launch.Substitution`` subclass written the standard way (as nav2_common's ``RewrittenYaml``),
``launch.utilities`` and its ``type_utils``, conditions evaluated by user code, and includes
under a false condition that fail to load.

Every expectation was recorded from the real launch (``ros2_launch.py`` of the reference tools:
launch 3.4.3, launch_ros 0.26.6) on the same files; each test names its run.
"""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

from tests.compat.conftest import run_launch, stub_prefix

UTILITIES = '''\
import launch
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, LogInfo, OpaqueFunction
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import LaunchConfiguration, TextSubstitution
from launch.utilities import (ensure_argument_type, is_a, is_a_subclass,
                              normalize_to_list_of_substitutions, perform_substitutions)
from launch.utilities.type_utils import (coerce_to_type, get_typed_value, is_substitution,
                                         normalize_typed_substitution,
                                         perform_typed_substitution)


class Joined(launch.Substitution):
    """Written the way nav2_common writes its substitutions."""

    def __init__(self, parts, separator):
        super().__init__()
        self.__parts = normalize_to_list_of_substitutions(parts)
        self.__separator = normalize_to_list_of_substitutions(separator)

    def describe(self):
        return 'Joined'

    def perform(self, context):
        separator = perform_substitutions(context, self.__separator)
        return separator.join(perform_substitutions(context, [p]) for p in self.__parts)


def report(context):
    name = LaunchConfiguration('name')
    lines = [
        'normalized: ' + ' '.join(type(s).__name__ for s in
                                  normalize_to_list_of_substitutions(['a', name])),
        'one: ' + ' '.join(type(s).__name__ for s in normalize_to_list_of_substitutions(name)),
        'text: ' + ' '.join(type(s).__name__ for s in normalize_to_list_of_substitutions('t')),
        'is a Substitution: %s %s' % (isinstance(name, launch.Substitution),
                                      is_a(name, launch.Substitution)),
        'is_a_subclass: %s %s' % (is_a_subclass(LaunchConfiguration, launch.Substitution),
                                  is_a_subclass(5, str)),
        'performed: ' + perform_substitutions(context, [TextSubstitution(text='<'), name]),
        'joined: ' + Joined(['x', name, TextSubstitution(text='z')], '+').perform(context),
        'if: %s unless: %s' % (IfCondition(LaunchConfiguration('flag')).evaluate(context),
                               UnlessCondition('1').evaluate(context)),
        'typed: %r' % (perform_typed_substitution(
            context, normalize_typed_substitution(['1', LaunchConfiguration('num')], None), None),),
        'typed list: %r' % (perform_typed_substitution(
            context, normalize_typed_substitution([1, [LaunchConfiguration('num')]], None), None),),
        'coerce: %r %r %r' % (coerce_to_type('1', bool), coerce_to_type('2.5'),
                              get_typed_value(['1', '2'], None)),
        'is_substitution: %s %s %s' % (is_substitution([name, 'a']), is_substitution('a'),
                                       is_substitution([])),
    ]
    for check in [lambda: ensure_argument_type(5, str, 'value', 'report'),
                  lambda: ensure_argument_type('x', [int, float], 'value'),
                  lambda: normalize_to_list_of_substitutions([5]),
                  lambda: coerce_to_type('abc', int)]:
        try:
            check()
            lines.append('no error')
        except (TypeError, ValueError) as error:
            lines.append('%s: %s' % (type(error).__name__, error))
    return [LogInfo(msg=line) for line in lines]


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('name', default_value='robot'),
        DeclareLaunchArgument('flag', default_value='true'),
        DeclareLaunchArgument('num', default_value='3'),
        OpaqueFunction(function=report),
        LogInfo(msg=['joined as an argument: ',
                     Joined([LaunchConfiguration('name'), 'b'], TextSubstitution(text='/'))]),
        LogInfo(msg='predicate condition held',
                condition=launch.Condition(
                    predicate=lambda context: context.launch_configurations['flag'] == 'true')),
        LogInfo(msg='never shown', condition=launch.Condition()),
    ])
'''

# `ros2 launch utilities.launch.py` (reference run 2026-11-29, launch 3.4.3), its lines after
# "Default logging verbosity is set to INFO"
UTILITIES_EXPECTED = """\
[INFO] [launch.user]: normalized: TextSubstitution LaunchConfiguration
[INFO] [launch.user]: one: LaunchConfiguration
[INFO] [launch.user]: text: TextSubstitution
[INFO] [launch.user]: is a Substitution: True True
[INFO] [launch.user]: is_a_subclass: True False
[INFO] [launch.user]: performed: <robot
[INFO] [launch.user]: joined: x+robot+z
[INFO] [launch.user]: if: True unless: False
[INFO] [launch.user]: typed: 13
[INFO] [launch.user]: typed list: [1, 3]
[INFO] [launch.user]: coerce: True 2.5 [1, 2]
[INFO] [launch.user]: is_substitution: True False False
[INFO] [launch.user]: TypeError: 'report' expected 'value' to be one of [<class 'str'>], \
but got '5' of type '<class 'int'>'
[INFO] [launch.user]: TypeError: Expected 'value' to be one of [<class 'int'>, <class 'float'>], \
but got 'x' of type '<class 'str'>'
[INFO] [launch.user]: TypeError: Failed to normalize given item of type '<class 'int'>', when \
only 'str' or 'launch.Substitution' were expected.
[INFO] [launch.user]: ValueError: invalid literal for int() with base 10: 'abc'
[INFO] [launch.user]: joined as an argument: robot/b
[INFO] [launch.user]: predicate condition held"""


def test_launch_utilities_and_a_standard_substitution_class(launch_dir: Path) -> None:
    (launch_dir / "utilities.launch.py").write_text(UTILITIES)
    ran = run_launch(launch_dir, "utilities.launch.py")
    assert ran.status == 0, ran.text
    assert ran.launch_lines() == UTILITIES_EXPECTED.splitlines()


def test_perform_substitutions_refuses_plain_text_as_ros_does(launch_dir: Path) -> None:
    # ROS: "Caught exception in launch (see debug for traceback): 'str' object has no
    # attribute 'perform'" (reference run 2026-11-29), exit status 1 (launchkit's status for a
    # mistake in a launch file is 2)
    (launch_dir / "plain.launch.py").write_text(
        textwrap.dedent(
            """\
            from launch import LaunchDescription
            from launch.actions import OpaqueFunction
            from launch.utilities import perform_substitutions


            def use(context):
                perform_substitutions(context, ['<', 'text'])


            def generate_launch_description():
                return LaunchDescription([OpaqueFunction(function=use)])
            """
        )
    )
    ran = run_launch(launch_dir, "plain.launch.py")
    assert ran.status == 2, ran.text
    assert "'str' object has no attribute 'perform'" in ran.text
    assert "plain.launch.py:7" in ran.text  # and where


# -- a bringup in nav2's style, against stub packages ----------------------------------------

#: A helper module written the way nav2_common's RewrittenYaml is (launchkit's own words).
REWRITE_PARAMS = '''\
"""A substitution written the way third-party launch helpers write them."""
import tempfile

import launch
import yaml


class RewriteParams(launch.Substitution):
    def __init__(self, source_file, rewrites, root_key=None):
        super().__init__()
        from launch.utilities import normalize_to_list_of_substitutions
        self.__source = normalize_to_list_of_substitutions(source_file)
        self.__rewrites = {key: normalize_to_list_of_substitutions(value)
                           for key, value in rewrites.items()}
        self.__root = None if root_key is None else normalize_to_list_of_substitutions(root_key)

    def describe(self):
        return ''

    def perform(self, context):
        path = launch.utilities.perform_substitutions(context, self.__source)
        data = yaml.safe_load(open(path))
        for key, value in self.__rewrites.items():
            text = launch.utilities.perform_substitutions(context, value)
            for node in data.values():
                if key in node['ros__parameters']:
                    node['ros__parameters'][key] = yaml.safe_load(text)
        if self.__root is not None:
            root = launch.utilities.perform_substitutions(context, self.__root)
            if root:
                data = {root: data}
        out = tempfile.NamedTemporaryFile('w', suffix='.yaml', delete=False)
        yaml.dump(data, out)
        out.close()
        return out.name
'''

BRINGUP = """\
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction, IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PythonExpression
from launch_ros.actions import Node, PushROSNamespace
from launch_ros.descriptions import ParameterFile
from demo_common import RewriteParams


def generate_launch_description():
    share = get_package_share_directory('demo_bringup')
    namespace = LaunchConfiguration('namespace')
    params = ParameterFile(
        RewriteParams(source_file=LaunchConfiguration('params_file'),
                      rewrites={'autostart': LaunchConfiguration('autostart')},
                      root_key=namespace),
        allow_substs=True)
    return LaunchDescription([
        DeclareLaunchArgument('namespace', default_value=''),
        DeclareLaunchArgument('autostart', default_value='true'),
        DeclareLaunchArgument('slam', default_value='False'),
        DeclareLaunchArgument('params_file',
                              default_value=os.path.join(share, 'params.yaml')),
        GroupAction([
            PushROSNamespace(condition=IfCondition(PythonExpression(["'", namespace, "' != ''"])),
                             namespace=namespace),
            Node(package='demo_nodes', executable='planner', name='planner', output='screen',
                 parameters=[params], remappings=[('/tf', 'tf')],
                 arguments=['--ros-args', '--log-level', 'info']),
            Node(package='demo_nodes', executable='mapper', name='mapper', output='screen',
                 parameters=[params, {'use_sim_time': False}],
                 condition=IfCondition(PythonExpression(['not ', LaunchConfiguration('slam')]))),
            IncludeLaunchDescription(
                PythonLaunchDescriptionSource(os.path.join(share, 'slam.launch.py')),
                condition=IfCondition(LaunchConfiguration('slam'))),
        ]),
    ])
"""

#: Included under a false condition: it needs a package that is not installed.
SLAM = """\
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription


def generate_launch_description():
    print('slam.launch.py was loaded')
    get_package_share_directory('slam_toolbox')
    return LaunchDescription([])
"""

PARAMS = """\
planner:
  ros__parameters:
    rate: 5
    frame: map
    autostart: false
mapper:
  ros__parameters:
    resolution: 0.05
"""


def _bringup(root: Path) -> dict[str, str]:
    """The stub prefix and helper module; the environment that finds them."""
    prefix = stub_prefix(root / "prefix", {"demo_nodes": ["planner", "mapper"], "demo_bringup": []})
    share = prefix / "share" / "demo_bringup"
    (share / "params.yaml").write_text(PARAMS)
    (share / "bringup.launch.py").write_text(BRINGUP)
    (share / "slam.launch.py").write_text(SLAM)
    site = root / "site"
    (site / "demo_common").mkdir(parents=True)
    (site / "demo_common" / "__init__.py").write_text(REWRITE_PARAMS)
    return {"AMENT_PREFIX_PATH": str(prefix), "PYTHONPATH": str(site)}


def _without_paths(lines: list[str]) -> list[str]:
    return [re.sub(r"/\S+/(launch_)?params_\S+", "FILE", line) for line in lines]


# `ros2 launch .../bringup.launch.py` (reference run 2026-11-29): each node's output
BRINGUP_EXPECTED = {
    "planner-1": [
        "argv: --ros-args --log-level info --ros-args -r __node:=planner --params-file FILE "
        "-r /tf:=tf",
        "params: mapper:|  ros__parameters:|    resolution: 0.05|planner:|  ros__parameters:|"
        "    autostart: true|    frame: map|    rate: 5|",
    ],
    "mapper-2": [
        "argv: --ros-args -r __node:=mapper --params-file FILE --params-file FILE",
        "params: mapper:|  ros__parameters:|    resolution: 0.05|planner:|  ros__parameters:|"
        "    autostart: true|    frame: map|    rate: 5|",
        "params: /**:|  ros__parameters:|    use_sim_time: false|",
    ],
}

# `ros2 launch .../bringup.launch.py namespace:=robot1 autostart:=false` (same run)
NAMESPACED_EXPECTED = {
    "planner-1": [
        "argv: --ros-args --log-level info --ros-args -r __node:=planner -r __ns:=/robot1 "
        "--params-file FILE -r /tf:=tf",
        "params: robot1:|  mapper:|    ros__parameters:|      resolution: 0.05|  planner:|"
        "    ros__parameters:|      autostart: false|      frame: map|      rate: 5|",
    ],
    "mapper-2": [
        "argv: --ros-args -r __node:=mapper -r __ns:=/robot1 --params-file FILE --params-file FILE",
        "params: robot1:|  mapper:|    ros__parameters:|      resolution: 0.05|  planner:|"
        "    ros__parameters:|      autostart: false|      frame: map|      rate: 5|",
        "params: /robot1/mapper:|  ros__parameters:|    use_sim_time: false|",
    ],
}


def test_a_bringup_in_nav2s_style_gives_jazzys_command_lines_and_files(
    launch_dir: Path,
) -> None:
    env = _bringup(launch_dir)
    launch_file = str(launch_dir / "prefix/share/demo_bringup/bringup.launch.py")
    for args, expected in [
        ([], BRINGUP_EXPECTED),
        (["namespace:=robot1", "autostart:=false"], NAMESPACED_EXPECTED),
    ]:
        ran = run_launch(launch_dir, launch_file, *args, env=env)
        assert ran.status == 0, ran.text
        for process, lines in expected.items():
            assert _without_paths(ran.of(process)) == lines, ran.text
        # ROS reads the include under the false condition for its arguments (the print shows),
        # and says nothing of its failure
        assert ran.lines.count("slam.launch.py was loaded") == 1, ran.text
        assert "slam_toolbox" not in ran.text


FRONTEND_INCLUDES = {
    "cond.launch.xml": """\
<launch>
  <arg name="use_slam" default="false"/>
  <include file="$(find-pkg-share demo_bringup)/slam.launch.py" if="$(var use_slam)"/>
  <include file="$(dirname)/broken.launch.xml" if="false"/>
  <log message="after the includes"/>
</launch>
""",
    "cond.launch.yaml": """\
launch:
- include:
    file: "$(find-pkg-share demo_bringup)/slam.launch.py"
    if: "false"
- log:
    message: "after the includes"
""",
}


def test_xml_and_yaml_includes_under_a_false_condition_do_not_stop_the_launch(
    launch_dir: Path,
) -> None:
    # `ros2 launch cond.launch.xml` and `cond.launch.yaml` (reference run 2026-11-29): exit
    # status 0, "slam.launch.py was loaded" then "[INFO] [launch.user]: after the includes";
    # the broken XML file under if="false" is never reported
    env = _bringup(launch_dir)
    (launch_dir / "broken.launch.xml").write_text("<launch><nosuchtag/></launch>\n")
    for name, text in FRONTEND_INCLUDES.items():
        (launch_dir / name).write_text(text)
        ran = run_launch(launch_dir, name, env=env)
        assert ran.status == 0, ran.text
        assert ran.launch_lines() == [
            "slam.launch.py was loaded",
            "[INFO] [launch.user]: after the includes",
        ]
    # `ros2 launch cond.launch.xml use_slam:=true` (same run): "Caught exception in launch
    # ...: PackageNotFoundError: "package 'slam_toolbox' not found ...", exit status 1;
    # launchkit says where, as for any error in a launch file
    ran = run_launch(launch_dir, "cond.launch.xml", "use_slam:=true", env=env)
    assert ran.status != 0, ran.text
    assert "slam.launch.py:7: error: package 'slam_toolbox' not found" in ran.text
