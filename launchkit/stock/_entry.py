"""How every stock node starts and ends.

Each node module ends with ``_entry.run(main, "program")``, the one ``__main__`` wrapper: its
``main(argv)`` raises a :class:`launchkit.errors.UserError` (or a subclass) for a bad command
line, parameter or file, which becomes one line and exit status 2 (no traceback); Ctrl-C is a
clean exit, and so is SIGTERM (rclpy's ``ExternalShutdownException`` from a spinning executor);
the process exits promptly (:mod:`launchkit._exit`). Inside ``main``, a node's ROS
set-up and teardown is :func:`ros_node` (or :func:`spin`, for a node that only needs spinning).
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Any, NoReturn

import launchkit.ros as ros
from launchkit._exit import exit_promptly
from launchkit.errors import LaunchkitError
from launchkit.startup_sigint import release_sigint

#: Seconds the ROS layer's shutdown may take before the node exits regardless.
SHUTDOWN_BOUND = 2.0


def run(main: Callable[[list[str]], int], program: str) -> NoReturn:
    """Run ``main(sys.argv)``; report a launchkit error as ``program: error: ...``, no traceback.

    Then exit promptly (see :mod:`launchkit._exit`) with ``main``'s status, the error's (2 for
    a user mistake), or 0 after Ctrl-C (``KeyboardInterrupt``, also one that came while the
    node's modules were imported: :mod:`launchkit.startup_sigint`) or SIGTERM (the
    spinning executor's ``ExternalShutdownException``): a stop request is a normal end for a
    stock node.
    """
    try:
        release_sigint()  # a Ctrl-C held while the node's modules were imported lands here
        status = main(sys.argv)
    except LaunchkitError as exc:
        print(f"{program}: {exc.format()}", file=sys.stderr, flush=True)
        status = exc.exit_status
    except (KeyboardInterrupt, ros.ExternalShutdownException):
        status = 0
    exit_promptly(status)


@contextlib.contextmanager
def ros_node(argv: list[str], name: str, **options: Any) -> Iterator[ros.Node]:
    """The ROS layer initialised from ``argv`` (its ``--ros-args``) and node ``name`` (made
    with ``options``) for the ``with`` block; then the node destroyed and the layer shut down
    (within :data:`SHUTDOWN_BOUND`), however the block ends."""
    ros.init(args=argv)
    try:
        node = ros.Node(name, **options)
        try:
            yield node
        finally:
            node.destroy_node()
    finally:
        shutdown_within(SHUTDOWN_BOUND)


def spin(argv: list[str], name: str, setup: Callable[[ros.Node], object], **options: Any) -> int:
    """Run node ``name`` (see :func:`ros_node`) set up by ``setup(node)`` until shutdown
    (Ctrl-C or SIGTERM); 0."""
    with ros_node(argv, name, **options) as node:
        setup(node)
        ros.spin(node)
    return 0


def shutdown_within(seconds: float) -> None:
    """``ros.try_shutdown()`` (a signal may have shut ROS down already), but exit (status 0)
    anyway if it has not returned in ``seconds``.

    A node process must never outlive its supervisor's stop request because closing the
    transport blocked; the supervisor's SIGKILL may not come if the supervisor itself is gone.
    """
    done = threading.Event()

    def _close() -> None:
        try:
            ros.try_shutdown()
        finally:
            done.set()

    threading.Thread(target=_close, daemon=True, name="shutdown").start()
    if not done.wait(seconds):
        print("shutdown of the ROS session timed out; exiting", file=sys.stderr, flush=True)
        sys.stdout.flush()
        os._exit(0)
