"""turtlesim_node and rviz2 side by side, as the tutorials run them (turtlesim in one terminal,
rviz2 in another, or a launch with rviz2): whichever comes second finds the first one's viewer
on the port and does not fail. The tests use a free port of their own through
``LAUNCHKIT_VIEWER_PORT``, as a user would set it."""

from __future__ import annotations

import re
import sys
from collections.abc import Callable

from launchkit.stock.rviz2.viewer_probe import is_viewer
from launchkit.testing._isolation import free_loopback_port
from tests.turtlesim.conftest import Program

LAUNCHKIT = [sys.executable, "-m", "launchkit"]
SERVED = re.compile(r"^viewer: http://127\.0\.0\.1:(\d+)/ \(open it in a browser")


def test_rviz2_beside_turtlesim_serves_on_a_free_port_and_says_so(
    programs: Callable[..., Program],
) -> None:
    port = free_loopback_port()
    env = {"LAUNCHKIT_VIEWER_PORT": str(port)}
    sim = programs(*LAUNCHKIT, "exec", "turtlesim", "turtlesim_node", env=env)
    assert sim.wait_out("viewer: ") == f"viewer: http://127.0.0.1:{port}/ (open it in a browser)"
    rviz = programs(*LAUNCHKIT, "exec", "rviz2", "rviz2", env=env)
    try:
        line = rviz.wait_out("viewer: ")
        found = SERVED.match(line)
        assert found and int(found[1]) != port, line
        assert line.endswith(
            f"(open it in a browser; port {port} already serves another launchkit viewer, "
            "without this rviz2's displays)"
        )
        assert rviz.proc.poll() is None, rviz.err
        assert is_viewer("127.0.0.1", int(found[1])) and is_viewer("127.0.0.1", port)
    finally:
        assert rviz.stop() == 0 and sim.stop() == 0


def test_turtlesim_beside_rviz2_shows_itself_in_rviz2s_viewer(
    programs: Callable[..., Program],
) -> None:
    port = free_loopback_port()
    env = {"LAUNCHKIT_VIEWER_PORT": str(port)}
    rviz = programs(*LAUNCHKIT, "exec", "rviz2", "rviz2", env=env)
    assert rviz.wait_out("viewer: ") == f"viewer: http://127.0.0.1:{port}/ (open it in a browser)"
    sim = programs(*LAUNCHKIT, "exec", "turtlesim", "turtlesim_node", env=env)
    try:
        assert sim.wait_out("viewer: ") == (
            f"viewer: http://127.0.0.1:{port}/ (the viewer already running there shows this "
            "turtlesim)"
        )
    finally:
        assert sim.stop() == 0 and rviz.stop() == 0
