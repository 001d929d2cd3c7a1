"""The simulator server's child processes: a node per diff drive plugin and per camera plugin.

Gazebo runs plugins inside the server; launchkit runs the diff drive as its own node process so
it is visible in ``launchkit node list`` and testable alone. Under ``launchkit run`` the server
asks the launcher to start it (over the child-request socket, see
:mod:`launchkit.runtime.supervisor_client`): it is then a process of the launch like any other,
with its own ``[name-N]`` output prefix, log files, respawn after :data:`RESTART_DELAY`,
ordered stop and the launcher's orphan guard, and the launcher stops it when the server goes.
Run any other way (``launchkit exec``, by hand), the server supervises it itself: a new session
(its own process group), death with the server (PR_SET_PDEATHSIG), restart after
:data:`RESTART_DELAY` when it dies, SIGTERM then SIGKILL on stop; its output then goes to the
server's.

Every plugin child goes through :meth:`PluginProcesses._start_child` (a name and an argv), which
picks the launcher or the fallback.
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

from launchkit.runtime.supervisor_client import SupervisorClient, SupervisorError
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
    """One plugin child: its command, and either the launcher's id for it or, when the server
    supervises it itself, its process and when it may restart."""

    name: str
    argv: list[str]
    launcher_id: int | None = None
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
    _launcher: SupervisorClient | None = None
    _asked_launcher: bool = False

    def start_diff_drive(self, entity: str, plugin: PluginSpec, params: DiffDriveParams) -> None:
        """Start the diff drive node of ``plugin`` for ``entity``."""
        params_file = Path(self._tmp.name) / f"{entity}-{plugin.name}.yaml"
        self._start_child(
            entity, plugin.name, diff_drive_command(entity, plugin, params, params_file)
        )

    def _start_child(self, entity: str, name: str, argv: list[str]) -> None:
        """Start one plugin child of ``entity``: by the launcher if there is one, else here."""
        child = Child(name, argv)
        launcher = self._connect()
        if launcher is None:
            self._spawn(child)
        else:
            try:
                started = launcher.start(name, argv, respawn=True, respawn_delay=RESTART_DELAY)
            except SupervisorError as error:
                self.log(f"the launcher did not start plugin node '{name}': {error}")
                return
            child.launcher_id = started.id
            self.log(
                f"started plugin node '{name}' (pid {started.pid}) as {started.label} of the launch"
            )
        self.children.setdefault(entity, []).append(child)

    def _connect(self) -> SupervisorClient | None:
        """The launcher's child-request connection, made on first use; None without one."""
        if not self._asked_launcher:
            self._asked_launcher = True
            try:
                self._launcher = SupervisorClient.from_environment()
            except OSError as error:
                self.log(f"cannot reach the launcher ({error}); the server runs its plugin nodes")
        return self._launcher

    def start_camera(self, entity: str, plugin: PluginSpec, params: CameraNodeParams) -> None:
        """Start the camera node of ``plugin`` for ``entity`` (it renders in its own process)."""
        params_file = Path(self._tmp.name) / f"{entity}-{plugin.name}.yaml"
        self._start_child(entity, plugin.name, camera_command(entity, plugin, params, params_file))

    def _spawn(self, child: Child) -> None:
        child.process = subprocess.Popen(
            child.argv, start_new_session=True, preexec_fn=_die_with_parent
        )
        self.log(f"started plugin node '{child.name}' (pid {child.process.pid})")

    def supervise(self) -> None:
        """Restart children the server runs itself that died (after :data:`RESTART_DELAY`);
        call now and then. (The launcher restarts its own.)"""
        now = time.monotonic()
        for children in self.children.values():
            for child in children:
                if child.launcher_id is not None:
                    continue
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
        self._stop(self.children.pop(entity, []))

    def stop(self) -> None:
        """Stop every child, close the launcher connection, remove the parameter files."""
        everything = [c for children in self.children.values() for c in children]
        self.children.clear()
        self._stop(everything)
        if self._launcher is not None:
            self._launcher.close()  # the launcher would stop what is left of them now anyway
            self._launcher = None
        self._tmp.cleanup()

    def _stop(self, children: list[Child]) -> None:
        for child in children:
            if child.launcher_id is not None and self._launcher is not None:
                try:
                    self._launcher.stop(child.launcher_id)
                except SupervisorError as error:
                    self.log(f"the launcher did not stop plugin node '{child.name}': {error}")
        _stop_all([c for c in children if c.launcher_id is None])


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
