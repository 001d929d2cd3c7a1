"""Benchmark: what the launch engine costs (run by hand; results go in docs/benchmarks.md).

    python bench/launch_overhead.py [--repeat 5] [--ros-python VENV/bin/python]

Measures, each as the median of --repeat runs, beside a baseline measured in the same run:
  * `launchkit run` of an empty launch file vs starting the Python interpreter;
  * N = 1, 10, 100 short processes (`true`) run to completion vs a plain Popen/wait loop;
  * SIGINT to exit with 10 sleeping children;
  * parse + check of a 1000-entity file in-process, XML and the same file in YAML (ROS 2
    launch: 1.6 s for the XML one on this machine);
  * a 1000-entity Python launch file, loaded and evaluated, beside ROS 2's own launch doing
    the same in the same run (with --ros-python);
  * the launcher's peak RSS with 100 children.

With --ros-python (the Python of a venv holding the real Jazzy launch stack, built with
../shared/tools/ros2-reference/), ROS's own load + parse_description of the same XML and YAML
files is timed in the same run, in that interpreter.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

LAUNCHKIT = [sys.executable, "-m", "launchkit"]


def median_time(action: Callable[[], object], repeat: int) -> float:
    """Median wall time of ``action`` in seconds."""
    samples = []
    for _ in range(repeat):
        start = time.perf_counter()
        action()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def write(directory: Path, name: str, body: str) -> Path:
    """A launch file with ``body`` inside <launch>."""
    path = directory / name
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    return path


def run_quiet(argv: list[str], env: dict[str, str]) -> None:
    """Run to completion, output discarded, failing loudly."""
    subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, check=True)


def launch_times(path: Path, count: int, env: dict[str, str]) -> tuple[float, float]:
    """Seconds from spawning ``launchkit run`` to its ``count``-th "process started" line, and
    to its exit."""
    start = time.perf_counter()
    proc = subprocess.Popen(
        [*LAUNCHKIT, "run", str(path)], stdout=subprocess.PIPE, text=True, env=env
    )
    assert proc.stdout is not None
    started, all_started = 0, 0.0
    for line in proc.stdout:
        if "process started with pid" in line:
            started += 1
            if started == count:
                all_started = time.perf_counter() - start
    proc.wait()
    return all_started, time.perf_counter() - start


def popen_times(count: int) -> tuple[float, float]:
    """The floor: ``count`` plain Popen calls of ``echo hi``, then waiting for them all."""
    start = time.perf_counter()
    procs = [subprocess.Popen(["echo", "hi"], stdout=subprocess.DEVNULL) for _ in range(count)]
    all_started = time.perf_counter() - start
    for proc in procs:
        proc.wait()
    return all_started, time.perf_counter() - start


def shutdown_time(path: Path, env: dict[str, str]) -> float:
    """Seconds from SIGINT to the launcher's exit, once its 10 children have started."""
    proc = subprocess.Popen(
        [*LAUNCHKIT, "run", str(path)], stdout=subprocess.PIPE, text=True, env=env
    )
    assert proc.stdout is not None
    started = 0
    for line in proc.stdout:
        if "process started with pid" in line:
            started += 1
            if started == 10:
                break
    start = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    proc.communicate(timeout=30)
    return time.perf_counter() - start


def peak_rss_mb(path: Path, env: dict[str, str]) -> float:
    """Peak RSS of a launcher running ``path`` (from its own getrusage, via a wrapper)."""
    code = (
        "import resource, runpy, sys; sys.argv = ['launchkit', 'run', sys.argv[1]];\n"
        "try:\n    runpy.run_module('launchkit', run_name='__main__')\n"
        "except SystemExit:\n    pass\n"
        "print('RSS', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)"
    )
    result = subprocess.run(
        [sys.executable, "-c", code, str(path)],
        capture_output=True,
        text=True,
        env=env,
        check=True,
    )
    line = [x for x in result.stderr.splitlines() if x.startswith("RSS")][-1]
    return int(line.split()[1]) / 1024


BIG_PYTHON = """
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, GroupAction
from launch.actions import SetLaunchConfiguration
from launch.conditions import IfCondition
from launch.substitutions import EnvironmentVariable, LaunchConfiguration


def generate_launch_description():
    entities = [DeclareLaunchArgument('on', default_value='true'),
                DeclareLaunchArgument('base', default_value='b')]
    for i in range(333):
        entities.append(GroupAction([
            SetLaunchConfiguration(f'v{i}', [LaunchConfiguration('base'), f'-{i}']),
            ExecuteProcess(cmd=['echo', LaunchConfiguration(f'v{i}'), EnvironmentVariable('HOME')],
                           name=f'p{i}', output='screen'),
        ], condition=IfCondition(LaunchConfiguration('on'))))
    return LaunchDescription(entities)
"""

#: What ROS 2's launch does with the same file, timed in its own process: load it (run
#: generate_launch_description), then load and run it with the groups off (nothing starts).
ROS_TIMING = """
import statistics, sys, time
from launch import LaunchDescription, LaunchService
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.launch_description_sources import get_launch_description_from_python_launch_file
path, repeat = sys.argv[1], int(sys.argv[2])
def timed(action):
    samples = []
    for _ in range(repeat):
        start = time.perf_counter(); action(); samples.append(time.perf_counter() - start)
    return statistics.median(samples)
def run_off():
    service = LaunchService(argv=['on:=false'])
    service.include_launch_description(LaunchDescription([IncludeLaunchDescription(
        PythonLaunchDescriptionSource(path), launch_arguments={'on': 'false'}.items())]))
    assert service.run() == 0
load = timed(lambda: get_launch_description_from_python_launch_file(path))
print("TIMES", load, timed(run_off))
"""


def python_file_times(
    directory: Path, repeat: int, ros_python: str | None, env: dict[str, str]
) -> None:
    """The 1000-entity Python launch file: launchkit's load + check and load + evaluate (with
    the groups off, as ROS runs it), beside ROS 2's launch in the same run."""
    from launchkit import api
    from launchkit.checks import check_tree
    from launchkit.frontend.launch_loader import LaunchLoader
    from launchkit.packages import PackageIndex

    path = directory / "big.launch.py"
    path.write_text(BIG_PYTHON)
    load = median_time(lambda: check_tree(path, {}, LaunchLoader(), PackageIndex()), repeat)
    entities = check_tree(path, {}, LaunchLoader(), PackageIndex()).entity_count
    evaluate = median_time(lambda: api.describe(path, {"on": "false"}), repeat)
    ros = "not measured (no --ros-python)"
    if ros_python:
        result = subprocess.run(
            [ros_python, "-c", ROS_TIMING, str(path), str(repeat)],
            capture_output=True, text=True, env=env, check=True,
        )  # fmt: skip
        times = [line for line in result.stdout.splitlines() if line.startswith("TIMES")]
        ros_load, ros_run = (float(x) for x in times[-1].split()[1:])
        ros = f"ROS 2 launch, same run: {ros_load * 1000:.0f} ms / {ros_run * 1000:.0f} ms"
    print(
        f"Python file of {entities} entities, load + check / load + evaluate (groups off): "
        f"{load * 1000:.0f} ms / {evaluate * 1000:.0f} ms ({ros})"
    )


ROS_PARSE = """
import statistics, sys, time
from launch.frontend import Parser
samples = []
for _ in range(int(sys.argv[2])):
    start = time.perf_counter()
    root, parser = Parser.load(sys.argv[1])
    parser.parse_description(root)
    samples.append(time.perf_counter() - start)
print(statistics.median(samples))
"""


def big_files(directory: Path) -> tuple[Path, Path]:
    """The same 1004-entity launch file in XML and in YAML: 334 groups with a condition, each
    holding a let and an executable whose command has substitutions (none inside quotes, which
    ROS cannot parse, so that ROS can read the same files)."""
    body = "\n".join(
        f'<group if="$(var on)"><let name="v{i}" value="$(var base)-{i}"/>'
        f'<executable cmd="echo $(var v{i}) $(env HOME)" name="p{i}" output="screen"/>'
        "</group>"
        for i in range(334)
    )
    xml = write(
        directory,
        "big.launch.xml",
        '<arg name="on" default="true"/><arg name="base" default="b"/>\n' + body,
    )
    groups = "".join(
        f"- group:\n    if: $(var on)\n    children:\n"
        f"    - let: {{name: v{i}, value: $(var base)-{i}}}\n"
        f"    - executable: {{cmd: echo $(var v{i}) $(env HOME), name: p{i},"
        " output: screen}\n"
        for i in range(334)
    )
    yaml_file = directory / "big.launch.yaml"
    yaml_file.write_text(
        "launch:\n- arg: {name: 'on', default: 'true'}\n- arg: {name: base, default: b}\n" + groups
    )
    return xml, yaml_file


def ros_parse_time(ros_python: str, path: Path, repeat: int) -> float | str:
    """ROS's median load + parse_description of ``path``, in the reference interpreter (or
    the last line of its error)."""
    # the venv's prefix plays /opt/ros/jazzy (launch finds its grammar through the ament index)
    prefix = str(Path(ros_python).absolute().parents[1])
    result = subprocess.run(
        [ros_python, "-c", ROS_PARSE, str(path), str(repeat)],
        capture_output=True,
        text=True,
        check=False,
        env={**os.environ, "AMENT_PREFIX_PATH": prefix},
    )
    if result.returncode:
        return (result.stderr.strip().splitlines() or ["failed"])[-1]
    return float(result.stdout.split()[-1])


def main() -> None:
    """Run every measurement and print one line each."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--ros-python", help="the Python of a venv with the Jazzy launch stack")
    options = parser.parse_args()
    repeat = options.repeat
    print(
        f"machine: {platform.node()} {platform.machine()} {os.cpu_count()} cores, "
        f"Python {platform.python_version()}; {datetime.date.today()}"
    )
    with tempfile.TemporaryDirectory() as tmp:
        directory = Path(tmp)
        env = {**os.environ, "ROS_LOG_DIR": str(directory / "log")}
        empty = write(directory, "empty.launch.xml", "")
        baseline = median_time(lambda: run_quiet([sys.executable, "-c", "pass"], env), repeat)
        empty_t = median_time(lambda: run_quiet([*LAUNCHKIT, "run", str(empty)], env), repeat)
        print(
            f"empty launch file: {empty_t * 1000:.0f} ms (python -c pass: "
            f"{baseline * 1000:.0f} ms; ros2 launch measured 240 ms fixed cost)"
        )
        for n in (1, 10, 100):
            path = write(directory, f"n{n}.launch.xml", '<executable cmd="echo hi"/>\n' * n)
            runs = [launch_times(path, n, env) for _ in range(repeat)]
            started = statistics.median(r[0] for r in runs)
            finished = statistics.median(r[1] for r in runs)
            floor = [popen_times(n) for _ in range(repeat)]
            floor_started = statistics.median(f[0] for f in floor)
            floor_finished = statistics.median(f[1] for f in floor)
            print(
                f"{n:>3} x echo: all started {started * 1000:.0f} ms, all exited "
                f"{finished * 1000:.0f} ms (Popen loop: {floor_started * 1000:.1f} ms / "
                f"{floor_finished * 1000:.1f} ms); beyond the empty launch: "
                f"{(started - empty_t) * 1000:.0f} ms to start them all"
            )
        sleepers = write(directory, "sleepers.launch.xml", '<executable cmd="sleep 60"/>\n' * 10)
        stop = statistics.median(shutdown_time(sleepers, env) for _ in range(repeat))
        print(f"SIGINT to exit with 10 children: {stop * 1000:.0f} ms")

        from launchkit.checks import check_tree
        from launchkit.frontend.launch_loader import LaunchLoader
        from launchkit.packages import PackageIndex

        for big in big_files(directory):
            check = median_time(
                lambda big=big: check_tree(big, {}, LaunchLoader(), PackageIndex()), repeat
            )
            entities = check_tree(big, {}, LaunchLoader(), PackageIndex()).entity_count
            ros = ""
            if options.ros_python:
                ros_t = ros_parse_time(options.ros_python, big, repeat)
                ros = (
                    f"; ros2 launch in this run: {ros_t * 1000:.0f} ms, {ros_t / check:.0f}x"
                    if isinstance(ros_t, float)
                    else f"; ros2 launch failed: {ros_t}"
                )
            print(
                f"parse + check {entities} entities, {big.suffix[1:].upper()}: "
                f"{check * 1000:.1f} ms (ros2 launch measured 1600 ms for 1000 XML{ros})"
            )
        python_file_times(directory, repeat, options.ros_python, env)
        hundred = write(directory, "sleep100.launch.xml", '<executable cmd="sleep 0.5"/>\n' * 100)
        print(f"launcher peak RSS with 100 children: {peak_rss_mb(hundred, env):.1f} MB")
        imports = median_time(
            lambda: run_quiet([sys.executable, "-c", "import launchkit.api, launchkit.cli"], env),
            repeat,
        )
        print(
            f"python -c 'import launchkit.api, launchkit.cli': {imports * 1000:.0f} ms "
            f"(python -c pass: {baseline * 1000:.0f} ms)"
        )


if __name__ == "__main__":
    main()
