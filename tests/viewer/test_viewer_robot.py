"""The robot launch's viewer in a real browser: README line 1, then open the printed address.

One robot launch (the obstacle world, the viewer on a free port) and one scenario, step by
step, as a user would go: the console names the viewer; with no page open the camera renders
nothing; a page draws the robot (pixels where its wheels project differ from the background and
go when the model is hidden), the scan and the camera image; a key press in the page drives the
robot; Foxglove clients get the same topics; when the page closes the camera stops again.

``LAUNCHKIT_VIEWER_SCREENSHOT=docs/viewer.png pytest tests/viewer/test_viewer_robot.py``
refreshes the picture in docs/viewer.md.
"""

from __future__ import annotations

import os
import shutil
import threading
import time
from pathlib import Path
from typing import Any

import pytest

import launchkit.ros as ros
from launchkit.ros.msgs import deserialize
from tests.stock.foxglove_client import receive_topics
from tests.viewer.conftest import Viewer

pytestmark = pytest.mark.long  # started first: see tests/conftest.py

CAMERA = "/camera1/image_raw"
LINKS = ["wheel_left_link", "wheel_right_link", "caster", "base", "lidar", "camera"]


@pytest.fixture(scope="module")
def robot(launch_module: Any) -> Any:
    """gazebo_and_rviz.launch.xml with the obstacle world and the viewer on a free port."""
    return launch_module(
        "robot_wheel", "gazebo_and_rviz.launch.xml", args={"world": "obstacles"}, ready_timeout=60
    )


def subscribers(handle: Any, topic: str) -> int:
    """How many subscriptions ``topic`` has in the launch's graph, as a ROS tool sees it."""
    context = ros.Context(router=handle.router)
    context.init([], handle.domain_id)
    node = ros.Node("viewer_test_probe", context=context, enable_rosout=False)
    try:
        # the graph arrives in one batch: once the topic's publisher shows, its subscribers do
        assert node.context.graph.wait_for(lambda: node.count_publishers(topic) > 0, 30), topic
        return int(node.count_subscribers(topic))
    finally:
        node.destroy_node()
        context.shutdown()


def foxglove_view(url: str) -> Any:
    """What a Foxglove client gets (run in a thread: playwright owns this one's event loop)."""
    result: dict[str, Any] = {}

    def run() -> None:
        try:
            # the camera's process starts after the robot is spawned: wait for its topic too
            # (advertised only: subscribing would make it render)
            result["client"] = receive_topics(
                url, ["/robot_description", "/tf", "/scan"], 60, advertised=(CAMERA,)
            )
        except BaseException as error:  # re-raised in the test's thread
            result["error"] = error

    thread = threading.Thread(target=run)
    thread.start()
    thread.join(90)
    if "error" in result:
        raise result["error"]
    return result["client"]


def robot_pixels(viewer: Viewer) -> tuple[list[Any], list[Any], list[Any]]:
    """Where the links' origins project, and the colours there with the model shown and hidden,
    every other display (grid, TF axes, scan, odometry) hidden for both pictures."""
    others = ["Grid", "TF", "LaserScan", "Odometry"]
    points = viewer.page.evaluate(f"{LINKS}.map(f => window.__viewer.project(f))")
    viewer.page.evaluate(f"{others}.forEach(d => window.__viewer.setDisplay(d, false))")
    shown = viewer.page.evaluate("p => window.__viewer.sample(p)", points)
    viewer.page.evaluate("window.__viewer.setDisplay('RobotModel', false)")
    hidden = viewer.page.evaluate("p => window.__viewer.sample(p)", points)
    viewer.page.evaluate("window.__viewer.setDisplay('RobotModel', true)")
    viewer.page.evaluate(f"{others}.forEach(d => window.__viewer.setDisplay(d, true))")
    return points, shown, hidden


def distance(a: list[int], b: list[int]) -> int:
    """The largest difference of two colours' channels."""
    return max(abs(x - y) for x, y in zip(a, b, strict=True))


def test_a_page_shows_and_drives_the_robot_and_the_camera_renders_only_for_it(
    robot: Any, open_viewer: Any
) -> None:
    url = f"http://127.0.0.1:{robot.viewer_port}/"
    rviz2 = robot.process("rviz2")
    camera = robot.process("camera_controller")

    # 1. the console names the address, whatever rviz2's output (here "log": not on screen)
    rviz2.wait_output("Foxglove WebSocket on", timeout=60)  # printed after the announcement
    # the launcher prints it as the bring-up's last line, once its console has settled
    deadline = time.monotonic() + 30
    while f"]: viewer: {url}" not in (console := robot.launcher_log.read_text()):
        assert time.monotonic() < deadline, console[-3000:]
        time.sleep(0.1)

    # 2. Foxglove clients see every topic (the camera's too) and get what they subscribe to ...
    client = foxglove_view(f"ws://127.0.0.1:{robot.viewer_port}")
    assert CAMERA in client.channels
    description = deserialize(client.received["/robot_description"][0], "std_msgs/msg/String")
    assert "three_wheeled_robot" in description.data
    frames = {
        t.child_frame_id
        for raw in client.received["/tf"]
        for t in deserialize(raw, "tf2_msgs/msg/TFMessage").transforms
    }
    assert frames & {"base", "wheel_left_link", "wheel_right_link"}, frames
    scan = deserialize(client.received["/scan"][0], "sensor_msgs/msg/LaserScan")
    assert len(scan.ranges) == 360 and scan.header.frame_id == "lidar"
    # ... and with no page open nothing subscribes to the camera, which renders nothing
    assert subscribers(robot, CAMERA) == 0
    assert not [line for line in camera.output if "image subscribed: rendering" in line]

    # 3. a page draws the robot: its links posed from TF in the fixed frame, in pixels
    viewer = open_viewer(url)
    viewer.wait("s.connected && s.robotLinks >= 6", "the robot's six links drawn")
    stats = viewer.stats()
    assert stats["fixedFrame"] == "odom" and stats["robotName"] == "three_wheeled_robot"
    points, shown, hidden = robot_pixels(viewer)
    background = viewer.page.evaluate("window.__viewer.background()")
    on_screen = [p for p in points if p and p["visible"]]
    assert len(on_screen) == len(LINKS), points
    # the white wheel, the lidar and the camera stand out; the dark grey base barely does
    changed = [i for i in range(len(LINKS)) if distance(shown[i], hidden[i]) > 40]
    seen = list(zip(LINKS, shown, hidden, strict=True))
    assert len(changed) >= 2, f"the model changes too few pixels: {seen}"
    assert all(distance(colour, background) < 10 for colour in hidden), (seen, background)

    # 4. the laser scan is drawn as points
    viewer.wait("s.scanMessages >= 3 && s.scanPoints > 0", "scan points (obstacles in range)")

    # 5. the image panel: the camera renders only now, and the page draws its frames
    # the config's Image display is disabled: tick it, as a user would
    viewer.page.locator("#displays label", has_text=CAMERA).locator("input").check()
    camera.wait_output("image subscribed: rendering", timeout=60)
    viewer.wait("s.imageFrames >= 5", "five camera frames in the image panel")
    first = viewer.stats()["imageFrames"]
    viewer.wait(f"s.imageFrames >= {first + 3}", "the image panel to keep updating")
    lit = viewer.page.evaluate(
        "(() => { const c = document.getElementById('image'); const d = c.getContext('2d')"
        ".getImageData(0, 0, c.width, c.height).data; let n = 0;"
        " for (let i = 0; i < d.length; i += 4000) n += d[i] + d[i + 1] + d[i + 2]; return n; })()"
    )
    assert lit > 0, "the camera image is black"
    shot = viewer.screenshot("viewer")
    if os.environ.get("LAUNCHKIT_VIEWER_SCREENSHOT"):
        shutil.copyfile(shot, Path(os.environ["LAUNCHKIT_VIEWER_SCREENSHOT"]))

    # 6. holding "i" in the page drives the robot (teleop_twist_keyboard's +x: 0.5 m/s), which
    # the seed's wheel axes turn into backwards, toward -x, as the drive panel says
    assert "drives backwards" in viewer.page.locator("#drive-note").inner_text()
    (before,) = robot.expect_topic("/odom", within=10)
    viewer.page.locator("#scene").focus()
    viewer.page.keyboard.down("i")
    try:
        robot.expect_topic("/odom", within=30, where=lambda m: abs(m.twist.twist.linear.x) > 0.3)
    finally:
        viewer.page.keyboard.up("i")
    (moving,) = robot.expect_topic("/odom", within=10)
    robot.expect_topic(
        "/odom", within=30, where=lambda m: abs(m.twist.twist.linear.x) < 0.02
    )  # let go: a zero twist stops it
    assert moving.pose.pose.position.x < before.pose.pose.position.x - 0.05, (before, moving)

    # 7. the page goes: nobody watches the camera, and it stops rendering
    viewer.page.close()
    camera.wait_output("no image subscribers: rendering stopped", timeout=60)
    assert subscribers(robot, CAMERA) == 0
