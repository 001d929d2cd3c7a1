"""The simulator server's child processes: one ``diff_drive`` node per diff drive plugin.

Gazebo runs plugins inside the server; launchkit runs the diff drive as its own node process so
it is visible in ``launchkit node list`` and testable alone. The server supervises it: a new
session (its own process group), death with the server (PR_SET_PDEATHSIG), restart after a
delay when it dies, SIGTERM then SIGKILL on stop. Its output goes to the server's, whose lines
the launcher prefixes; ROS log lines name the node.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from launchkit.stock.gazebo_ros.camera_node import CameraNodeParams, camera_command
from launchkit.stock.gazebo_ros.diff_drive import DiffDriveParams
from launchkit.stock.gazebo_ros.sim.model import PluginSpec

RESTART_DELAY = 1.0
STOP_TIMEOUT = 3.0
_PR_SET_PDEATHSIG = 1


def _die_with_parent() -> None:
    # Runs in the child between fork and exec.
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGTERM)


def diff_drive_command(
    entity: str, plugin: PluginSpec, params: DiffDriveParams, params_file: Path
) -> list[str]:
    """The command line of the diff drive node for ``plugin`` of ``entity``."""
    values: dict[str, object] = {"entity": entity, **params.as_parameters()}
    params_file.write_text(yaml.safe_dump({"/**": {"ros__parameters": values}}))
    argv = [sys.executable, "-m", "launchkit.stock.gazebo_ros.diff_drive_node", "--ros-args"]
    argv += ["-r", f"__node:={plugin.name}"]
    if plugin.ros.namespace:
        argv += ["-r", f"__ns:=/{plugin.ros.namespace.strip('/')}"]
    argv += ["--params-file", str(params_file)]
    for source, target in plugin.ros.remappings:
        argv += ["-r", f"{source}:={target}"]
    return argv


@dataclass
class Child:
    """One supervised child: its command, its process and when it may restart."""

    name: str
    argv: list[str]
    process: subprocess.Popen[bytes] | None = None
    restart_at: float = 0.0
    restarts: int = 0


@dataclass
class PluginProcesses:
    """The children of the server, keyed by entity."""

    log: Callable[[str], None]
    children: dict[str, list[Child]] = field(default_factory=dict)
    _tmp: tempfile.TemporaryDirectory[str] = field(
        default_factory=lambda: tempfile.TemporaryDirectory(prefix="launchkit-gazebo-")
    )

    def start_diff_drive(self, entity: str, plugin: PluginSpec, params: DiffDriveParams) -> None:
        """Start the diff drive node of ``plugin`` for ``entity``."""
        params_file = Path(self._tmp.name) / f"{entity}-{plugin.name}.yaml"
        child = Child(plugin.name, diff_drive_command(entity, plugin, params, params_file))
        self.children.setdefault(entity, []).append(child)
        self._spawn(child)

    def start_camera(self, entity: str, plugin: PluginSpec, params: CameraNodeParams) -> None:
        """Start the camera node of ``plugin`` for ``entity`` (it renders in its own process)."""
        params_file = Path(self._tmp.name) / f"{entity}-{plugin.name}.yaml"
        child = Child(plugin.name, camera_command(entity, plugin, params, params_file))
        self.children.setdefault(entity, []).append(child)
        self._spawn(child)

    def _spawn(self, child: Child) -> None:
        child.process = subprocess.Popen(
            child.argv, start_new_session=True, preexec_fn=_die_with_parent
        )
        self.log(f"started plugin node '{child.name}' (pid {child.process.pid})")

    def supervise(self) -> None:
        """Restart children that died (after :data:`RESTART_DELAY`); call now and then."""
        now = time.monotonic()
        for children in self.children.values():
            for child in children:
                process = child.process
                if process is not None and process.poll() is not None:
                    self.log(
                        f"plugin node '{child.name}' exited with {process.returncode}; "
                        f"restarting in {RESTART_DELAY:.0f} s"
                    )
                    child.process = None
                    child.restart_at = now + RESTART_DELAY
                elif process is None and now >= child.restart_at:
                    child.restarts += 1
                    self._spawn(child)

    def stop_entity(self, entity: str) -> None:
        """Stop the children of ``entity``."""
        _stop_all(self.children.pop(entity, []))

    def stop(self) -> None:
        """Stop every child and remove the parameter files."""
        everything = [c for children in self.children.values() for c in children]
        self.children.clear()
        _stop_all(everything)
        self._tmp.cleanup()


def _stop_all(children: list[Child]) -> None:
    running = [c.process for c in children if c.process is not None and c.process.poll() is None]
    for process in running:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGTERM)
    deadline = time.monotonic() + STOP_TIMEOUT
    for process in running:
        try:
            process.wait(max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)
            process.wait()
