"""One supervised process as the operating system sees it: spawned in its own session (so its
own process group), its output read line by line, its group signalled.

A child is started *gated*: ``/bin/sh`` waits for one line on its stdin before it execs the
program, and the line is written only once ``on_spawn`` (the orphan guard) knows the new group.
If the launcher is SIGKILLed in between, the gate reads end-of-file and the program never runs.

The supervisor makes processes through a factory (:data:`ProcessFactory`), so its loop can be
unit-tested with processes that are not real (:class:`SupervisedProcess` is what it needs of
one). Where each process is in its life is its :class:`~launchkit.runtime.lifecycle.Lifecycle`.
"""

from __future__ import annotations

import errno
import os
import pty
import shutil
import signal
import subprocess
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

from launchkit.description.process_spec import ProcessSpec
from launchkit.errors import LaunchFileError, LaunchkitError
from launchkit.runtime.lifecycle import Escalation, Lifecycle, RespawnPolicy, State
from launchkit.runtime.lines import LineBuffer
from launchkit.startup_sigint import holds_sigint, sigint_blocked

#: The most a single read of one stream takes (then the loop looks at everything else).
READ_CHUNK = 64 * 1024

# sh -c GATE PROGRAM ARGS...: $0 is the program, "$@" its arguments.
_GATE = 'read -r _ || exit 125; exec "$0" "$@" </dev/null'


@dataclass
class Stream:
    """One output channel of a child (a pipe, or a pty for emulate_tty)."""

    fd: int
    kind: str  # "stdout" or "stderr"
    lines: LineBuffer = field(default_factory=LineBuffer)


def lifecycle_of(spec: ProcessSpec) -> Lifecycle:
    """A new lifecycle with ``spec``'s stop timeouts and respawn settings."""
    return Lifecycle(
        Escalation.ros(spec.sigterm_timeout, spec.sigkill_timeout),
        RespawnPolicy(spec.respawn, spec.respawn_delay, spec.respawn_max_retries),
    )


class SupervisedProcess(Protocol):
    """What the supervisor (and its observers) use of a process."""

    spec: ProcessSpec
    label: str
    index: int
    lifecycle: Lifecycle
    pidfd: int | None
    streams: dict[int, Stream]

    @property
    def pid(self) -> int | None:
        """The current incarnation's pid (and process group)."""

    @property
    def state(self) -> State:
        """Where the process is in its life."""

    @property
    def alive(self) -> bool:
        """Whether an incarnation is running (or being stopped)."""

    def spawn(self) -> None:
        """Start a new incarnation; ``OSError`` if it cannot be started."""

    def read(self, fd: int, limit: int = READ_CHUNK) -> tuple[list[str], bool]:
        """Lines available on ``fd`` (reading at most ``limit`` bytes), and whether it ended."""

    def close_stream(self, fd: int) -> None:
        """Forget and close one output stream."""

    def close_pidfd(self) -> None:
        """Close the exit notification fd (after it fired, or at the end)."""

    def poll(self) -> int | None:
        """Reap the incarnation if it exited; its return code."""

    def signal_group(self, signum: int) -> None:
        """Send ``signum`` to the incarnation's process group."""

    def group_alive(self) -> bool:
        """Whether anything is left in the incarnation's process group."""

    def kill_leftovers(self) -> None:
        """SIGKILL whatever is left in the incarnation's process group."""

    def reap(self) -> None:
        """Wait for the incarnation to exit (after it was killed)."""


#: Makes a process to supervise from its spec, its label (``name-N``) and its index N.
ProcessFactory = Callable[[ProcessSpec, str, int], SupervisedProcess]


def by_machine(local: ProcessFactory, remote: ProcessFactory | None) -> ProcessFactory:
    """A factory that makes a spec for another host (``spec.machine``, ``<group machine>``)
    with ``remote`` (its agent runs it) and every other spec with ``local``."""

    def make(spec: ProcessSpec, label: str, index: int) -> SupervisedProcess:
        if not spec.machine:
            return local(spec, label, index)
        if remote is None:
            raise LaunchkitError(f"'{spec.name}' is for machine {spec.machine!r}: no agents here")
        return remote(spec, label, index)

    return make


class ProcessPipes:
    """What the supervisor reads of any process it supervises, here or on another host
    (:class:`ManagedProcess`, :class:`launchkit.remote.remote_process.RemoteProcess`): its
    spec, label and lifecycle, its output streams (non-blocking fds read line by line) and the
    fd that becomes readable when it exits (``pidfd``)."""

    def __init__(self, spec: ProcessSpec, label: str, index: int) -> None:
        self.spec = spec
        self.label = label
        self.index = index
        self.lifecycle = lifecycle_of(spec)
        self.pidfd: int | None = None
        self.streams: dict[int, Stream] = {}

    @property
    def state(self) -> State:
        """Where the process is in its life."""
        return self.lifecycle.state

    @property
    def alive(self) -> bool:
        """Whether an incarnation is running (or being stopped)."""
        return self.lifecycle.alive

    def add_stream(self, fd: int, kind: str) -> None:
        """Follow ``fd`` (made non-blocking) as the process's ``kind`` output."""
        os.set_blocking(fd, False)
        self.streams[fd] = Stream(fd, kind)

    def read(self, fd: int, limit: int = READ_CHUNK) -> tuple[list[str], bool]:
        """Read what is available on ``fd``, at most ``limit`` bytes (so that a flood cannot
        hold the loop): the lines it completes (bounded and split by the stream's
        :class:`LineBuffer`), and whether the stream ended."""
        stream = self.streams[fd]
        lines: list[str] = []
        taken = 0
        while taken < limit:
            try:
                chunk = os.read(fd, min(READ_CHUNK, limit - taken))
            except BlockingIOError:
                return lines, False
            except OSError as error:
                if error.errno != errno.EIO:  # EIO: the pty's other side closed
                    raise
                chunk = b""
            if not chunk:
                lines.extend(stream.lines.finish())
                return lines, True
            taken += len(chunk)
            lines.extend(stream.lines.feed(chunk))
        return lines, False

    def close_stream(self, fd: int) -> None:
        """Forget and close one stream."""
        if self.streams.pop(fd, None) is not None:
            os.close(fd)

    def close_pidfd(self) -> None:
        """Close the exit notification fd."""
        if self.pidfd is not None:
            os.close(self.pidfd)
            self.pidfd = None


class ManagedProcess(ProcessPipes):
    """A real process the supervisor owns: its spec, its current incarnation, its lifecycle.
    ``on_spawn`` is told each new process group (the orphan guard watches them)."""

    def __init__(
        self,
        spec: ProcessSpec,
        label: str,
        index: int,
        on_spawn: Callable[[int], None] = lambda _pgid: None,
    ) -> None:
        super().__init__(spec, label, index)
        self.on_spawn = on_spawn
        self.popen: subprocess.Popen[bytes] | None = None

    @property
    def pid(self) -> int | None:
        """The current incarnation's pid."""
        return self.popen.pid if self.popen is not None else None

    def spawn(self) -> None:
        """Start the process in a new session (so its own process group); raises OSError.
        Streams of an earlier incarnation that a grandchild still holds stay until their end."""
        spec = self.spec
        if spec.emulate_tty:
            out_r, out_w = pty.openpty()
            err_r, err_w = None, out_w
        else:
            out_r, out_w = os.pipe()
            err_r, err_w = os.pipe()
        gate_r, gate_w = os.pipe()
        try:
            with sigint_blocked(holds_sigint(spec.cmd)):  # launchkit's nodes take it once ready
                self.popen = subprocess.Popen(
                    ["/bin/sh", "-c", _GATE, *spec.cmd],
                    cwd=spec.cwd or None,
                    env=spec.env,
                    stdin=gate_r,
                    stdout=out_w,
                    stderr=err_w,
                    start_new_session=True,
                    close_fds=True,
                )
        except BaseException:
            for fd in {out_r, err_r, gate_w} - {None}:
                os.close(fd)  # type: ignore[arg-type]
            raise
        finally:
            # the child has its copies; ours must go so EOF arrives when it exits
            for fd in {out_w, err_w, gate_r}:
                try:
                    os.close(fd)
                except OSError:
                    pass
        self.add_stream(out_r, "stdout")
        if err_r is not None:
            self.add_stream(err_r, "stderr")
        self.pidfd = _pidfd_open(self.popen.pid)
        try:
            self.on_spawn(self.popen.pid)
        finally:
            _open_gate(gate_w)

    def poll(self) -> int | None:
        """Reap the process if it exited; its return code (negative: killed by a signal)."""
        return None if self.popen is None else self.popen.poll()

    def signal_group(self, signum: int) -> None:
        """Send ``signum`` to the process's whole group (its ``sh -c`` children too)."""
        if self.popen is not None:
            kill_group(self.popen.pid, signum)

    def group_alive(self) -> bool:
        """Whether anything is left in the process group (a grandchild after the exit)."""
        return self.popen is not None and group_exists(self.popen.pid)

    def kill_leftovers(self) -> None:
        """SIGKILL whatever is left in the process group (orphaned grandchildren)."""
        if self.popen is not None:
            kill_group(self.popen.pid, signal.SIGKILL)

    def reap(self) -> None:
        """Wait for the incarnation to exit."""
        if self.popen is not None:
            self.popen.wait()


def kill_group(pgid: int, signum: int) -> None:
    """Send ``signum`` to process group ``pgid``; a group that is gone is no error."""
    try:
        os.killpg(pgid, signum)
    except (ProcessLookupError, PermissionError):
        pass


def group_exists(pgid: int | None) -> bool:
    """Whether process group ``pgid`` has a member."""
    if not pgid:
        return False
    try:
        os.killpg(pgid, 0)
    except (ProcessLookupError, PermissionError):
        return False
    return True


def missing_folder(spec: ProcessSpec) -> bool:
    """Whether ``spec`` runs on this host in a working folder that does not exist (as in ROS,
    that process fails to start and the launch goes on)."""
    return bool(spec.cwd) and not spec.machine and not os.path.isdir(spec.cwd or "")


def check_program(spec: ProcessSpec) -> None:
    """Fail before anything starts when a process's program does not exist (its working
    folder is looked for when it starts: see :func:`missing_folder`)."""
    if missing_folder(spec):
        return  # reported when it starts; its program is relative to a folder that is not
    program = spec.cmd[0]
    if "/" in program:
        path = program if os.path.isabs(program) else os.path.join(spec.cwd or os.getcwd(), program)
        if os.access(path, os.X_OK) and os.path.isfile(path):
            return
    elif shutil.which(program, path=spec.env.get("PATH", os.defpath)):
        return
    raise LaunchFileError(
        f"program '{program}' of process '{spec.name}' not found",
        spec.location,
        expected="an executable file, or a program on the PATH",
    )


def check_programs(specs: list[ProcessSpec]) -> None:
    """:func:`check_program` for each spec, in order; a program already found with the same
    folder and ``PATH`` is not looked up again (a PATH search is a dozen ``stat`` calls, and a
    launch may start one program a hundred times)."""
    found: set[tuple[str | None, str, str | None]] = set()
    for spec in specs:
        key = (spec.cwd, spec.cmd[0], spec.env.get("PATH"))
        if key not in found:
            check_program(spec)
            found.add(key)


def _open_gate(fd: int) -> None:
    try:
        os.write(fd, b"\n")
    except OSError:
        pass  # it died already (a signal to its group)
    finally:
        os.close(fd)


def _pidfd_open(pid: int) -> int | None:
    opener = getattr(os, "pidfd_open", None)
    if opener is None:
        return None
    try:
        return int(opener(pid))
    except OSError:
        return None


def describe_exit(code: int) -> str:
    """``exit code 3`` or ``signal SIGTERM``."""
    if code < 0:
        try:
            return f"signal {signal.Signals(-code).name}"
        except ValueError:
            return f"signal {-code}"
    return f"exit code {code}"
