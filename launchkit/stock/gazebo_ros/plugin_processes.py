"""The simulator server's child processes: a node per diff drive plugin and per camera plugin.

Gazebo runs plugins inside the server; launchkit runs the diff drive as its own node process so
it is visible in ``launchkit node list`` and testable alone. Under ``launchkit run`` the server
asks the launcher to start it (over the child-request socket, see
:mod:`launchkit.runtime.supervisor_client`): it is then a process of the launch like any other,
with its own ``[name-N]`` output prefix, log files, respawn after :data:`RESTART_DELAY`,
ordered stop and the launcher's orphan guard, and the launcher stops it when the server goes.
Run any other way (``launchkit exec``, by hand), the server supervises it itself, with the
launcher's lifecycle state machine (:mod:`launchkit.runtime.lifecycle`): a new session (its own
process group), death with the server (PR_SET_PDEATHSIG), restart after :data:`RESTART_DELAY`
when it dies, SIGTERM then SIGKILL after :data:`STOP_TIMEOUT` on stop; its output then goes to
the server's.

Every plugin child's command line comes from :func:`plugin_command` (``python -m`` the node's
own module, so ``ps`` and ``pgrep`` name it), and every child goes through
:meth:`PluginProcesses._start_child` (a name and an argv), which picks the launcher or the
fallback.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from launchkit.envvars import RUN_TMPDIR
from launchkit.runtime.lifecycle import Escalation, Lifecycle, Respawn, RespawnPolicy, SendSignal
from launchkit.runtime.process import kill_group
from launchkit.runtime.supervisor_client import SupervisorClient, SupervisorError
from launchkit.stock.gazebo_ros.camera_node import CameraNodeParams
from launchkit.stock.gazebo_ros.sim.diff_drive import DiffDriveParams
from launchkit.stock.gazebo_ros.sim.model import PluginSpec

RESTART_DELAY = 1.0
STOP_TIMEOUT = 3.0
#: How the server stops a plugin node it runs itself.
FALLBACK_STOP = Escalation(((signal.SIGTERM, STOP_TIMEOUT), (signal.SIGKILL, None)))
DIFF_DRIVE_MODULE = "launchkit.stock.gazebo_ros.diff_drive_node"
CAMERA_MODULE = "launchkit.stock.gazebo_ros.camera_node"
_PR_SET_PDEATHSIG = 1


def _die_with_parent() -> None:
    # Runs in the child between fork and exec.
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGTERM)


def _plugin_folder() -> Path:
    """Where the plugin nodes' parameter files go: in the launch's private folder under
    ``launchkit run``, else in the system's temporary folder."""
    launch_folder = os.environ.get(RUN_TMPDIR)
    if launch_folder and os.path.isdir(launch_folder):
        return Path(tempfile.mkdtemp(prefix="gazebo-", dir=launch_folder))
    return Path(tempfile.mkdtemp(prefix="launchkit-gazebo-"))


def _owned_by_the_launch(folder: Path) -> bool:
    """True when ``folder`` is in the launch's private folder: the launcher removes it after
    its last process ended (its orphan guard even if everything is SIGKILLed), so a plugin node
    it started just before a Ctrl-C still finds its file after the server is gone."""
    launch_folder = os.environ.get(RUN_TMPDIR)
    return launch_folder is not None and folder.parent == Path(launch_folder)


def plugin_command(
    module: str,
    entity: str,
    plugin: PluginSpec,
    parameters: Mapping[str, object],
    params_file: Path,
    *,
    remap: bool,
) -> list[str]:
    """The command line of the node process that runs ``plugin`` of ``entity``: ``python -m
    module`` named after the plugin, in its ``<ros>`` namespace, with ``parameters`` (and the
    entity's name) written to ``params_file``. ``remap``: pass the block's remappings on (the
    camera has applied them to its topic names already)."""
    values: dict[str, object] = {"entity": entity, **parameters}
    params_file.write_text(yaml.safe_dump({"/**": {"ros__parameters": values}}))
    argv = [sys.executable, "-m", module, "--ros-args", "-r", f"__node:={plugin.name}"]
    if plugin.ros.namespace:
        argv += ["-r", f"__ns:=/{plugin.ros.namespace.strip('/')}"]
    argv += ["--params-file", str(params_file)]
    for source, target in plugin.ros.remappings if remap else ():
        argv += ["-r", f"{source}:={target}"]
    return argv


@dataclass
class Child:
    """One plugin child: its command, and either the launcher's id for it or, when the server
    supervises it itself, its process and its lifecycle."""

    name: str
    argv: list[str]
    launcher_id: int | None = None
    process: subprocess.Popen[bytes] | None = None
    lifecycle: Lifecycle = field(
        default_factory=lambda: Lifecycle(FALLBACK_STOP, RespawnPolicy(True, RESTART_DELAY))
    )


@dataclass
class PluginProcesses:
    """The children of the server, keyed by entity."""

    log: Callable[[str], object]
    children: dict[str, list[Child]] = field(default_factory=dict)
    _folder: Path = field(default_factory=_plugin_folder)
    _launcher: SupervisorClient | None = None
    _asked_launcher: bool = False

    def start_diff_drive(self, entity: str, plugin: PluginSpec, params: DiffDriveParams) -> None:
        """Start the diff drive node of ``plugin`` for ``entity``."""
        params_file = self._folder / f"{entity}-{plugin.name}.yaml"
        parameters = params.as_parameters()
        argv = plugin_command(
            DIFF_DRIVE_MODULE, entity, plugin, parameters, params_file, remap=True
        )
        self._start_child(entity, plugin.name, argv)

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
        params_file = self._folder / f"{entity}-{plugin.name}.yaml"
        parameters = params.as_parameters()
        argv = plugin_command(CAMERA_MODULE, entity, plugin, parameters, params_file, remap=False)
        self._start_child(entity, plugin.name, argv)

    def _spawn(self, child: Child) -> None:
        child.process = subprocess.Popen(
            child.argv, start_new_session=True, preexec_fn=_die_with_parent
        )
        child.lifecycle.started()
        self.log(f"started plugin node '{child.name}' (pid {child.process.pid})")

    def supervise(self) -> None:
        """Restart children the server runs itself that died (after :data:`RESTART_DELAY`);
        call now and then. (The launcher restarts its own.)"""
        now = time.monotonic()
        for children in self.children.values():
            for child in children:
                process = child.process
                if child.launcher_id is not None or process is None:
                    continue
                code = process.poll() if child.lifecycle.alive else None
                if code is not None:
                    outcome = child.lifecycle.exited(code, now)
                    self.log(
                        f"plugin node '{child.name}' exited with {code}; "
                        f"restarting in {outcome.respawn_in or 0:.0f} s"
                    )
                elif isinstance(child.lifecycle.due(now), Respawn):
                    self._spawn(child)

    def stop_entity(self, entity: str) -> None:
        """Stop the children of ``entity``."""
        self._stop(self.children.pop(entity, []))

    def stop(self) -> None:
        """Stop every child, close the launcher connection, remove the parameter files (the
        launcher removes them when it started the children: see :func:`_owned_by_the_launch`)."""
        everything = [c for children in self.children.values() for c in children]
        self.children.clear()
        self._stop(everything)
        if self._launcher is not None:
            self._launcher.close()  # the launcher would stop what is left of them now anyway
            self._launcher = None
        if not _owned_by_the_launch(self._folder):
            shutil.rmtree(self._folder, ignore_errors=True)

    def _stop(self, children: list[Child]) -> None:
        for child in children:
            if child.launcher_id is not None and self._launcher is not None:
                try:
                    self._launcher.stop(child.launcher_id)
                except SupervisorError as error:
                    self.log(f"the launcher did not stop plugin node '{child.name}': {error}")
        _stop_all([c for c in children if c.launcher_id is None])


def _stop_all(children: list[Child]) -> None:
    """Stop the children the server runs itself, all at once, escalating each on its own
    deadline (SIGTERM, then SIGKILL)."""
    now = time.monotonic()
    running: list[tuple[Child, subprocess.Popen[bytes]]] = []
    for child in children:
        effect = child.lifecycle.stop(now, retire=True)
        if effect is not None and child.process is not None and child.process.poll() is None:
            kill_group(child.process.pid, effect.signum)
            running.append((child, child.process))
    for child, process in running:
        while True:
            deadline = child.lifecycle.deadline
            try:
                process.wait(None if deadline is None else max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                escalation = child.lifecycle.due(time.monotonic())
                if isinstance(escalation, SendSignal):
                    kill_group(process.pid, escalation.signum)
                continue
            child.lifecycle.exited(process.returncode, time.monotonic())
            break
