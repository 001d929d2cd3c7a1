"""tf2 across processes: a broadcaster node and a listener node, both written against tf2_ros'
API (the face packages on their PYTHONPATH), talk over launchkit's transport; the listener,
started after the static transform was latched, still gets it; its lookups at the latest time,
at a past time and at a time the data has yet to reach, with and without timeouts, give what
the broadcaster's motion says. A buffer given a node answers ``tf2_frames``."""

from __future__ import annotations

import math
import os
import threading
import time
from pathlib import Path

import pytest

import launchkit.ros
from launchkit.ros import Node, spin_once
from launchkit.ros.context import Context
from launchkit.ros.msgs import get_service, type_hash
from launchkit.ros.tf2 import Buffer
from tests.ros.ros_helpers import Child
from tests.tf2.transforms import stamped

NODES = Path(__file__).resolve().parent / "nodes"
FACE = Path(launchkit.ros.__file__).resolve().parent / "face"
S = math.sqrt(0.5)


def node(script: str, *args: str) -> Child:
    """A node script of tests/tf2/nodes with the face packages importable (``tf2_ros``)."""
    path = os.pathsep.join([str(FACE), os.environ.get("PYTHONPATH", "")])
    return Child(["-u", str(NODES / script), *args], env={"PYTHONPATH": path})


def values(line: str) -> tuple[int, list[float]]:
    """``NAME STAMP_NS X Y Z QZ QW`` as the stamp and the numbers."""
    _, stamp, *numbers = line.split()
    return int(stamp), [float(n) for n in numbers]


def test_a_listener_node_looks_up_what_a_broadcaster_node_sends(router: str) -> None:
    t0 = time.time_ns()
    broadcaster = node("tf_broadcaster.py", str(t0))
    listener = None
    try:
        broadcaster.expect("static sent", timeout=60)
        listener = node("tf_listener.py")  # late: the static transform is latched by now

        stamp, (x, y, z, qz, qw) = values(listener.expect("latest ", timeout=90))
        # the laser, 0.5 m ahead of the base and turned 90°, on a base at x = seconds since t0
        assert x == pytest.approx((stamp - t0) / 1e9 + 0.5, abs=1e-6)
        assert (y, z, qz, qw) == pytest.approx((0.0, 0.2, S, S), abs=1e-9)

        stamp, (x, *_) = values(listener.expect("ahead ", timeout=60))
        assert x == pytest.approx((stamp - t0) / 1e9, abs=1e-6)

        stamp, (x, *_) = values(listener.expect("past ", timeout=30))
        assert x == pytest.approx((stamp - t0) / 1e9, abs=1e-6)

        gave_up = listener.expect("gave up after", timeout=30)
        waited = float(gave_up.split()[3])
        assert waited >= 0.5
        assert gave_up.endswith(
            ': "gripper" passed to lookupTransform argument source_frame does not exist. '
        )
        listener.expect("done", timeout=30)
        assert listener.stop(timeout=20) == 0, "".join(listener.stderr)[-2000:]
    finally:
        if listener is not None:
            listener.stop()
        broadcaster.stop()


def test_a_buffer_given_a_node_serves_its_frames(router: str) -> None:
    # the service type is tf2_msgs' own: rosidl's hash of tf2_msgs/srv/FrameGraph (Jazzy)
    assert type_hash("tf2_msgs/srv/FrameGraph") == (
        "RIHS01_0d1fbc6222c018ba5f33822904a2fdd4063705289956d3fdde07cd8c50fe8067"
    )
    contexts = [Context(), Context()]
    for context in contexts:
        context.init([])
    serving = Node("frames_server", context=contexts[0])
    buffer = Buffer(node=serving)
    buffer.set_transform_static(stamped("base", "laser", xyz=(0.5, 0.0, 0.0)), "urdf")
    stop = threading.Event()

    def spin() -> None:
        while not stop.is_set():
            spin_once(serving, timeout_sec=0.05)

    spinner = threading.Thread(target=spin)
    spinner.start()
    try:
        asking = Node("frames_client", context=contexts[1])
        client = asking.create_client(get_service("tf2_msgs/srv/FrameGraph"), "/tf2_frames")
        assert client.wait_for_service(timeout_sec=30)
        response = client.call(client.srv_type.Request(), timeout_sec=30)
        assert response.frame_yaml == buffer.all_frames_as_yaml()
        assert response.frame_yaml.startswith("laser: \n  parent: 'base'\n  broadcaster: 'urdf'")
    finally:
        stop.set()
        spinner.join(10)
        for context in contexts:
            context.shutdown()
