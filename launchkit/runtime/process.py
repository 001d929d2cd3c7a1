"""One supervised process: spawning it in its own process group, reading its output, and the
lifecycle states it moves through.

States (supervisor/circus style)::

    STARTING -> RUNNING -> EXITED            (exited on its own; may go to BACKOFF to respawn)
                       \\-> STOPPING -> EXITED (we signalled it)
    STARTING -> FAILED                        (could not be spawned)
    BACKOFF  -> STARTING                      (respawn after respawn_delay)
"""

from __future__ import annotations

import enum
import errno
import os
import pty
import signal
import subprocess
from dataclasses import dataclass, field

from launchkit.description.process_spec import ProcessSpec


class State(enum.Enum):
    """Where a process is in its lifecycle."""

    STARTING = "starting"
    RUNNING = "running"
    STOPPING = "stopping"
    BACKOFF = "backoff"
    EXITED = "exited"
    FAILED = "failed"


@dataclass
class Stream:
    """One output channel of a child (a pipe, or a pty for emulate_tty)."""

    fd: int
    kind: str  # "stdout" or "stderr"
    pending: bytes = b""


@dataclass
class ManagedProcess:
    """A process the supervisor owns: its spec, its current incarnation and its history."""

    spec: ProcessSpec
    label: str
    index: int
    state: State = State.STARTING
    popen: subprocess.Popen[bytes] | None = None
    pidfd: int | None = None
    streams: dict[int, Stream] = field(default_factory=dict)
    returncode: int | None = None
    retries: int = 0
    signals_sent: list[int] = field(default_factory=list)
    escalation_at: float | None = None
    respawn_at: float | None = None
    retired: bool = False  # stopped on request (not by a shutdown): never respawned

    @property
    def pid(self) -> int | None:
        """The current incarnation's pid."""
        return self.popen.pid if self.popen is not None else None

    @property
    def alive(self) -> bool:
        """Whether an incarnation is running (or being stopped)."""
        return self.state in (State.RUNNING, State.STOPPING)

    def spawn(self) -> None:
        """Start the process in a new session (so its own process group); raises OSError."""
        spec = self.spec
        if spec.emulate_tty:
            out_r, out_w = pty.openpty()
            err_r, err_w = None, out_w
        else:
            out_r, out_w = os.pipe()
            err_r, err_w = os.pipe()
        try:
            self.popen = subprocess.Popen(
                spec.cmd,
                cwd=spec.cwd or None,
                env=spec.env,
                stdin=subprocess.DEVNULL,
                stdout=out_w,
                stderr=err_w,
                start_new_session=True,
                close_fds=True,
            )
        except BaseException:
            for fd in {out_r, out_w, err_r, err_w} - {None}:
                os.close(fd)  # type: ignore[arg-type]
            raise
        finally:
            # the child has its copies; ours must go so EOF arrives when it exits
            for fd in {out_w, err_w}:
                try:
                    os.close(fd)
                except OSError:
                    pass
        self.streams.clear()
        self._add_stream(out_r, "stdout")
        if err_r is not None:
            self._add_stream(err_r, "stderr")
        self.pidfd = _pidfd_open(self.popen.pid)
        self.returncode = None
        self.signals_sent.clear()
        self.escalation_at = None
        self.state = State.RUNNING

    def _add_stream(self, fd: int, kind: str) -> None:
        os.set_blocking(fd, False)
        self.streams[fd] = Stream(fd, kind)

    def read(self, fd: int) -> tuple[list[str], bool]:
        """Read what is available on ``fd``: complete lines, and whether it reached EOF."""
        stream = self.streams[fd]
        lines: list[str] = []
        eof = False
        while True:
            try:
                chunk = os.read(fd, 65536)
            except BlockingIOError:
                break
            except OSError as error:
                if error.errno != errno.EIO:  # EIO: the pty's other side closed
                    raise
                chunk = b""
            if not chunk:
                eof = True
                break
            stream.pending += chunk
            *complete, stream.pending = stream.pending.split(b"\n")
            lines.extend(_decode(line) for line in complete)
        if eof and stream.pending:
            lines.append(_decode(stream.pending))
            stream.pending = b""
        return lines, eof

    def close_stream(self, fd: int) -> None:
        """Forget and close one stream."""
        if self.streams.pop(fd, None) is not None:
            os.close(fd)

    def poll(self) -> int | None:
        """Reap the process if it exited; its return code (negative: killed by a signal)."""
        return None if self.popen is None else self.popen.poll()

    def signal_group(self, signum: int) -> None:
        """Send ``signum`` to the process's whole group (its ``sh -c`` children too)."""
        if self.popen is None:
            return
        self.signals_sent.append(signum)
        try:
            os.killpg(self.popen.pid, signum)
        except (ProcessLookupError, PermissionError):
            pass

    def kill_leftovers(self) -> None:
        """SIGKILL whatever is left in the process group (orphaned grandchildren)."""
        if self.popen is not None:
            try:
                os.killpg(self.popen.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass


def _decode(data: bytes) -> str:
    return data.decode("utf-8", errors="replace").rstrip("\r")


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
