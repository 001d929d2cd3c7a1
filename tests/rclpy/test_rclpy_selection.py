"""Which rclpy a process gets: launchkit's (the face first on ``PYTHONPATH``) or the real one,
decided from its environment when it starts; ``launchkit exec --python``; a launch's processes;
the face's ``sitecustomize`` chaining to the one it shadows."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from launchkit.envvars import RCLPY
from launchkit.ros import face
from launchkit.ros.msgs._packages import BUILTIN_PACKAGES
from launchkit.ros.msgs._registry import registry

WHICH = """\
import sys, rclpy
print("rclpy from", "launchkit" if "/face/" in rclpy.__file__ else "elsewhere", sys.argv[1:])
"""


def _env(**changes: str | None) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in (RCLPY, "PYTHONPATH", "ROS_DISTRO")}
    for name, value in changes.items():
        if value is None:
            env.pop(name, None)
        else:
            env[name] = value
    return env


def _with_the_face(probe: str) -> subprocess.CompletedProcess[str]:
    """Run Python code ``probe`` with launchkit's face first on ``PYTHONPATH``; it must succeed."""
    result = subprocess.run(
        [sys.executable, "-c", probe],
        capture_output=True,
        text=True,
        env=_env(PYTHONPATH=str(face.path())),
        timeout=120,
    )
    assert result.returncode == 0, result.stderr
    return result


def _ros_install(root: Path) -> Path:
    """A prefix laid out as a sourced ROS 2 install's, with an rclpy package in it."""
    package = root / "lib" / "python3.11" / "site-packages" / "rclpy"
    package.mkdir(parents=True)
    (package / "__init__.py").write_text("")
    return root


def test_the_choice_follows_the_variable_then_a_sourced_install(tmp_path: Path) -> None:
    prefix = str(_ros_install(tmp_path / "opt"))
    assert face.choose({}) == "launchkit"
    assert face.choose({RCLPY: "ros"}) == "ros"
    assert face.choose({RCLPY: " Launchkit "}) == "launchkit"
    assert face.choose({"ROS_DISTRO": "jazzy", "AMENT_PREFIX_PATH": prefix}) == "ros"
    # ROS_DISTRO without an rclpy under the prefixes, or the prefixes without ROS_DISTRO
    assert face.choose({"ROS_DISTRO": "jazzy", "AMENT_PREFIX_PATH": str(tmp_path)}) == "launchkit"
    assert face.choose({"AMENT_PREFIX_PATH": prefix}) == "launchkit"
    sourced = {"ROS_DISTRO": "jazzy", "AMENT_PREFIX_PATH": prefix, RCLPY: "launchkit"}
    assert face.choose(sourced) == "launchkit"  # the variable wins
    with pytest.raises(face.RclpyChoiceError, match="LAUNCHKIT_RCLPY='real' is not a choice"):
        face.choose({RCLPY: "real"})


def test_the_face_goes_first_on_pythonpath_once() -> None:
    folder = str(face.path())
    changed = face.environment({"PYTHONPATH": f"/a{os.pathsep}{folder}{os.pathsep}/b"})
    assert changed == {"PYTHONPATH": os.pathsep.join([folder, "/a", "/b"])}
    assert face.environment({RCLPY: "ros", "PYTHONPATH": "/a"}) == {}
    # launchkit's own programs are started as they are (the bridge needs the real rclpy)
    assert face.child_environment([sys.executable, "-m", "launchkit.bridge"], {}) == {}
    assert face.child_environment([sys.executable, "node.py"], {})["PYTHONPATH"] == folder


def _launchkit(*args: str, env: dict[str, str], cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "launchkit", *args],
        capture_output=True,
        text=True,
        env=env,
        cwd=cwd,
        timeout=120,
    )


def test_exec_python_runs_a_script_with_the_chosen_rclpy(tmp_path: Path) -> None:
    script = tmp_path / "which.py"
    script.write_text(WHICH)
    ours = _launchkit("exec", "--python", "which.py", "a", "--ros-args", env=_env(), cwd=tmp_path)
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout == "rclpy from launchkit ['a', '--ros-args']\n"
    real = _launchkit("exec", "--python", "which.py", env=_env(**{RCLPY: "ros"}), cwd=tmp_path)
    assert "rclpy from launchkit" not in real.stdout


@pytest.mark.parametrize(
    ("args", "env", "message"),
    [
        (["exec", "--python"], {}, "error: exec --python needs a file"),
        (["exec", "--python", "missing.py"], {}, "error: no file 'missing.py'"),
        (["exec", "--python", "which.py"], {RCLPY: "real"}, "error: LAUNCHKIT_RCLPY='real' is"),
    ],
)
def test_exec_python_mistakes_are_one_line(
    tmp_path: Path, args: list[str], env: dict[str, str], message: str
) -> None:
    (tmp_path / "which.py").write_text(WHICH)
    result = _launchkit(*args, env=_env(**env), cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith(message) and result.stderr.count("\n") == 1, result.stderr


def test_a_launchs_processes_get_the_face(tmp_path: Path) -> None:
    (tmp_path / "which.py").write_text(WHICH)
    launch = tmp_path / "which.launch.xml"
    launch.write_text(
        "<launch>\n"
        f'  <executable cmd="{sys.executable} which.py user" cwd="{tmp_path}" output="screen"/>\n'
        "</launch>\n"
    )
    result = _launchkit("run", str(launch), env=_env(), cwd=tmp_path)
    assert "rclpy from launchkit ['user']" in result.stdout, result.stdout + result.stderr


def test_sitecustomize_runs_the_one_it_shadows(tmp_path: Path) -> None:
    other = tmp_path / "other"
    other.mkdir()
    (other / "sitecustomize.py").write_text("import builtins\nbuiltins.CHAINED = 'yes'\n")
    env = _env(PYTHONPATH=os.pathsep.join([str(face.path()), str(other)]))
    probe = "import builtins, sys; print(builtins.CHAINED, 'std_msgs.msg' in sys.modules)"
    result = subprocess.run(
        [sys.executable, "-c", probe + "; from std_msgs.msg import String; print(String())"],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == "yes False"  # chained; no message package imported before it is asked
    assert "data=''" in lines[1]  # launchkit's std_msgs, not the installed one


def test_the_face_loads_the_message_layer_only_when_a_message_package_is_imported() -> None:
    # installing the import hook at start-up must not load rosbags and the classes into every
    # Python process a launch starts; numpy (0.25 s of CPU) loads only with the first value of
    # a fixed-size array, not with the types that have one (every service's Event type does)
    layer = ("rosbags.typesys.store", "launchkit.ros.msgs._registry")
    probe = (
        f"import sys, json\nlayer = {layer!r}\n"
        "before = [m for m in layer if m in sys.modules]\n"
        "import example_interfaces.srv, geometry_msgs.msg\n"
        "after = [m for m in layer if m in sys.modules]\n"
        "example_interfaces.srv.AddTwoInts.Event, geometry_msgs.msg.PoseWithCovariance\n"
        "types_made = 'numpy' in sys.modules\n"
        "covariance = geometry_msgs.msg.PoseWithCovariance().covariance\n"
        "print(json.dumps([before, after, types_made, type(covariance).__module__]))\n"
    )
    result = _with_the_face(probe)
    assert json.loads(result.stdout) == [[], list(layer), False, "numpy"]


def test_a_module_the_platform_lacks_reads_no_distribution_metadata() -> None:
    # subprocess tries msvcrt, missing on Linux: asking the finder of registered packages about
    # it read every installed distribution's entry points (75 ms) in every node that started
    probe = (
        "import sys, subprocess, rclpy, rclpy.node\n"
        "try:\n    import winreg\nexcept ImportError:\n    pass\n"
        "print('importlib.metadata' in sys.modules)\n"
    )
    assert _with_the_face(probe).stdout == "False\n"


def test_the_hooks_list_of_built_in_packages_is_the_stores() -> None:
    assert BUILTIN_PACKAGES == registry().builtin_packages()


def test_every_face_module_imports_and_names_what_it_exports() -> None:
    probe = (
        "import importlib, pkgutil, rclpy\n"
        "names = [m.name for m in pkgutil.walk_packages(rclpy.__path__, 'rclpy.')]\n"
        "for name in names:\n"
        "    module = importlib.import_module(name)\n"
        "    missing = [n for n in getattr(module, '__all__', []) if not hasattr(module, n)]\n"
        "    assert not missing, (name, missing)\n"
        "print(len(names), rclpy.executors.MultiThreadedExecutor.__module__)\n"
    )
    result = _with_the_face(probe)
    count, where = result.stdout.split()
    assert int(count) >= 30 and where == "launchkit.ros.executors"


@pytest.mark.skipif(
    not (Path(sys.prefix) / "share" / "ament_index" / "resource_index" / "packages").is_dir(),
    reason="no ROS packages installed with pip here (the ros-jazzy wheels: CPython 3.11 only)",
)
def test_packages_the_wheels_installed_come_from_launchkits_message_layer() -> None:
    # The wheels put test_msgs' Python package on sys.path: without the interpreter's prefix on
    # AMENT_PREFIX_PATH, `import test_msgs.action` gave their rosidl class beside launchkit's
    # rclpy, two ROS layers mixed in one process.
    code = "import test_msgs.action as a, std_msgs.msg as m; print(type(a.Fibonacci).__module__)"
    env = _env(AMENT_PREFIX_PATH=None, **face.environment(_env()))
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "launchkit.ros.msgs._classes"
