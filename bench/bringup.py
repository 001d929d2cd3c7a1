"""Benchmark: the robot bring-up (run by hand; results go in docs/benchmarks.md).

    python bench/bringup.py [--runs 3] [--seconds 10]

Measures, for `launchkit run robot_wheel gazebo_and_rviz.launch.xml start_rviz:=false`:
  * the time from starting the command to the first /odom message (target <= 3 s; the seed's
    Gazebo flow waits 8 s before it even spawns);
  * the simulator's real-time factor headless with the lidar, unpaced (real_time_factor:=0),
    from /clock (target >= 20x);
  * with the seed's 800x800 30 Hz camera subscribed, for TinyRenderer and EGL (egl:=true), the
    server unpaced (real_time_factor:=0) and paced at 1.0: the real-time factor (target >= 1.0x)
    and the camera frames received per wall second and per sim second (30 nominal), over
    ``--seconds`` of wall time after the first frame, ``--runs`` times each;
  * the total resident memory of the bring-up (launcher, router, every node).
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any


def free_port() -> int:
    """A free TCP port on loopback."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


class BringUp:
    """One robot launch on its own router, and a probe node of this process on its network."""

    def __init__(self, *args: str, env: dict[str, str] | None = None) -> None:
        """Start the launch with ``args`` (``env``: variables to add, e.g. ``PYTHONPATH`` of
        another tree; the launch then runs from the temporary folder, so that the current
        folder cannot shadow that tree)."""
        import launchkit.ros as ros

        self.ros = ros
        self.router = f"tcp/127.0.0.1:{free_port()}"
        self.log_dir = tempfile.mkdtemp(prefix="bringup-")
        env = {
            **os.environ,
            **(env or {}),
            "LAUNCHKIT_ROUTER": self.router,
            "ROS_LOG_DIR": self.log_dir,
        }
        self.started = time.perf_counter()
        self.proc = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "launchkit",
                "run",
                "--router",
                self.router,
                "robot_wheel",
                "gazebo_and_rviz.launch.xml",
                "start_rviz:=false",
                *args,
            ],
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
            cwd=tempfile.gettempdir(),
        )
        # start_router=False: the launch hosts the router; the probe must not start one first
        self.context = ros.Context(router=self.router, start_router=False)
        self.context.init([], 0)
        self.node = ros.Node("bench_probe", context=self.context, enable_rosout=False)

    def first(self, msg_type: Any, topic: str, timeout: float = 60.0) -> tuple[Any, float]:
        """The first message on ``topic`` and the seconds since the launch started."""
        got: list[Any] = []
        qos = self.ros.qos_profile_sensor_data
        sub = self.node.create_subscription(msg_type, topic, got.append, qos)
        deadline = time.monotonic() + timeout
        while not got and time.monotonic() < deadline:
            self.ros.spin_once(self.node, timeout_sec=0.01)
        self.node.destroy_subscription(sub)
        if not got:
            raise SystemExit(f"no message on {topic} within {timeout} s")
        return got[0], time.perf_counter() - self.started

    def real_time_factor(self, seconds: float) -> float:
        """Simulated seconds per wall second, from /clock, over ``seconds``."""
        from launchkit.ros.msgs.rosgraph_msgs.msg import Clock

        first, t0 = self.first(Clock, "/clock")
        time.sleep(seconds)
        last, t1 = self.first(Clock, "/clock")
        sim = (last.clock.sec - first.clock.sec) + (last.clock.nanosec - first.clock.nanosec) / 1e9
        return sim / (t1 - t0)

    def with_camera(self, seconds: float) -> tuple[float, float, float]:
        """(real-time factor, frames per wall s, frames per sim s) with the image subscribed.

        Images are counted undecoded, so the probe's own cost stays small.
        """
        from launchkit.ros.msgs.rosgraph_msgs.msg import Clock
        from launchkit.ros.msgs.sensor_msgs.msg import Image

        frames = [0]
        clock: list[Any] = []

        def count(_data: bytes) -> None:
            frames[0] += 1

        qos = self.ros.qos_profile_sensor_data
        self.node.create_subscription(Image, "/camera1/image_raw", count, qos, raw=True)
        self.node.create_subscription(Clock, "/clock", clock.append, qos)
        self._spin_until(lambda: frames[0] > 0 and bool(clock), 60, "a camera image and /clock")
        f0, c0, t0 = frames[0], _seconds(clock[-1]), time.perf_counter()
        self._spin_until(lambda: time.perf_counter() - t0 >= seconds, seconds + 5, "the window")
        f1, c1, t1 = frames[0], _seconds(clock[-1]), time.perf_counter()
        return (c1 - c0) / (t1 - t0), (f1 - f0) / (t1 - t0), (f1 - f0) / max(c1 - c0, 1e-9)

    def _spin_until(self, done: Any, timeout: float, what: str) -> None:
        deadline = time.monotonic() + timeout
        while not done():
            if time.monotonic() > deadline:
                raise SystemExit(f"no {what} within {timeout} s")
            self.ros.spin_once(self.node, timeout_sec=0.01)

    def memory_mb(self) -> float:
        """Resident memory of every process in the launch's sessions, in MB."""
        total = 0
        sessions = {self.proc.pid}
        for pid_dir in Path("/proc").iterdir():
            if not pid_dir.name.isdigit():
                continue
            try:
                stat = (pid_dir / "stat").read_text()
                status = (pid_dir / "status").read_text()
            except OSError:
                continue
            fields = stat.rsplit(")", 1)[1].split()
            ppid, sid = int(fields[1]), int(fields[3])
            if sid in sessions or ppid == self.proc.pid or self._descends(int(pid_dir.name)):
                for line in status.splitlines():
                    if line.startswith("VmRSS:"):
                        total += int(line.split()[1])
        return total / 1024

    def _descends(self, pid: int) -> bool:
        while pid > 1:
            if pid == self.proc.pid:
                return True
            try:
                stat = Path(f"/proc/{pid}/stat").read_text()
            except OSError:
                return False
            pid = int(stat.rsplit(")", 1)[1].split()[1])
        return False

    def stop(self) -> None:
        """Ctrl-C the launch and leave its network."""
        self.node.destroy_node()
        self.context.shutdown()
        os.kill(self.proc.pid, signal.SIGINT)
        self.proc.wait(30)


def _seconds(clock: Any) -> float:
    return float(clock.clock.sec) + float(clock.clock.nanosec) * 1e-9


def camera_case(egl: bool, rtf: str, seconds: float) -> tuple[float, float, float]:
    """One bring-up with the camera subscribed: see :meth:`BringUp.with_camera`."""
    from launchkit.ros.msgs.nav_msgs.msg import Odometry

    bring = BringUp(f"real_time_factor:={rtf}", f"egl:={str(egl).lower()}")
    try:
        bring.first(Odometry, "/odom")
        return bring.with_camera(seconds)
    finally:
        bring.stop()


def main() -> None:
    """Run each measurement and print it."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="runs of each camera case")
    parser.add_argument("--seconds", type=float, default=10.0, help="camera window, wall s")
    args = parser.parse_args()
    print(
        f"machine: {platform.node()} {platform.machine()} {os.cpu_count()} cores, "
        f"Python {platform.python_version()}; {datetime.date.today()}"
    )
    from launchkit.ros.msgs.nav_msgs.msg import Odometry

    paced = BringUp()
    try:
        _, to_odom = paced.first(Odometry, "/odom")
        print(f"launchkit run -> first /odom: {to_odom:.2f} s (target <= 3 s)")
        time.sleep(3)
        print(f"bring-up resident memory: {paced.memory_mb():.0f} MB")
        print(f"paced real-time factor: {paced.real_time_factor(3):.2f}x")
    finally:
        paced.stop()
    fast = BringUp("real_time_factor:=0")
    try:
        fast.first(Odometry, "/odom")
        print(
            f"unpaced real-time factor, lidar only: {fast.real_time_factor(5):.1f}x (target >= 20x)"
        )
    finally:
        fast.stop()
    for run in range(1, args.runs + 1):
        for egl in (False, True):
            for rtf in ("0", "1.0"):
                factor, per_wall, per_sim = camera_case(egl, rtf, args.seconds)
                print(
                    f"run {run}: 800x800 camera subscribed, "
                    f"{'EGL' if egl else 'TinyRenderer':12s} "
                    f"{'unpaced' if rtf == '0' else 'paced 1.0'}: real-time factor "
                    f"{factor:.2f}x (target >= 1.0x), {per_wall:.1f} frames per wall s, "
                    f"{per_sim:.1f} per sim s (30 nominal)",
                    flush=True,
                )


if __name__ == "__main__":
    main()
