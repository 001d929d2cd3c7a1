"""turtlesim in a real browser: ``launchkit run turtlesim multisim.launch.py`` serves the viewer
from one of its turtlesims, the page shows the turtlesim panel, and after a ``cmd_vel`` the
picture's pixels show the turtle moved and the trail it drew (and the background parameter).

Pixels are read from the panel's canvas (``window.__turtlesim.pixel``), in the world's pixels:
500 x 500, 45 to a metre, y down from the top edge.
"""

from __future__ import annotations

import os
import shlex
import socket
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from launchkit.testing._isolation import free_loopback_port
from tests.viewer.conftest import keep_screenshot

pytestmark = pytest.mark.long  # started first: see tests/conftest.py

PEN = [179, 184, 255, 255]
BACKGROUND = [69, 86, 255, 255]
METER = 45.0
BOTTOM = 499 / METER  # the world's height in metres


def pixel_of(x: float, y: float) -> tuple[int, int]:
    """The picture's pixel at world point ``(x, y)``."""
    return int(x * METER), int((BOTTOM - y) * METER)


def wait_for_port(port: int, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while True:
        with socket.socket() as sock:
            if sock.connect_ex(("127.0.0.1", port)) == 0:
                return
        if time.monotonic() > deadline:
            raise AssertionError(f"nothing listened on port {port} within {timeout} s")
        time.sleep(0.1)


def run_cli(handle: Any, command: str) -> str:
    """``launchkit COMMAND`` on the launch's ROS network; its output."""
    done = subprocess.run(
        [sys.executable, "-m", "launchkit", *shlex.split(command)],
        env={**os.environ, **handle.ros_env},
        capture_output=True,
        text=True,
        timeout=120,
        stdin=subprocess.DEVNULL,
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


def at_rest(viewer: Any, timeout: float = 60.0) -> float:
    """turtle1's x once the page shows it still: the same x 1.2 s apart, longer than the second a
    command moves it (so a command just sent has shown its first steps)."""
    deadline = time.monotonic() + timeout
    last = None
    while True:
        x = float(viewer.page.evaluate("window.__turtlesim.stats.turtles[0].x"))
        if x == last:
            return x
        if time.monotonic() > deadline:
            raise AssertionError(f"turtle1 still moving after {timeout} s (x={x})")
        last = x
        time.sleep(1.2)


def drive_east(viewer: Any, handle: Any, beyond: float, timeout: float = 120.0) -> float:
    """Send turtlesim1's turtle1 ``cmd_vel`` commands (2 m/s east, each good for a second) until
    the page shows it past ``beyond``; its x once at rest. (A busy machine's delayed timer moves
    a turtle less a command, so the number of commands is not fixed.)"""
    deadline = time.monotonic() + timeout
    command = (
        'topic pub --once /turtlesim1/turtle1/cmd_vel geometry_msgs/msg/Twist "{linear: {x: 2.0}}"'
    )
    x = 0.0
    while x <= beyond:
        assert time.monotonic() < deadline, f"turtle1 only reached x={x} in {timeout} s"
        run_cli(handle, command)
        x = at_rest(viewer)
    return x


def pixel(viewer: Any, x: float, y: float) -> list[int]:
    px, py = pixel_of(x, y)
    return list(viewer.page.evaluate(f"window.__turtlesim.pixel({px}, {py})"))


def test_the_panel_draws_the_turtles_their_trails_and_the_background(
    launch: Any, open_viewer: Any, tmp_path: Path
) -> None:
    port = free_loopback_port()
    handle = launch("turtlesim", "multisim.launch.py", env={"LAUNCHKIT_VIEWER_PORT": str(port)})
    wait_for_port(port)
    viewer = open_viewer(f"http://127.0.0.1:{port}/")
    # the page leaves the 3D view for the turtlesim panel by itself
    viewer.wait(
        "v.panel() === 'turtlesim' && window.__turtlesim.nodes().length === 2 "
        "&& window.__turtlesim.stats.scenes > 0",
        "the turtlesim panel shown, following both turtlesims",
    )
    viewer.page.evaluate("window.__turtlesim.choose('/turtlesim1/turtlesim')")
    viewer.wait(
        "window.__turtlesim.stats.drawn === '/turtlesim1/turtlesim' "
        "&& window.__turtlesim.stats.turtles.length === 1",
        "turtlesim1 shown",
    )
    assert viewer.page.locator("#turtlesim-panel").is_visible()
    centre = 499 / METER / 2
    assert pixel(viewer, 0.5, 0.5) == BACKGROUND
    at_start = pixel(viewer, centre, centre)
    assert at_start not in (BACKGROUND, PEN)  # turtle1 is drawn there

    end = drive_east(viewer, handle, centre + 1.5)
    keep_screenshot(viewer, "panel-turtlesim")
    assert pixel(viewer, centre, centre) == PEN  # the turtle left; its trail stays
    assert pixel(viewer, (centre + end) / 2, centre) == PEN  # along the way
    assert pixel(viewer, centre, centre + 0.2) == BACKGROUND  # beside the 3-pixel line
    assert pixel(viewer, end, centre) not in (BACKGROUND, PEN)  # the turtle, where it is now
    assert pixel(viewer, end + 1.0, centre) == BACKGROUND  # nothing drawn ahead of it

    run_cli(handle, "param set /turtlesim1/turtlesim background_r 150")
    viewer.wait("window.__turtlesim.stats.background[0] === 150", "the new background drawn")
    assert pixel(viewer, 0.5, 0.5) == [150, 86, 255, 255]
    assert pixel(viewer, (centre + end) / 2, centre) == PEN

    # the other turtlesim's world: its own turtle, no trail
    viewer.page.evaluate("window.__turtlesim.choose('/turtlesim2/turtlesim')")
    viewer.wait("window.__turtlesim.stats.drawn === '/turtlesim2/turtlesim'", "turtlesim2 shown")
    viewer.wait(
        f"window.__turtlesim.pixel({pixel_of((centre + end) / 2, centre)[0]}, "
        f"{pixel_of(centre, centre)[1]})[0] === {BACKGROUND[0]}",
        "turtlesim2's picture",
    )
    assert pixel(viewer, 0.5, 0.5) == BACKGROUND

    # a page opened now gets the trail drawn so far from the latched snapshot
    late = open_viewer(f"http://127.0.0.1:{port}/")
    late.wait("window.__turtlesim && window.__turtlesim.stats.scenes > 0", "the late page's scene")
    late.page.evaluate("window.__turtlesim.choose('/turtlesim1/turtlesim')")
    late.wait(
        "window.__turtlesim.stats.drawn === '/turtlesim1/turtlesim' "
        "&& window.__turtlesim.stats.snapshots > 0",
        "the late page's trails snapshot",
    )
    late.wait(
        f"window.__turtlesim.pixel({pixel_of((centre + end) / 2, centre)[0]}, "
        f"{pixel_of(centre, centre)[1]}).join() === '{','.join(map(str, PEN))}'",
        "the trail on the late page",
    )
    late.screenshot("turtlesim-late-page")
    assert viewer.problems == [] and late.problems == []
    handle.stop().assert_exit_codes({"*": 0})
