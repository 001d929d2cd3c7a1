"""Workspaces the build tests write: ROS 2 packages as a user writes them (package.xml,
setup.py/setup.cfg, CMakeLists.txt), and a way to run ``launchkit build`` and the installed
workspace's commands in a shell that sourced ``install/setup.sh``."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Mapping
from pathlib import Path

#: The `launchkit` command of the environment running the tests.
BIN = Path(sys.executable).parent


def package_xml(
    name: str,
    build_type: str,
    depends: Mapping[str, list[str]] | None = None,
    groups: list[str] | None = None,
    fmt: int = 3,
) -> str:
    """A package.xml with dependencies by kind (``{"exec_depend": ["rclpy"]}``)."""
    lines = [
        '<?xml version="1.0"?>',
        f'<package format="{fmt}">',
        f"  <name>{name}</name>",
        "  <version>0.1.0</version>",
        "  <description>A test package.</description>",
        '  <maintainer email="me@example.com">me</maintainer>',
        "  <license>Apache-2.0</license>",
    ]
    for kind, names in (depends or {}).items():
        lines.extend(f"  <{kind}>{dep}</{kind}>" for dep in names)
    lines.extend(f"  <member_of_group>{group}</member_of_group>" for group in groups or [])
    lines += ["  <export>", f"    <build_type>{build_type}</build_type>", "  </export>"]
    return "\n".join([*lines, "</package>", ""])


def python_package(
    name: str, scripts: Mapping[str, str], depends: Mapping[str, list[str]] | None = None
) -> dict[str, str]:
    """An ament_python package as `ros2 pkg create --build-type ament_python` lays it out,
    with console scripts (``{"talk": "def main(): ..."}``, one module each), a launch file
    and a parameters file installed by data_files."""
    entry_points = ", ".join(f"'{s} = {name}.{s}:main'" for s in scripts)
    files = {
        "package.xml": package_xml(name, "ament_python", depends),
        "setup.cfg": f"[develop]\nscript_dir=$base/lib/{name}\n"
        f"[install]\ninstall_scripts=$base/lib/{name}\n",
        "setup.py": f"""\
import os
from glob import glob

from setuptools import find_packages, setup

package_name = '{name}'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        (os.path.join('share', package_name, 'launch'), glob('launch/*.launch.*')),
        (os.path.join('share', package_name, 'config'), glob('config/*.yaml')),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    entry_points={{'console_scripts': [{entry_points}]}},
)
""",
        f"resource/{name}": "",
        f"{name}/__init__.py": "",
        "test/test_nothing.py": "def test_nothing():\n    pass\n",
    }
    for script, body in scripts.items():
        files[f"{name}/{script}.py"] = body
    return files


def interface_package(name: str, interfaces: Mapping[str, str]) -> dict[str, str]:
    """An interface-only ament_cmake package (``{"msg/Num.msg": "int64 num\\n"}``), its
    CMakeLists.txt as `ros2 pkg create` and the interface tutorial write it."""
    listed = "\n".join(f'  "{path}"' for path in interfaces)
    return {
        "package.xml": package_xml(
            name,
            "ament_cmake",
            {
                "buildtool_depend": ["ament_cmake", "rosidl_default_generators"],
                "depend": ["std_msgs", "action_msgs"],
                "exec_depend": ["rosidl_default_runtime"],
            },
            groups=["rosidl_interface_packages"],
        ),
        "CMakeLists.txt": f"""\
cmake_minimum_required(VERSION 3.8)
project({name})

if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  add_compile_options(-Wall -Wextra -Wpedantic)
endif()

find_package(ament_cmake REQUIRED)
find_package(rosidl_default_generators REQUIRED)

rosidl_generate_interfaces(${{PROJECT_NAME}}
{listed}
  DEPENDENCIES std_msgs action_msgs
)

install(FILES README.md DESTINATION share/${{PROJECT_NAME}})

if(BUILD_TESTING)
  find_package(ament_lint_auto REQUIRED)
  ament_lint_auto_find_test_dependencies()
endif()

ament_package()
""",
        "README.md": f"# {name}\n",
        **interfaces,
    }


def cpp_package(name: str) -> dict[str, str]:
    """An ament_cmake package with a C++ node."""
    return {
        "package.xml": package_xml(
            name, "ament_cmake", {"buildtool_depend": ["ament_cmake"], "depend": ["rclcpp"]}
        ),
        "CMakeLists.txt": f"""\
cmake_minimum_required(VERSION 3.8)
project({name})
find_package(ament_cmake REQUIRED)
find_package(rclcpp REQUIRED)

add_executable(talker src/talker.cpp)
ament_target_dependencies(talker rclcpp)
install(TARGETS talker DESTINATION lib/${{PROJECT_NAME}})
ament_package()
""",
        "src/talker.cpp": "int main() { return 0; }\n",
    }


def write_package(src: Path, folder: str, files: Mapping[str, str]) -> Path:
    """Write a package's files under ``src/FOLDER``; the package's folder."""
    root = src / folder
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root


def environment(home: Path, **extra: str) -> dict[str, str]:
    """The environment the commands run in: the tests' own, no workspace sourced yet, HOME
    a folder of the test (so that a write to the home folder shows), ``launchkit`` on PATH."""
    env = {k: v for k, v in os.environ.items() if k not in ("AMENT_PREFIX_PATH", "PYTHONPATH")}
    env["HOME"] = str(home)
    env["PATH"] = f"{BIN}{os.pathsep}{env.get('PATH', '')}"
    env.update(extra)
    return env


def launchkit_build(
    workspace: Path, *args: str, env: Mapping[str, str]
) -> subprocess.CompletedProcess[str]:
    """``launchkit build ARGS`` in ``workspace``."""
    return _run([sys.executable, "-m", "launchkit", "build", *args], workspace, env)


def in_sourced_shell(
    workspace: Path, script: str, env: Mapping[str, str], cwd: Path
) -> subprocess.CompletedProcess[str]:
    """``script`` run by ``sh -c`` after ``. WORKSPACE/install/setup.sh``, in ``cwd``."""
    setup = workspace / "install" / "setup.sh"
    return _run(["sh", "-c", f'. "{setup}" && {script}'], cwd, env)


def _run(argv: list[str], cwd: Path, env: Mapping[str, str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        argv, cwd=cwd, env=dict(env), capture_output=True, text=True, timeout=600, check=False
    )
