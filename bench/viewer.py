"""Benchmark: the browser viewer of the robot launch (run by hand; results go in
docs/benchmarks.md).

    python bench/viewer.py [--seconds 10] [--runs 3]

Brings up `launchkit run robot_wheel gazebo_and_rviz.launch.xml world:=obstacles` with the
viewer on a free port and measures, with Debian's headless chromium driven by playwright:
  * the robot launch's CPU (all its processes, in cores) with no page open, with one page open
    (the robot.rviz view: model, TF, scan, odometry) and with the camera shown in the image
    panel; chromium's own CPU beside it;
  * the time from opening the page to the first frame with the robot drawn (target <= 2 s),
    ``--runs`` times, each in a fresh browser context (nothing cached);
  * the frames per second the page draws while /tf streams at 50 Hz (this benchmark publishes
    an extra moving frame at 50 Hz beside the launch's own /tf), with /scan and /odom;
  * the camera frames per second the page shows (target >= 10 with the seed's 800x800 camera);
  * the server side of the page protocol: microseconds to turn one message into what the page
    gets (CDR decode + compact JSON), per message type.
"""

from __future__ import annotations

import argparse
import datetime
import http.client
import math
import os
import platform
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

TICKS = os.sysconf("SC_CLK_TCK")
FLAGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def free_port() -> int:
    """A free TCP port on loopback."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _stat(pid: int) -> tuple[int, float] | None:
    """(parent pid, CPU seconds so far) of a process."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return int(fields[1]), (int(fields[11]) + int(fields[12])) / TICKS


def descendants(root: int) -> dict[int, float]:
    """CPU seconds of ``root`` and every process below it."""
    stats = {int(p.name): _stat(int(p.name)) for p in Path("/proc").iterdir() if p.name.isdigit()}
    found = {root}
    changed = True
    while changed:
        changed = False
        for pid, stat in stats.items():
            if stat is not None and stat[0] in found and pid not in found:
                found.add(pid)
                changed = True
    return {pid: stats[pid][1] for pid in found if stats.get(pid) is not None}  # type: ignore[index]


def _used(before: dict[int, float], after: dict[int, float]) -> float:
    return sum(after.values()) - sum(before.get(pid, 0.0) for pid in after)


def cpu_cores(root: int, seconds: float, wait: Any = time.sleep) -> float:
    """The cores ``root``'s process tree used over ``seconds`` of wall time."""
    return cpu_split(root, root, seconds, wait)[0]


def cpu_split(launch: int, me: int, seconds: float, wait: Any = time.sleep) -> tuple[float, float]:
    """(cores of the launch's tree, cores of the rest of ``me``'s tree: chromium, this script)
    over ``seconds``; ``wait(seconds)`` passes the time (playwright's, to keep the page alive)."""
    launch0, all0, t0 = descendants(launch), descendants(me), time.monotonic()
    wait(seconds)
    launch1, all1, t1 = descendants(launch), descendants(me), time.monotonic()
    ours = _used(launch0, launch1)
    rest = _used(all0, all1) - ours if launch != me else 0.0
    return ours / (t1 - t0), rest / (t1 - t0)


class RobotLaunch:
    """The robot launch with its viewer, on a private router."""

    def __init__(self) -> None:
        self.router = f"tcp/127.0.0.1:{free_port()}"
        self.port = free_port()
        self.log = tempfile.NamedTemporaryFile("w+", prefix="viewer-bench-", suffix=".log")
        env = {**os.environ, "LAUNCHKIT_ROUTER": self.router}
        self.proc = subprocess.Popen(
            [
                *(sys.executable, "-m", "launchkit", "run", "--router", self.router),
                *("robot_wheel", "gazebo_and_rviz.launch.xml", "world:=obstacles"),
                f"viewer_port:={self.port}",
            ],
            env=env,
            stdout=self.log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        self.url = f"http://127.0.0.1:{self.port}/"

    def wait_ready(self, timeout: float = 90.0) -> None:
        """Until the viewer serves and the robot has spawned (/odom flows)."""
        deadline = time.monotonic() + timeout
        while "SpawnEntity: Successfully spawned" not in Path(self.log.name).read_text():
            if time.monotonic() > deadline or self.proc.poll() is not None:
                raise SystemExit(f"the launch did not come up: see {self.log.name}")
            time.sleep(0.2)
        while True:
            try:
                connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=2)
                connection.request("GET", "/")
                if connection.getresponse().status == 200:
                    return
            except OSError:
                pass
            if time.monotonic() > deadline:
                raise SystemExit("the viewer did not answer")
            time.sleep(0.2)

    def stop(self) -> None:
        """Ctrl-C the launch."""
        os.kill(self.proc.pid, signal.SIGINT)
        self.proc.wait(30)


class ExtraTf:
    """Publishes a moving frame on /tf at 50 Hz beside the launch (so /tf streams at 50 Hz)."""

    def __init__(self, router: str) -> None:
        from launchkit.ros.msgs.tf2_msgs.msg import TFMessage

        import launchkit.ros as ros

        self.ros = ros
        self.context = ros.Context(router=router)
        self.context.init([], 0)
        self.node = ros.Node("bench_tf", context=self.context, enable_rosout=False)
        self.publisher = self.node.create_publisher(TFMessage, "/tf", 10)
        self.stop_flag = threading.Event()
        self.sent = 0
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self) -> None:
        from launchkit.ros.msgs.geometry_msgs.msg import TransformStamped
        from launchkit.ros.msgs.tf2_msgs.msg import TFMessage

        start = time.monotonic()
        while not self.stop_flag.wait(0.02):
            t = time.monotonic() - start
            transform = TransformStamped(child_frame_id="bench_marker")
            transform.header.frame_id = "odom"
            transform.transform.translation.x = math.cos(t)
            transform.transform.translation.y = math.sin(t)
            transform.transform.rotation.w = 1.0
            self.publisher.publish(TFMessage(transforms=[transform]))
            self.sent += 1

    def close(self) -> None:
        """Stop publishing and leave the network."""
        self.stop_flag.set()
        self.thread.join(5)
        self.node.destroy_node()
        self.context.shutdown()


def page_window(page: Any, seconds: float) -> dict[str, float]:
    """Frames drawn, camera frames shown and their rates over ``seconds``."""
    s0 = page.evaluate("window.__viewer.stats")
    t0 = time.monotonic()
    page.wait_for_timeout(seconds * 1000)
    s1 = page.evaluate("window.__viewer.stats")
    wall = time.monotonic() - t0
    return {
        "fps": (s1["frames"] - s0["frames"]) / wall,
        "camera_fps": (s1["imageFrames"] - s0["imageFrames"]) / wall,
        "tf_per_s": (s1["tfMessages"] - s0["tfMessages"]) / wall,
        "scan_per_s": (s1["scanMessages"] - s0["scanMessages"]) / wall,
        "odom_per_s": (s1["odomMessages"] - s0["odomMessages"]) / wall,
    }


def decode_costs() -> None:
    """Microseconds per message for the page protocol's conversion, by type."""
    import numpy as np

    from launchkit.ros.msgs import get_message, serialize
    from launchkit.stock.rviz2.convert import to_page

    transform = get_message("geometry_msgs/msg/TransformStamped")(child_frame_id="wheel")
    samples = {
        "tf2_msgs/msg/TFMessage (3 transforms)": (
            "tf2_msgs/msg/TFMessage",
            get_message("tf2_msgs/msg/TFMessage")(transforms=[transform] * 3),
        ),
        "sensor_msgs/msg/LaserScan (360 ranges)": (
            "sensor_msgs/msg/LaserScan",
            get_message("sensor_msgs/msg/LaserScan")(ranges=np.full(360, 2.5, np.float32)),
        ),
        "nav_msgs/msg/Odometry": ("nav_msgs/msg/Odometry", get_message("nav_msgs/msg/Odometry")()),
        "sensor_msgs/msg/Image (800x800 rgb8)": (
            "sensor_msgs/msg/Image",
            get_message("sensor_msgs/msg/Image")(
                width=800, height=800, encoding="rgb8", step=2400, data=bytes(1920000)
            ),
        ),
    }
    for label, (type_name, message) in samples.items():
        payload = serialize(message, type_name)
        runs = 200 if "Image" in label else 3000
        start = time.perf_counter()
        for _ in range(runs):
            to_page("/bench", type_name, payload)
        print(f"  {label}: {(time.perf_counter() - start) / runs * 1e6:.0f} us")


def main() -> None:
    """Run each measurement and print it."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=10.0, help="each measuring window")
    parser.add_argument("--runs", type=int, default=3, help="page loads timed")
    args = parser.parse_args()
    print(
        f"machine: {platform.node()} {platform.machine()} {os.cpu_count()} cores, "
        f"Python {platform.python_version()}; {datetime.datetime.now():%Y-%m-%d %H:%M}; "
        f"load average {os.getloadavg()[0]:.1f}"
    )
    print("page protocol, server side (CDR -> what the page gets), per message:")
    decode_costs()
    chromium = shutil.which("chromium")
    if chromium is None:
        raise SystemExit("needs Debian's chromium (apt-get install chromium)")
    from playwright.sync_api import sync_playwright

    launch = RobotLaunch()
    extra: ExtraTf | None = None
    try:
        launch.wait_ready()
        time.sleep(3)  # let start-up work settle
        print(
            f"robot launch CPU, no page open: {cpu_cores(launch.proc.pid, args.seconds):.2f} cores"
        )
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=chromium, args=FLAGS)
            me = os.getpid()
            for run in range(args.runs):
                context = browser.new_context(viewport={"width": 1100, "height": 700})
                page = context.new_page()
                start = time.monotonic()
                page.goto(launch.url)
                page.wait_for_function("window.__viewer && window.__viewer.stats.robotLinks >= 6")
                wall = time.monotonic() - start
                first = page.evaluate("window.__viewer.stats.firstRobotMs")
                print(
                    f"page open -> robot drawn, run {run + 1}: {wall:.2f} s "
                    f"(first drawn frame {first / 1000:.2f} s after navigation start)"
                )
                if run < args.runs - 1:
                    context.close()
            pause = lambda seconds: page.wait_for_timeout(seconds * 1000)  # noqa: E731
            pause(2)
            launch_cpu, browser_cpu = cpu_split(launch.proc.pid, me, args.seconds, pause)
            print(
                f"robot launch CPU, one page open: {launch_cpu:.2f} cores "
                f"(chromium and this script: {browser_cpu:.2f})"
            )
            extra = ExtraTf(launch.router)
            page.wait_for_timeout(2000)
            window = page_window(page, args.seconds)
            print(
                "page with /tf at 50 Hz (+ the launch's own), /scan, /odom: "
                f"{window['fps']:.1f} frames drawn per s (config Frame Rate 30); "
                f"received per s: /tf {window['tf_per_s']:.0f}, /scan {window['scan_per_s']:.1f}, "
                f"/odom {window['odom_per_s']:.1f}"
            )
            extra.close()
            extra = None
            page.evaluate("window.__viewer.showImage('/camera1/image_raw')")
            page.wait_for_function("window.__viewer.stats.imageFrames >= 5", timeout=60000)
            pause(2)
            window = page_window(page, args.seconds)
            arriving = page.evaluate("window.__viewer.rates()['/camera1/image_raw']")
            print(
                f"camera frames shown in the page: {window['camera_fps']:.1f} per s "
                f"(page says {page.evaluate('window.__viewer.stats.imageFps')}; target >= 10); "
                f"the camera delivered {arriving:.1f} per s to rviz2; "
                f"page drew {window['fps']:.1f} frames per s"
            )
            launch_cpu, browser_cpu = cpu_split(launch.proc.pid, me, args.seconds, pause)
            print(
                f"robot launch CPU, page with the camera shown: {launch_cpu:.2f} cores "
                f"(chromium and this script: {browser_cpu:.2f})"
            )
            browser.close()
        time.sleep(3)
        print(
            "robot launch CPU, page closed again: "
            f"{cpu_cores(launch.proc.pid, args.seconds):.2f} cores"
        )
        print(f"load average at the end: {os.getloadavg()[0]:.1f}")
    finally:
        if extra is not None:
            extra.close()
        launch.stop()


if __name__ == "__main__":
    main()
