"""package.xml read as colcon reads it: formats 1 to 3, build types, dependency kinds with
their places, groups, conditions (catkin_pkg's grammar), and located mistakes."""

from __future__ import annotations

from pathlib import Path

import pytest

from launchkit.errors import Location
from launchkit.workspace.conditions import ConditionError, evaluate
from launchkit.workspace.graph import Workspace
from launchkit.workspace.manifest import ManifestError, read_manifest

FORMAT3 = """\
<?xml version="1.0"?>
<package format="3">
  <name>demo</name>
  <version>1.2.3</version>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <depend>std_msgs</depend>
  <build_depend condition="$ROS_VERSION == 1">roscpp</build_depend>
  <exec_depend condition="$ROS_VERSION == 2">rclpy</exec_depend>
  <test_depend>ament_flake8</test_depend>
  <group_depend>rosidl_interface_packages</group_depend>
  <member_of_group>demo_group</member_of_group>
  <export>
    <build_type condition="$ROS_VERSION == 1">catkin</build_type>
    <build_type condition="$ROS_VERSION == 2">ament_python</build_type>
  </export>
</package>
"""


def _write(tmp_path: Path, text: str, folder: str = "demo") -> Path:
    path = tmp_path / folder / "package.xml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def test_format_3_with_conditions(tmp_path: Path) -> None:
    manifest = read_manifest(_write(tmp_path, FORMAT3), environ={})
    assert (manifest.name, manifest.version, manifest.build_type) == (
        "demo",
        "1.2.3",
        "ament_python",
    )
    assert [(d.name, d.kind) for d in manifest.dependencies] == [
        ("ament_cmake", "buildtool_depend"),
        ("std_msgs", "depend"),
        ("rclpy", "exec_depend"),
        ("ament_flake8", "test_depend"),
    ]
    assert manifest.dependencies[2].location == Location(
        str(tmp_path / "demo" / "package.xml"), 8, 3
    )
    assert manifest.groups == ("demo_group",)
    assert manifest.group_depends == ("rosidl_interface_packages",)


def test_the_environment_decides_conditions(tmp_path: Path) -> None:
    manifest = read_manifest(_write(tmp_path, FORMAT3), environ={"ROS_VERSION": "1"})
    assert manifest.build_type == "catkin"
    assert "roscpp" in [d.name for d in manifest.dependencies]


def test_format_1_run_depend_is_exec_depend_and_no_build_type_is_catkin(tmp_path: Path) -> None:
    text = "<package>\n  <name>old</name>\n  <run_depend>roslib</run_depend>\n</package>\n"
    manifest = read_manifest(_write(tmp_path, text), environ={})
    assert [(d.name, d.kind) for d in manifest.dependencies] == [("roslib", "exec_depend")]
    assert manifest.build_type == "catkin"


@pytest.mark.parametrize(
    ("text", "where", "message"),
    [
        ("<package>\n  <name>../up</name>\n</package>\n", "2:3", "is not a valid package name"),
        ("<manifest>\n</manifest>\n", "1:1", "the root element is <manifest>"),
        (
            '<package>\n  <name>x</name>\n  <depend condition="$A = 1">y</depend>\n</package>\n',
            "3:3",
            "unexpected '=' in condition '$A = 1'",
        ),
        ("<package>\n  <name>x\n", "3:1", "not well-formed XML"),
    ],
)
def test_mistakes_are_located(tmp_path: Path, text: str, where: str, message: str) -> None:
    with pytest.raises(ManifestError) as raised:
        read_manifest(_write(tmp_path, text), environ={})
    assert str(raised.value.location).endswith(f"package.xml:{where}")
    assert message in raised.value.message


@pytest.mark.parametrize(
    ("condition", "expected"),
    [
        ("$ROS_VERSION == 2", True),
        ("$ROS_VERSION != 2", False),
        ("$ROS_VERSION == 1 or $ROS_DISTRO == jazzy", True),
        ("$ROS_VERSION == 1 or $ROS_VERSION == 2 and $ROS_DISTRO == humble", False),
        ("($ROS_VERSION == 1 or $ROS_VERSION == 2) and $ROS_DISTRO >= humble", True),
        ("$UNSET == $ALSO_UNSET", True),  # an unset variable is the empty string
        ("$ROS_PYTHON_VERSION < 3", False),
    ],
)
def test_conditions_follow_catkin_pkg(condition: str, expected: bool) -> None:
    context = {"ROS_VERSION": "2", "ROS_DISTRO": "jazzy", "ROS_PYTHON_VERSION": "3"}
    assert evaluate(condition, context) is expected


@pytest.mark.parametrize("condition", ["$A ==", "$A = 1", "($A == 1", "$A == ''", "and", ""])
def test_a_malformed_condition_is_an_error(condition: str) -> None:
    with pytest.raises(ConditionError):
        evaluate(condition, {})


def test_order_follows_dependencies_and_group_depends(tmp_path: Path) -> None:
    def package(name: str, extra: str) -> Path:
        return _write(
            tmp_path,
            f"<package format='3'>\n  <name>{name}</name>\n{extra}</package>\n",
            name,
        )

    manifests = [
        read_manifest(package("app", "  <exec_depend>lib</exec_depend>\n"), environ={}),
        read_manifest(package("lib", "  <group_depend>msgs_group</group_depend>\n"), environ={}),
        read_manifest(package("a_msgs", "  <member_of_group>msgs_group</member_of_group>\n"), {}),
        read_manifest(package("z_msgs", "  <member_of_group>msgs_group</member_of_group>\n"), {}),
        read_manifest(package("tested", "  <test_depend>app</test_depend>\n"), environ={}),
    ]
    workspace = Workspace(manifests)
    assert workspace.order() == ["a_msgs", "tested", "z_msgs", "lib", "app"]
    assert workspace.select(up_to=["lib"]) == ["a_msgs", "z_msgs", "lib"]
    assert workspace.select(skip=["app", "tested"]) == ["a_msgs", "z_msgs", "lib"]
