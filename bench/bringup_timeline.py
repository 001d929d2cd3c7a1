"""Where README line 1's bring-up spends its time: one timeline per run (run by hand).

    python bench/bringup_timeline.py [--runs 3] [--before DIR]

Runs ``launchkit run robot_wheel gazebo_and_rviz.launch.xml start_rviz:=false`` with its output
read line by line, and prints when (seconds since the command started) the launcher was ready,
each process started, gzserver had its world, spawn_entity.py waited for and called
``/spawn_entity``, the diff drive was started and logged its first line, and the first /odom
arrived (with its frame ids, stamp and position, which must be the spawn point's), and the CPU
time every process of the launch had used by then.
``--before DIR`` alternates runs with an older tree's ``launchkit`` package (as
``bench/user_waits.py --before``).
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bringup

LAUNCH = [sys.executable, "-m", "launchkit", "run"]
README_LINE_1 = ["robot_wheel", "gazebo_and_rviz.launch.xml", "start_rviz:=false"]
MARKS = {
    "All log files can be found": "launcher ready",
    "[gzserver-1]: process started": "gzserver started",
    "[spawn_entity.py-2]: process started": "spawn_entity.py started",
    "world 'default' loaded": "gzserver: world loaded, services up",
    "Waiting for service /spawn_entity": "spawn_entity.py: imported, waits",
    "Calling service /spawn_entity": "spawn_entity.py: calls",
    "[gazebo_base_controller-4]: process started": "diff drive started",
    "[gazebo]: SpawnEntity: Successfully spawned": "gzserver: spawned, answers",
    "driving 'my_robot'": "diff drive: node up",
}


def timeline(extra_env: dict[str, str]) -> list[tuple[float, str]]:
    """One bring-up's marks, in order, ending with the first /odom."""
    from launchkit.ros.msgs.nav_msgs.msg import Odometry

    import launchkit.ros as ros

    router = f"tcp/127.0.0.1:{bringup.free_port()}"
    env = {**os.environ, **extra_env, "LAUNCHKIT_ROUTER": router}
    env["ROS_LOG_DIR"] = tempfile.mkdtemp(prefix="bringup-")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    start = time.perf_counter()
    proc = subprocess.Popen(
        [*LAUNCH, "--router", router, *README_LINE_1],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
        cwd=tempfile.gettempdir(),
    )
    marks: list[tuple[float, str]] = []

    def read() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            for key, what in MARKS.items():
                if key in line:
                    marks.append((time.perf_counter() - start, what))

    threading.Thread(target=read, daemon=True).start()
    context = ros.Context(router=router, start_router=False)
    context.init([], 0)
    node = ros.Node("timeline_probe", context=context, enable_rosout=False)
    got: list[tuple[float, object]] = []
    node.create_subscription(
        Odometry,
        "/odom",
        lambda m: got.append((time.perf_counter() - start, m)),
        ros.qos_profile_sensor_data,
    )
    deadline = time.monotonic() + 60
    while not got and time.monotonic() < deadline:
        ros.spin_once(node, timeout_sec=0.01)
    cpu = tree_cpu(proc.pid)
    time.sleep(0.3)  # the lines written just before
    node.destroy_node()
    context.shutdown()
    os.killpg(proc.pid, signal.SIGINT)
    proc.wait(30)
    if not got:
        raise SystemExit("no /odom within 60 s")
    at, msg = got[0]
    odom: Any = msg
    p, s = odom.pose.pose.position, odom.header.stamp
    marks.append(
        (
            at,
            f"first /odom: {odom.header.frame_id} -> {odom.child_frame_id}, stamp "
            f"{s.sec + s.nanosec * 1e-9:.3f} s sim, at ({p.x:.3f}, {p.y:.3f}, {p.z:.3f})",
        )
    )
    marks.append((at, f"CPU of every process of the launch by then: {cpu[0]:.2f} s: {cpu[1]}"))
    return sorted(marks)


def tree_cpu(root: int) -> tuple[float, str]:
    """CPU seconds of ``root`` and every process under it, including the children they have
    reaped (spawn_entity.py has exited by the first /odom), and each process's share."""
    parents: dict[int, int] = {}
    cpu: dict[int, tuple[float, float]] = {}
    commands: dict[int, str] = {}
    tick = os.sysconf("SC_CLK_TCK")
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            commands[int(entry.name)] = (entry / "cmdline").read_text()
        except OSError:
            continue
        pid = int(entry.name)
        parents[pid] = int(fields[1])
        own = (int(fields[11]) + int(fields[12])) / tick  # utime stime
        cpu[pid] = (own, (int(fields[13]) + int(fields[14])) / tick)  # cutime cstime

    def under(pid: int) -> bool:
        while pid > 1:
            if pid == root:
                return True
            pid = parents.get(pid, 0)
        return False

    def module_of(argv: list[str]) -> str:
        parts = argv[argv.index("-m") + 1].split(".") if "-m" in argv else [argv[0]]
        return parts[-2] if parts[-1] == "node" and len(parts) > 1 else parts[-1]

    def name(pid: int) -> str:
        return "launcher" if pid == root else module_of(commands[pid].split("\0"))

    ours = sorted(pid for pid in cpu if under(pid))
    total = sum(sum(cpu[pid]) for pid in ours)
    shares = ", ".join(
        f"{name(pid)} {cpu[pid][0]:.2f}" + (f" (+{cpu[pid][1]:.2f} reaped)" if cpu[pid][1] else "")
        for pid in ours
    )
    return total, shares


def main() -> None:
    """Print the timelines."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--before", type=Path, help="a folder with an older launchkit package")
    args = parser.parse_args()
    trees = [("this tree", {})]
    if args.before is not None:
        trees.append(("--before", {"PYTHONPATH": str(args.before.resolve())}))
    for run in range(1, args.runs + 1):
        for name, env in trees:
            print(f"# run {run}, {name}, load {os.getloadavg()[0]:.1f}", flush=True)
            for at, what in timeline(env):
                print(f"{at:6.2f} s  {what}", flush=True)


if __name__ == "__main__":
    main()
