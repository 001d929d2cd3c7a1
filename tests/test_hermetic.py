"""Whatever a user's shell exports, tests run apart from it: the plugin's launches get their own
router, ROS domain, viewer port and log folder and none of the shell's launchkit settings, and
the suite's own environment (tests/suite_env.py) keeps every process it starts off the user's
home folder, ports and robot."""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

from launchkit import envvars
from launchkit.testing import LaunchFactory
from tests import suite_env

LAUNCH_DIR = Path(__file__).parent / "testing" / "launch"
LAUNCHKIT = Path(__file__).resolve().parents[1] / "launchkit"
DEFAULT_ROUTER_PORT, DEFAULT_VIEWER_PORT = "7447", "8765"


def hostile_shell(home: Path) -> dict[str, str]:
    """What a user's shell may export: the default ports, a domain in use, a federation, log
    limits and folders in the home, ... every ``LAUNCHKIT_*`` variable set. (The cache folder
    is the user's own and the plugin keeps it: it changes nothing but speed.)"""
    shell = {name: "1" for name in envvars.NAMES}
    shell.update(
        {
            envvars.ROUTER: f"tcp/127.0.0.1:{DEFAULT_ROUTER_PORT}",
            envvars.VIEWER_PORT: DEFAULT_VIEWER_PORT,
            envvars.ROUTER_CONNECT: "tcp/127.0.0.1:9",
            envvars.ROUTER_LISTEN: "tcp/127.0.0.1:9",
            envvars.LOG_RUN_MB: "0.001",
            envvars.CACHE_DIR: str(home.parent / "user-cache"),
            envvars.SUPERVISOR_SOCKET: str(home / "socket"),
            envvars.RUN_TMPDIR: str(home / "tmp"),
            "ROS_DOMAIN_ID": "7",
            "ROS_LOG_DIR": str(home / "ros-log"),
            "RMW_IMPLEMENTATION": "rmw_fastrtps_cpp",
            "HOME": str(home),
        }
    )
    return shell


def printed_environment(handle: Any) -> dict[str, str]:
    """The ``LAUNCHKIT_*`` and ``ROS_*`` variables the launch's process printed."""
    handle.process("env").wait_output("env printed", timeout=10)
    lines = handle.output["env-1"]
    return dict(line.split("=", 1) for line in lines if "=" in line)


def test_a_launch_of_the_plugin_keeps_nothing_of_a_hostile_shell(
    launch: LaunchFactory, monkeypatch: Any, tmp_path: Path
) -> None:
    home = tmp_path / "home"
    home.mkdir()
    for name, value in hostile_shell(home).items():
        monkeypatch.setenv(name, value)
    handle = launch(LAUNCH_DIR / "isolation.launch.xml")
    seen = printed_environment(handle)

    assert seen[envvars.ROUTER] == handle.router
    assert not handle.router.endswith((f":{DEFAULT_ROUTER_PORT}", ":9"))
    assert seen["ROS_DOMAIN_ID"] == str(handle.domain_id) != "7"
    assert seen[envvars.VIEWER_PORT] == str(handle.viewer_port) != DEFAULT_VIEWER_PORT
    # the shell's settings are gone; what the launcher sets for its processes is its own
    for name in (envvars.ROUTER_CONNECT, envvars.ROUTER_LISTEN, envvars.LOG_RUN_MB):
        assert name not in seen, name
    assert seen.get(envvars.SUPERVISOR_SOCKET) != str(home / "socket")
    assert seen.get(envvars.RUN_TMPDIR) != str(home / "tmp")
    assert Path(seen["ROS_LOG_DIR"]).is_relative_to(handle.log_dir)
    assert f"below {handle.log_dir}" in handle.launcher_log.read_text()
    handle.stop().assert_exit_codes({"env": 0})
    assert list(home.iterdir()) == [], "the launch wrote into the shell's home"


def test_the_suite_environment_drops_the_shell_and_keeps_the_home_folder_clean(
    tmp_path: Path,
) -> None:
    home = tmp_path / "home"
    shell = {**hostile_shell(home), "PATH": "/usr/bin:/bin"}
    run = tmp_path / "run"
    run.mkdir()
    environment = suite_env.suite_environment(shell, run)
    for name in suite_env.DROPPED - set(suite_env.FOLDERS) - {envvars.ROUTER_AUTOSTART}:
        assert name not in environment, name
    assert environment["PATH"] == "/usr/bin:/bin" and environment["HOME"] == str(home)
    for name in suite_env.FOLDERS:
        folder = Path(environment[name])
        assert folder.is_dir() and folder.is_relative_to(run), name
    assert environment[envvars.ROUTER_AUTOSTART] == "0"
    assert "PYTHONPYCACHEPREFIX" not in environment


def test_the_suite_keeps_bytecode_in_its_folder_where_the_shell_forbids_writing_it(
    tmp_path: Path,
) -> None:
    shell = {"PATH": "/usr/bin:/bin", "PYTHONDONTWRITEBYTECODE": "1"}
    environment = suite_env.suite_environment(shell, tmp_path)
    assert "PYTHONDONTWRITEBYTECODE" not in environment
    assert environment["PYTHONPYCACHEPREFIX"] == str(tmp_path / suite_env.BYTECODE)
    assert (tmp_path / suite_env.BYTECODE).is_dir()
    # a worker inherits the run's environment: the same again
    assert suite_env.suite_environment(environment, tmp_path) == environment


def test_this_process_runs_with_private_defaults() -> None:
    """The suite's conftest applied tests/suite_env.py here: nothing a test starts without its
    own settings reaches the default ports, domain 0 or the home folder."""
    assert os.environ[envvars.ROUTER].startswith("tcp/127.0.0.1:")
    assert not os.environ[envvars.ROUTER].endswith(f":{DEFAULT_ROUTER_PORT}")
    assert os.environ[envvars.VIEWER_PORT] != DEFAULT_VIEWER_PORT
    assert os.environ["ROS_DOMAIN_ID"] != "0"
    assert "RMW_IMPLEMENTATION" not in os.environ
    home = Path.home()
    for name in suite_env.FOLDERS:
        assert not Path(os.environ[name]).is_relative_to(home), name


def test_envvars_names_every_launchkit_variable() -> None:
    """A variable launchkit reads (its name a string of its own in the code) but
    ``envvars.NAMES`` leaves out would reach the suite and the plugin's launches from the user's
    shell."""
    read = set()
    for path in LAUNCHKIT.rglob("*.py"):
        read |= set(re.findall(r"""["'](LAUNCHKIT_[A-Z0-9_]*[A-Z0-9])["']""", path.read_text()))
    assert read, "no LAUNCHKIT_ variable found: the search is broken"
    assert read <= set(envvars.NAMES), sorted(read - set(envvars.NAMES))


def test_ci_runs_the_suite_in_a_hostile_shell() -> None:
    script = (LAUNCHKIT.parent / ".ci" / "run").read_text()
    exported = " ".join(
        line
        for line in script[: script.index("python -m pytest")].splitlines()
        if line.startswith("export ")
    )
    for setting in (
        "ROS_DOMAIN_ID=7",
        f"{envvars.ROUTER}=tcp/127.0.0.1:9",
        f"{envvars.VIEWER_PORT}=9",
        "RMW_IMPLEMENTATION=rmw_fastrtps_cpp",
    ):
        assert setting in exported.split(), setting
