"""The ``ros2`` command for launched processes where no ROS 2 is installed: launch files that
call ``ros2`` (``<executable cmd="ros2 ...">``, ``FindExecutable(name='ros2')`` as the ROS 2
tutorials' event-handler example does) run launchkit's verbs; a real ``ros2`` earlier on the
PATH is never shadowed; ``launchkit shell-init`` gives a shell the same ``ros2``."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from cli_helpers import launchkit
from ros_helpers import Child, demo_package, free_port

from launchkit.ros_cli.ros2_shim import with_ros2


def path_without_ros2() -> str:
    """This process's PATH without any folder that holds a ``ros2``, and with this
    environment's scripts (``launchkit``) first."""
    folders = [str(Path(sys.executable).parent)]
    folders += [
        folder
        for folder in os.environ.get("PATH", os.defpath).split(os.pathsep)
        if folder and not os.path.exists(os.path.join(folder, "ros2"))
    ]
    return os.pathsep.join(folders)


def launch(tmp_path: Path, name: str, text: str, path: str) -> tuple[Child, str]:
    """``launchkit run`` of the launch file ``text`` with package ``demo`` installed, on a
    router of its own; the launcher and the router's endpoint."""
    demo_package(tmp_path / "prefix")
    file = tmp_path / name
    file.write_text(text)
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    launcher = Child(
        ["-m", "launchkit", "run", str(file)],
        env={
            "AMENT_PREFIX_PATH": str(tmp_path / "prefix"),
            "LAUNCHKIT_ROUTER": endpoint,
            "PATH": path,
        },
    )
    return launcher, endpoint


def test_a_launch_files_ros2_param_set_changes_the_parameter(tmp_path: Path) -> None:
    launcher, endpoint = launch(
        tmp_path,
        "set.launch.xml",
        "<launch>\n"
        '  <node pkg="demo" exec="knobs" name="knobs"/>\n'
        '  <executable cmd="ros2 param set --timeout 60 /knobs count 11" output="screen"/>\n'
        "</launch>\n",
        path_without_ros2(),
    )
    try:
        line = launcher.expect("Set parameter successful", timeout=90)
        assert line.startswith("[ros2-2] ")
        got = launchkit("param", "get", "/knobs", "count", env={"LAUNCHKIT_ROUTER": endpoint})
        assert got.stdout == "Integer value is: 11\n", got.stderr
    finally:
        assert launcher.stop(timeout=20) == 0


def test_find_executable_ros2_in_an_event_handler_as_the_tutorial_writes_it(
    tmp_path: Path,
) -> None:
    # the shape of the "Using event handlers" tutorial's example_event_handlers.launch.py
    launcher, endpoint = launch(
        tmp_path,
        "handlers.launch.py",
        "from launch import LaunchDescription\n"
        "from launch.actions import ExecuteProcess, RegisterEventHandler\n"
        "from launch.event_handlers import OnProcessStart\n"
        "from launch.substitutions import FindExecutable\n"
        "from launch_ros.actions import Node\n\n\n"
        "def generate_launch_description():\n"
        "    knobs = Node(package='demo', executable='knobs', name='knobs')\n"
        "    change = ExecuteProcess(\n"
        "        cmd=[[FindExecutable(name='ros2'), ' param set --timeout 60 /knobs ',\n"
        "              'count 13']],\n"
        "        shell=True,\n"
        "        output='screen',\n"
        "    )\n"
        "    return LaunchDescription([\n"
        "        knobs,\n"
        "        RegisterEventHandler(OnProcessStart(target_action=knobs, on_start=[change])),\n"
        "    ])\n",
        path_without_ros2(),
    )
    try:
        launcher.expect("Set parameter successful", timeout=90)
        got = launchkit("param", "get", "/knobs", "count", env={"LAUNCHKIT_ROUTER": endpoint})
        assert got.stdout == "Integer value is: 13\n", got.stderr
    finally:
        assert launcher.stop(timeout=20) == 0


def test_a_ros2_already_on_the_path_is_the_one_that_runs(tmp_path: Path) -> None:
    fake = tmp_path / "ros" / "bin"
    fake.mkdir(parents=True)
    (fake / "ros2").write_text('#!/bin/sh\necho "the real ros2: $*"\n')
    (fake / "ros2").chmod(0o755)
    path = os.pathsep.join([str(fake), path_without_ros2()])
    file = tmp_path / "fake.launch.xml"
    file.write_text(
        "<launch>\n"
        '  <executable cmd="ros2 param set /knobs count 1" output="screen"/>\n'
        '  <executable cmd="echo found $(find-exec ros2)" output="screen"/>\n'
        "</launch>\n"
    )
    ran = launchkit("run", str(file), env={"PATH": path})  # ends when both have run
    assert ran.returncode == 0, ran.stderr
    assert "the real ros2: param set /knobs count 1\n" in ran.stdout
    assert f"found {fake / 'ros2'}\n" in ran.stdout
    # and the shim folder is not even added to such a PATH
    assert with_ros2({"PATH": path})["PATH"] == path
    plain = path_without_ros2()
    added = with_ros2({"PATH": plain})["PATH"]
    assert added.startswith(plain + os.pathsep) and os.path.isfile(
        Path(added.split(os.pathsep)[-1]) / "ros2"
    )


def test_shell_init_gives_a_shell_ros2(tmp_path: Path) -> None:
    if shutil.which("sh") is None:
        pytest.skip("no POSIX shell")
    env = {**os.environ, "PATH": path_without_ros2()}
    script = (
        'eval "$(launchkit shell-init)"\n'
        "ros2 pkg prefix robot_wheel\n"
        "ros2 run robot_state_publisher nope || echo exec said no\n"
    )
    ran = subprocess.run(
        ["sh", "-c", script], capture_output=True, text=True, timeout=120, env=env, cwd=tmp_path
    )
    expected = launchkit("pkg", "prefix", "robot_wheel").stdout
    assert ran.stdout == expected + "exec said no\n", ran.stderr
    # `ros2 run PKG EXEC` is `launchkit exec PKG EXEC`, which names what it looked for
    assert "executable 'nope' not found in package 'robot_state_publisher'" in ran.stderr
    init = launchkit("shell-init", env={"PATH": path_without_ros2()}).stdout
    assert init.splitlines()[-1].startswith('export PATH="$PATH":')


def test_launchkit_exec_gives_its_executable_a_ros2(tmp_path: Path) -> None:
    prefix = tmp_path / "install"
    (prefix / "share" / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    (prefix / "share" / "ament_index" / "resource_index" / "packages" / "tools").touch()
    (prefix / "share" / "tools").mkdir()
    script = prefix / "lib" / "tools" / "ask"
    script.parent.mkdir(parents=True)
    script.write_text("#!/bin/sh\nros2 pkg prefix tools\n")
    script.chmod(0o755)
    env = {"AMENT_PREFIX_PATH": str(prefix), "PATH": path_without_ros2()}
    ran = launchkit("exec", "tools", "ask", env=env)
    assert ran.stdout == f"{prefix}\n", ran.stderr
    # and `launchkit run PKG EXEC`, ros2 run's spelling, is the same
    assert launchkit("run", "tools", "ask", env=env).stdout == f"{prefix}\n"
