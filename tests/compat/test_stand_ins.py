"""Real packages before stand-ins: a package of the same name on ``AMENT_PREFIX_PATH`` wins
over launchkit's stand-in (as ROS runs what is installed), ``$LAUNCHKIT_STANDINS`` forces
either, ``launchkit pkg list`` says which one each name is; and the rviz2 stand-in accepts real
rviz2's command line.

Expectations from the real launch (``ros2_launch.py`` of the reference tools: launch 3.4.3,
launch_ros 0.26.6) where there is one to compare with.
"""

from __future__ import annotations

import signal
from pathlib import Path

import pytest

from launchkit.errors import LaunchArgumentError
from launchkit.packages import PackageIndex
from tests.compat.conftest import run_launch, run_launchkit, stub_prefix
from tests.engine.launcher import Launcher, wait_gone

RSP = """\
<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp" output="screen">
    <param name="publish_frequency" value="5.0"/>
  </node>
</launch>
"""


@pytest.fixture
def installed(launch_dir: Path) -> Path:
    """An ament prefix with a (stub) robot_state_publisher installed."""
    return stub_prefix(launch_dir / "prefix", {"robot_state_publisher": ["robot_state_publisher"]})


def test_an_installed_package_runs_instead_of_the_stand_in(
    launch_dir: Path, installed: Path
) -> None:
    # `ros2 launch rsp.launch.xml` with the prefix on AMENT_PREFIX_PATH (reference run
    # 2026-11-29): the installed program runs, "--ros-args -r __node:=rsp --params-file ..."
    (launch_dir / "rsp.launch.xml").write_text(RSP)
    env = {"AMENT_PREFIX_PATH": str(installed)}
    ran = run_launch(launch_dir, "rsp.launch.xml", env=env)
    assert ran.status == 0, ran.text
    argv = ran.of("robot_state_publisher-1")
    assert len(argv) == 2 and argv[0].startswith(
        "argv: --ros-args -r __node:=rsp --params-file "
    ), ran.text
    printed = run_launch(launch_dir, "--print", "rsp.launch.xml", env=env)
    assert f"cmd: {installed}/lib/robot_state_publisher/robot_state_publisher " in printed.text
    forced = run_launch(
        launch_dir, "--print", "rsp.launch.xml", env={**env, "LAUNCHKIT_STANDINS": "prefer"}
    )
    assert "-m launchkit.stock.robot_state_publisher.node --ros-args" in forced.text


def test_the_index_and_pkg_list_say_which_one_a_name_is(installed: Path, launch_dir: Path) -> None:
    found = PackageIndex(str(installed)).find("robot_state_publisher")
    assert (found.source, found.prefix) == (f"ament:{installed}", installed)
    stand_in = PackageIndex(str(installed), stand_ins="prefer").find("robot_state_publisher")
    assert stand_in.source == "stand-in" and stand_in.python is not None
    assert PackageIndex("").find("rviz2").source == "stand-in"  # none installed: it serves
    never = PackageIndex("", stand_ins="never")
    assert "rviz2" not in never.names() and never.stand_in("rviz2") is None
    with pytest.raises(LaunchArgumentError, match="LAUNCHKIT_STANDINS is 'sometimes'"):
        PackageIndex("", stand_ins="sometimes")
    listed = run_launchkit(launch_dir, "pkg", "list", env={"AMENT_PREFIX_PATH": str(installed)})
    # ros2 pkg list's one name a line; only what a stand-in serves is marked
    assert "robot_state_publisher" in listed.lines  # the installed one
    assert "rviz2  (launchkit stand-in)" in listed.lines
    assert "robot_wheel" in listed.lines
    never_listed = run_launchkit(launch_dir, "pkg", "list", env={"LAUNCHKIT_STANDINS": "never"})
    assert not [line for line in never_listed.lines if "stand-in" in line]


RVIZ = """\
<launch>
  <node pkg="rviz2" exec="rviz2" name="rviz2" respawn="true" output="screen"
        args="-d $(dirname)/view.rviz -s $(dirname)/splash.png -l --opengl 210 --no-stereo"/>
</launch>
"""


def test_the_rviz2_stand_in_takes_real_rviz2_options_and_stays_up(launch_dir: Path) -> None:
    # real rviz2 (Jazzy) takes -s and -l; ROS 1's --opengl and --no-stereo come with launch
    # files carried over. The stand-in serves, says once what it ignores, and does not exit
    # (a respawning rviz2 would otherwise restart every second)
    (launch_dir / "view.rviz").write_text("Visualization Manager:\n  Displays: []\n")
    (launch_dir / "rviz.launch.xml").write_text(RVIZ)
    launcher = Launcher(
        "rviz.launch.xml",
        cwd=launch_dir,
        env={"ROS_LOG_DIR": str(launch_dir / "log"), "LAUNCHKIT_VIEWER_PORT": "0"},
    )
    try:
        ignored = launcher.wait_line("ignoring -s ")
        assert f"ignoring -s {launch_dir}/splash.png -l --opengl 210 --no-stereo: " in ignored
        launcher.wait_line("viewer: http://")
        launcher.signal(signal.SIGINT)
        assert launcher.finish() == 0, launcher.text
        assert "process has died" not in launcher.text and "respawning" not in launcher.text
    finally:
        if launcher.proc.poll() is None:
            launcher.kill()
        launcher.close()
        wait_gone(list(launcher.pids.values()))
