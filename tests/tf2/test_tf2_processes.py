"""tf2 across processes: a broadcaster node and a listener node, both written against tf2_ros'
API (the face packages on their PYTHONPATH), talk over launchkit's transport; the listener,
started after the static transform was latched, still gets it; its lookups at the latest time,
at a past time and at a time the data has yet to reach, with and without timeouts, give what
the broadcaster's motion says."""

from __future__ import annotations

import math
import os
import time
from pathlib import Path

import pytest

import launchkit.ros
from tests.ros.ros_helpers import Child

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
