"""Helpers for the ``launchkit <verb>`` tests: a private router with test nodes for a whole test
module (each command is a process of its own, as a user runs it), and running a command."""

from __future__ import annotations

import os
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ros_helpers import NODES_DIR, Child, free_port

from launchkit.ros.router import start_router
from tests.engine.launcher import run_launchkit


def launchkit(
    *args: str, env: dict[str, str] | None = None, stdin: str | None = None
) -> subprocess.CompletedProcess[str]:
    """Run ``launchkit ARGS`` to completion, in this process's environment plus ``env``."""
    return run_launchkit(*args, cwd=Path.cwd(), env=env, stdin=stdin)


@contextmanager
def graph_of(*nodes: str) -> Iterator[list[Child]]:
    """A router of this test process on a free port (``LAUNCHKIT_ROUTER`` points at it while the
    block runs), and the test nodes ``nodes`` (files of ``nodes/``) running and ready."""
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    handle = start_router(endpoint)
    before = os.environ.get("LAUNCHKIT_ROUTER")
    os.environ["LAUNCHKIT_ROUTER"] = endpoint
    children: list[Child] = []
    try:
        for node in nodes:
            child = Child([str(NODES_DIR / f"{node}.py")])
            children.append(child)
            child.expect(f"{node} ready", timeout=30)
        yield children
    finally:
        for child in children:
            child.stop()
        if before is None:
            os.environ.pop("LAUNCHKIT_ROUTER", None)
        else:
            os.environ["LAUNCHKIT_ROUTER"] = before
        handle.close()
