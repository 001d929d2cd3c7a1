"""``gzclient`` stand-in: Gazebo's GUI client. launchkit's simulator draws itself (the server's
``gui`` option) and the robot is seen in the rviz2 viewer, so this process only says so and
waits until it is stopped, as a GUI would stay open."""

from __future__ import annotations

import signal
import sys
import threading

from launchkit.stock import _entry


def main(argv: list[str]) -> int:
    """Say where the picture is, then wait for SIGINT or SIGTERM."""
    stop = threading.Event()
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: stop.set())
    print(
        "gzclient: launchkit has no Gazebo GUI; see the robot in the rviz2 viewer, or start "
        "the server with gui:=true for PyBullet's window",
        flush=True,
    )
    while not stop.wait(0.5):
        pass
    return 0


if __name__ == "__main__":
    sys.exit(_entry.run(main, "gzclient"))
