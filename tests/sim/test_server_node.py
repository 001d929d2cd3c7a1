"""The simulator server node end to end: a real router, the ``gazebo`` process, ``spawn_entity.py``,
the diff drive child node, and a probe node that drives the robot and reads what is published."""

from __future__ import annotations

import math
import os
import queue
import re
import signal
import socket
import subprocess
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from launchkit.ros.msgs.gazebo_msgs.srv import DeleteEntity
from launchkit.ros.msgs.geometry_msgs.msg import Twist, Vector3
from launchkit.ros.msgs.nav_msgs.msg import Odometry
from launchkit.ros.msgs.rosgraph_msgs.msg import Clock
from launchkit.ros.msgs.sensor_msgs.msg import CameraInfo, Image, JointState, LaserScan

from launchkit.packages import PackageIndex
from launchkit.ros import Node, QoSProfile, spin_once
from launchkit.ros.context import Context
from launchkit.ros.router import start_router
from launchkit.rotations import yaw_of

SEED_URDF = Path(__file__).resolve().parents[2] / "urdf" / "three_wheeled_robot.urdf"


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


class Server:
    """The ``gazebo`` process; its output lines are collected for ``expect``."""

    def __init__(self, argv: list[str]) -> None:
        command = PackageIndex().executable("gazebo_ros", "gazebo")
        self.proc = subprocess.Popen(
            [*command, *argv],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            start_new_session=True,
        )
        self.lines: queue.Queue[str] = queue.Queue()
        self.seen: list[str] = []
        self._reader = threading.Thread(target=self._pump, daemon=True)
        self._reader.start()

    def _pump(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.put(line.rstrip("\n"))

    def expect(self, pattern: str, timeout: float) -> re.Match[str]:
        """The first new output line matching ``pattern``; fails after ``timeout`` seconds."""
        deadline = time.monotonic() + timeout
        while (remaining := deadline - time.monotonic()) > 0:
            try:
                line = self.lines.get(timeout=remaining)
            except queue.Empty:
                break
            self.seen.append(line)
            match = re.search(pattern, line)
            if match:
                return match
        raise AssertionError(
            f"gazebo printed no line matching {pattern!r} within {timeout} s "
            f"(exit status {self.proc.poll()}); last lines:\n" + "\n".join(self.seen[-20:])
        )

    def stop(self) -> int:
        """SIGINT, then SIGKILL of its process group after 10 s; the exit status."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.send_signal(signal.SIGUSR1)  # its stacks, for the report
                time.sleep(0.5)
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        self._reader.join(5)
        if self.proc.stdout is not None:
            self.proc.stdout.close()
        return self.proc.returncode


@pytest.fixture
def network(monkeypatch: pytest.MonkeyPatch) -> Iterator[Context]:
    """A private router and a ROS context for the probe node."""
    endpoint = f"tcp/127.0.0.1:{_free_port()}"
    router = start_router(endpoint)
    monkeypatch.setenv("LAUNCHKIT_ROUTER", endpoint)
    context = Context()
    context.init([])
    try:
        yield context
    finally:
        context.shutdown()
        router.close()


@pytest.fixture
def server(network: Context) -> Iterator[Server]:
    """``gazebo --verbose -s ... obstacles`` at 2× real time."""
    args = ["--verbose", "-s", "libgazebo_ros_init.so", "-s", "libgazebo_ros_factory.so"]
    process = Server([*args, "obstacles", "--ros-args", "-p", "real_time_factor:=2.0"])
    try:
        yield process
    finally:
        status = process.stop()
        while not process.lines.empty():
            process.seen.append(process.lines.get())
        pids = [
            int(m.group(1)) for line in process.seen if (m := re.search(r"\(pid (\d+)\)", line))
        ]
        survivors = [pid for pid in pids if _alive(pid)]
        for pid in survivors:  # never leave one behind, even when failing
            os.kill(pid, signal.SIGKILL)
        output = "\n".join(process.seen[-60:])
        # (Its stop watchdog exits 1 after dumping every stack: that is a failure too.)
        assert status == 0, f"gazebo did not stop cleanly on SIGINT (status {status}):\n" + output
        assert survivors == [], "diff drive children outlived the server"


@pytest.fixture
def probe(network: Context, server: Server) -> Iterator[Node]:
    """A node of the test's own; destroyed before the server stops (it never stalls it)."""
    node = Node("probe", context=network)
    try:
        yield node
    finally:
        node.destroy_node()


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().split()[2] != "Z"
    except OSError:
        return False


def spawn(entity: str, *extra: str) -> subprocess.CompletedProcess[str]:
    """Run ``spawn_entity.py -file SEED -entity ENTITY``."""
    command = PackageIndex().executable("gazebo_ros", "spawn_entity.py")
    return subprocess.run(
        [*command, "-file", str(SEED_URDF), "-entity", entity, *extra],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )


def spin_until(node: Node, done: Callable[[], bool], timeout: float, what: str) -> None:
    """Spin ``node`` until ``done()``; fail naming ``what`` after ``timeout`` seconds."""
    deadline = time.monotonic() + timeout
    while not done():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        spin_once(node, timeout_sec=0.05)


def stamp(msg: Any) -> float:
    return float(msg.header.stamp.sec) + float(msg.header.stamp.nanosec) * 1e-9


def test_spawned_robot_publishes_drives_and_turns(probe: Node) -> None:
    result = spawn("my_robot")
    assert result.returncode == 0, result.stderr
    assert "Successfully spawned entity [my_robot]" in result.stdout
    odom: list[Any] = []
    truth: dict[float, Any] = {}
    scans: list[Any] = []
    clocks: list[Any] = []
    probe.create_subscription(Odometry, "/odom", odom.append, 50)
    probe.create_subscription(
        Odometry, "/gazebo/my_robot/ground_truth", lambda m: truth.__setitem__(stamp(m), m), 200
    )
    # The seed's lidar block leaves ~/out alone: gazebo_ros's /gazebo_lidar/out, launchkit's /scan.
    probe.create_subscription(LaserScan, "/scan", scans.append, QoSProfile(depth=5))
    probe.create_subscription(Clock, "/clock", clocks.append, 10)
    joints: list[Any] = []
    probe.create_subscription(JointState, "/joint_states", joints.append, 50)
    cmd = probe.create_publisher(Twist, "/cmd_vel", 1)
    spin_until(
        probe,
        lambda: bool(odom and scans and clocks and joints),
        20,
        "/odom, /scan, /clock, /joint_states",
    )
    # let the spawned robot settle on the ground before driving it (a command that reaches it
    # while it still drops from its spawn pose spins the wheels in the air)
    spin_until(probe, lambda: stamp(odom[-1]) > stamp(odom[0]) + 1.0, 20, "1 s of odometry")
    assert set(joints[-1].name) == {"wheel_left_joint", "wheel_right_joint", "caster_joint"}
    wheels_before = dict(zip(joints[-1].name, joints[-1].position, strict=True))

    scan = scans[-1]
    assert (scan.header.frame_id, len(scan.ranges)) == ("lidar", 360)
    assert 1.85 < scan.ranges[180] < 2.05  # the red box ahead (base -x)
    assert math.isinf(scan.ranges[0])
    first = odom[-1]
    assert (first.header.frame_id, first.child_frame_id) == ("odom", "base")

    # Forward: 0.5 m/s for 2 s of sim time. The seed's wheels drive it toward base -x.
    cmd.publish(Twist(linear=Vector3(x=0.5)))
    # Measure from the first sign of motion: on a loaded machine the command may reach the
    # server (stepping at 2x real time) a good part of a simulated second later.
    spin_until(
        probe, lambda: abs(odom[-1].twist.twist.linear.x) > 0.02, 20, "the robot to start moving"
    )
    start = odom[-1]
    spin_until(probe, lambda: stamp(odom[-1]) > stamp(start) + 2.0, 20, "2 s of odometry")
    cmd.publish(Twist())
    moved = odom[-1]
    dx = moved.pose.pose.position.x - start.pose.pose.position.x
    # 2 s at 0.5 m/s less the 0.7 m/s² ramp: about 0.82 m
    assert -1.1 < dx < -0.6, (dx, start, moved)
    # WORLD odometry is PyBullet's ground truth at the same sim time.
    spin_until(probe, lambda: stamp(moved) in truth, 5, "ground truth at the odometry's stamp")
    same = truth[stamp(moved)].pose.pose.position
    assert (same.x, same.y) == pytest.approx(
        (moved.pose.pose.position.x, moved.pose.pose.position.y), abs=1e-9
    )
    # /joint_states is PyBullet's: 0.82 m on 0.15 m wheels is more than 5 rad of rotation.
    wheels_after = dict(zip(joints[-1].name, joints[-1].position, strict=True))
    for wheel in ("wheel_left_joint", "wheel_right_joint"):
        assert abs(wheels_after[wheel] - wheels_before[wheel]) > 4.0, (wheel, wheels_after)

    # Turn: +1 rad/s is counter-clockwise.
    cmd.publish(Twist(angular=Vector3(z=1.0)))
    spin_until(probe, lambda: odom[-1].twist.twist.angular.z > 0.02, 20, "the robot to turn")
    before = odom[-1]
    spin_until(probe, lambda: stamp(odom[-1]) > stamp(before) + 1.5, 20, "1.5 s of turning")
    cmd.publish(Twist())
    turned = yaw_of(_quaternion(odom[-1])) - yaw_of(_quaternion(before))
    assert 0.6 < math.atan2(math.sin(turned), math.cos(turned)) < 1.6


def test_a_nan_command_is_refused_and_odometry_stays_finite(probe: Node) -> None:
    # One NaN Twist used to reach the wheel joints: the physics, and /odom with it, stayed NaN.
    assert spawn("nan_bot").returncode == 0
    odom: list[Any] = []
    probe.create_subscription(Odometry, "/odom", odom.append, 50)
    cmd = probe.create_publisher(Twist, "/cmd_vel", 1)
    spin_until(probe, lambda: bool(odom), 20, "/odom")
    cmd.publish(Twist(linear=Vector3(x=math.nan), angular=Vector3(z=math.inf)))
    sent = stamp(odom[-1])
    spin_until(probe, lambda: stamp(odom[-1]) > sent + 1.0, 20, "1 s of odometry after NaN")
    cmd.publish(Twist(linear=Vector3(x=0.5)))  # a good command after it still drives
    spin_until(
        probe, lambda: abs(odom[-1].twist.twist.linear.x) > 0.02, 20, "the robot to start moving"
    )
    cmd.publish(Twist())
    for msg in odom:
        pose, twist = msg.pose.pose, msg.twist.twist
        values = [pose.position.x, pose.position.y, pose.orientation.z, pose.orientation.w]
        values += [twist.linear.x, twist.angular.z]
        assert all(math.isfinite(v) for v in values), msg


def _quaternion(msg: Any) -> tuple[float, float, float, float]:
    q = msg.pose.pose.orientation
    return (q.x, q.y, q.z, q.w)


def test_camera_streams_once_subscribed(probe: Node) -> None:
    assert spawn("my_robot").returncode == 0
    images: list[Any] = []
    infos: list[Any] = []
    probe.create_subscription(CameraInfo, "/camera1/camera_info", infos.append, 5)
    probe.create_subscription(Image, "/camera1/image_raw", images.append, QoSProfile(depth=2))
    spin_until(probe, lambda: bool(images and infos), 30, "a camera image and camera info")
    image, info = images[-1], infos[-1]
    assert (image.width, image.height, image.encoding, image.step) == (800, 800, "rgb8", 2400)
    assert len(image.data) == 800 * 800 * 3 and image.header.frame_id == "camera"
    assert info.k[0] == pytest.approx(476.70, abs=0.01) and info.distortion_model == "plumb_bob"


def test_spawn_errors_exit_2_and_diff_drive_is_restarted(server: Server) -> None:
    assert spawn("my_robot").returncode == 0
    started = server.expect(r"started plugin node 'gazebo_base_controller' \(pid (\d+)\)", 20)
    cmdline = Path(f"/proc/{started.group(1)}/cmdline").read_text().split("\0")
    assert cmdline[1:3] == ["-m", "launchkit.stock.gazebo_ros.diff_drive_node"]  # itself in ps
    again = spawn("my_robot")
    assert again.returncode == 2
    assert "entity 'my_robot' already exists" in again.stderr
    assert "Traceback" not in again.stderr
    os.kill(int(started.group(1)), signal.SIGKILL)
    server.expect(r"plugin node 'gazebo_base_controller' exited", 20)
    restarted = server.expect(r"started plugin node 'gazebo_base_controller' \(pid (\d+)\)", 20)
    assert restarted.group(1) != started.group(1)


def test_spawn_without_a_server_fails_clearly(network: Context) -> None:
    result = spawn("lonely", "-spawn_service_timeout", "0.5")
    assert result.returncode == 2
    assert "service /spawn_entity not available within 0.5 s" in result.stderr


def _red_fraction(image: Any) -> float:
    """The share of an rgb8 image's pixels that are clearly red (the obstacles world's box)."""
    rgb = np.asarray(image.data, dtype=np.int16).reshape(image.height, image.width, 3)
    r, g, b = rgb[:, :, 0], rgb[:, :, 1], rgb[:, :, 2]
    return float(((r > 100) & (r > 2 * g) & (r > 2 * b)).mean())


def _camera_pid(server: Server) -> int:
    started = server.expect(r"started plugin node 'camera_controller' \(pid (\d+)\)", 20)
    return int(started.group(1))


def test_camera_renders_in_its_own_process_and_follows_the_robot(
    server: Server, probe: Node
) -> None:
    assert spawn("my_robot").returncode == 0
    pid = _camera_pid(server)
    assert pid != server.proc.pid
    assert "launchkit.stock.gazebo_ros.camera_node" in Path(f"/proc/{pid}/cmdline").read_text()
    images: list[Any] = []
    truth: list[Any] = []
    probe.create_subscription(Image, "/camera1/image_raw", images.append, QoSProfile(depth=2))
    probe.create_subscription(Odometry, "/gazebo/my_robot/ground_truth", truth.append, 50)
    spin_until(probe, lambda: bool(images and truth), 30, "a camera image and ground truth")
    assert _red_fraction(images[-1]) > 0.01  # spawned facing the red box

    # Turn about half a circle: the camera process knows only what the server's state says.
    cmd = probe.create_publisher(Twist, "/cmd_vel", 1)
    cmd.publish(Twist(angular=Vector3(z=1.0)))
    spin_until(
        probe, lambda: abs(yaw_of(_quaternion(truth[-1]))) > 2.8, 30, "the robot to turn around"
    )
    cmd.publish(Twist())
    turned = stamp(truth[-1])
    spin_until(probe, lambda: stamp(images[-1]) > turned, 30, "an image after the turn")
    assert _red_fraction(images[-1]) == 0.0


def test_camera_stops_with_its_subscribers_and_never_holds_up_the_physics(
    server: Server, probe: Node
) -> None:
    assert spawn("my_robot").returncode == 0
    pid = _camera_pid(server)
    images: list[Any] = []
    clocks: list[Any] = []
    image_sub = probe.create_subscription(
        Image, "/camera1/image_raw", images.append, QoSProfile(depth=2)
    )
    probe.create_subscription(Clock, "/clock", clocks.append, 10)
    spin_until(probe, lambda: bool(images and clocks), 30, "a camera image and /clock")
    server.expect(r"\[camera_controller\]: image subscribed: rendering", 10)

    # A renderer frozen mid-stream: the server's clock goes on.
    os.kill(pid, signal.SIGSTOP)
    try:
        frozen = stamp(images[-1])
        spin_until(
            probe,
            lambda: _clock_seconds(clocks[-1]) > frozen + 2.0,
            30,
            "/clock to advance 2 sim s while the camera process is stopped",
        )
    finally:
        os.kill(pid, signal.SIGCONT)
    spin_until(probe, lambda: stamp(images[-1]) > frozen + 2.0, 30, "images after the thaw")

    probe.destroy_subscription(image_sub)
    server.expect(r"\[camera_controller\]: no image subscribers: rendering stopped", 20)


def test_deleting_the_entity_stops_its_camera(server: Server, probe: Node) -> None:
    assert spawn("my_robot").returncode == 0
    pid = _camera_pid(server)
    client = probe.create_client(DeleteEntity, "/delete_entity")
    assert client.wait_for_service(10)
    response = client.call(DeleteEntity.Request(name="my_robot"), 20)
    assert response.success, response.status_message
    assert not _alive(pid)


def _clock_seconds(msg: Any) -> float:
    return float(msg.clock.sec) + float(msg.clock.nanosec) * 1e-9
