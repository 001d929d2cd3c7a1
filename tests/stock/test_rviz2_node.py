"""rviz2 as a process: a Foxglove client receives /robot_description, /tf and /scan."""

from __future__ import annotations

import queue
import threading
import time
from pathlib import Path
from typing import Any

from launchkit.ros.msgs.geometry_msgs.msg import TransformStamped
from launchkit.ros.msgs.sensor_msgs.msg import LaserScan
from launchkit.ros.msgs.std_msgs.msg import String
from launchkit.ros.msgs.tf2_msgs.msg import TFMessage

import launchkit.ros as ros
from launchkit.ros.msgs import deserialize
from tests.stock.conftest import Processes, free_port, latched
from tests.stock.foxglove_client import receive_topics

URDF = (Path(__file__).parents[2] / "urdf" / "three_wheeled_robot.urdf").read_text()
CONFIG = Path(__file__).parents[2] / "config" / "robot.rviz"  # robot_wheel's
TOPICS = ["/robot_description", "/tf", "/scan"]


def _read_until(proc: Any, text: str, timeout: float = 20.0) -> str:
    """rviz2's output up to the line containing ``text``; fails after ``timeout`` s or on exit."""
    lines: queue.Queue[str] = queue.Queue()
    assert proc.stdout is not None
    stdout = proc.stdout
    threading.Thread(target=lambda: [lines.put(line) for line in stdout], daemon=True).start()
    seen = []
    deadline = time.monotonic() + timeout
    while not seen or text not in seen[-1]:
        left = deadline - time.monotonic()
        if left <= 0 or (proc.poll() is not None and lines.empty()):
            raise AssertionError(f"rviz2 did not print {text!r} (exit {proc.poll()}): {seen}")
        try:
            seen.append(lines.get(timeout=min(left, 0.5)))
        except queue.Empty:
            continue
    return "".join(seen)


def test_late_foxglove_client_gets_latched_and_live_topics(
    processes: Processes, probe: Any
) -> None:
    description = probe.create_publisher(String, "/robot_description", latched())
    description.publish(String(data=URDF))
    tf = probe.create_publisher(TFMessage, "/tf", 10)
    scan = probe.create_publisher(LaserScan, "/scan", ros.qos_profile_sensor_data)
    port = free_port()
    proc = processes.start("launchkit.stock.rviz2.node", "-d", str(CONFIG), "--port", str(port))
    printed = _read_until(proc, "Foxglove desktop")
    assert f"ws://127.0.0.1:{port}" in printed
    assert "app.foxglove.dev" in printed

    transform = TFMessage(transforms=[TransformStamped(child_frame_id="wheel_left_link")])
    laser = LaserScan(ranges=[1.0] * 360, range_max=12.0)
    stop = threading.Event()

    def keep_publishing() -> None:  # live topics reach a client only once it is subscribed
        while not stop.wait(0.05):
            tf.publish(transform)
            scan.publish(laser)

    publisher = threading.Thread(target=keep_publishing)
    publisher.start()

    try:
        client = receive_topics(f"ws://127.0.0.1:{port}", list(TOPICS))
    finally:
        stop.set()
        publisher.join()
    assert client.channels["/tf"]["schemaName"] == "tf2_msgs/msg/TFMessage"
    got = deserialize(client.received["/robot_description"][0], "std_msgs/msg/String")
    assert got.data == URDF
    tf_got = deserialize(client.received["/tf"][0], "tf2_msgs/msg/TFMessage")
    assert tf_got.transforms[0].child_frame_id == "wheel_left_link"
    assert len(deserialize(client.received["/scan"][0], "sensor_msgs/msg/LaserScan").ranges) == 360


def test_missing_config_is_one_line_exit_2(processes: Processes, tmp_path: Path) -> None:
    proc = processes.start("launchkit.stock.rviz2.node", "-d", str(tmp_path / "none.rviz"))
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 2
    assert "cannot read the display config" in err and "Traceback" not in err
