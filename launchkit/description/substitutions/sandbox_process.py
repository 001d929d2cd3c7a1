"""``$(eval)`` evaluated where it can be stopped: a small evaluator process per launcher.

The sandbox (:mod:`launchkit.description.substitutions.sandbox`) bounds values between the
steps of an expression, but one step can be a single long C call (``sorted`` of a hundred
thousand huge integers with ``key=str``) that no check inside the interpreter interrupts. So
expressions are evaluated by a child process (:mod:`.sandbox_worker`), started on the first
``$(eval)`` of a launch and kept for the next ones: about 0.1 s once, then a fraction of a
millisecond per expression. The launcher measures what the evaluation costs by the kernel's
clocks: the child's CPU time (``/proc/PID/stat``) against the time limit, and wall time
against ten times it (a child starved by a loaded machine gets its share first). Past either,
the child is killed (and replaced at the next expression). Its address space is capped too.
"""

from __future__ import annotations

import atexit
import json
import os
import select
import subprocess
import sys
import threading
import time
from pathlib import Path

from launchkit.description.substitutions.sandbox_names import LimitError, Limits, SandboxError
from launchkit.own_process import own_helpers

__all__ = ["Evaluator", "LimitError", "Limits", "SandboxError", "evaluate"]

#: A slow machine's allowance for starting the evaluator (not counted against an expression).
STARTUP_TIMEOUT = 30.0
#: Wall time an expression may take, in multiples of its CPU time limit.
WALL_FACTOR = 10.0
_POLL = 0.02
#: The evaluator's program. It ignores SIGINT first thing: a Ctrl-C at the terminal reaches the
#: launcher's whole process group, and the launcher ends this process itself (its stdin closes,
#: or it is killed), so a KeyboardInterrupt traceback from it would only be noise.
_BOOT = (
    "import signal; signal.signal(signal.SIGINT, signal.SIG_IGN); "
    "import sys; sys.path.insert(0, sys.argv.pop(1)); "
    "from launchkit.description.substitutions.sandbox_worker import main; main()"
)
_TICKS = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


class Evaluator:
    """One evaluator process, started when first needed, replaced when it had to be killed;
    ``memory``: how many bytes it may grow by."""

    def __init__(self, memory: int = Limits.memory) -> None:
        self.memory = memory
        self._lock = threading.Lock()
        self._proc: subprocess.Popen[bytes] | None = None
        self._owner = os.getpid()

    def evaluate(self, expression: str, modules: list[str], limits: Limits) -> str:
        """``str()`` of the expression's value; :class:`SandboxError` for anything refused,
        failed, or beyond the limits."""
        request = {"expression": expression, "modules": modules, "seconds": limits.seconds}
        with self._lock:
            proc = self._running()
            assert proc.stdin is not None and proc.stdout is not None
            try:
                proc.stdin.write(json.dumps(request).encode() + b"\n")
                proc.stdin.flush()
                line = self._answer(proc, limits)
            except OSError:
                self._kill()
                raise SandboxError("the evaluator process ended unexpectedly") from None
            except BaseException:  # a signal (Ctrl-C) once the request may be on its way: its
                self._kill()  # answer would be read as the next expression's
                raise
        try:
            reply = json.loads(line)
        except ValueError:
            raise SandboxError("the evaluator process answered nonsense") from None
        if "error" in reply:
            raise (LimitError if reply.get("limit") else SandboxError)(str(reply["error"]))
        return str(reply["value"])

    def _running(self) -> subprocess.Popen[bytes]:
        if self._proc is not None and self._owner == os.getpid() and self._proc.poll() is None:
            return self._proc
        if self._owner != os.getpid():  # a forked copy: the evaluator is the parent's
            self._proc, self._owner = None, os.getpid()
        self._kill()
        root = str(Path(__file__).resolve().parents[3])  # the folder holding launchkit/
        proc = subprocess.Popen(
            [sys.executable, "-I", "-S", "-c", _BOOT, root, str(os.getpid()), str(self.memory)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            env={},
            close_fds=True,
        )
        assert proc.stdout is not None
        ready, _, _ = select.select([proc.stdout], [], [], STARTUP_TIMEOUT)
        if not ready or proc.stdout.readline() != b"ready\n":
            proc.kill()
            proc.wait()
            raise SandboxError(f"the evaluator process did not start within {STARTUP_TIMEOUT:g} s")
        self._proc = proc
        own_helpers.add(proc.pid)  # the launcher's own: not a stray of its launch
        return proc

    def _answer(self, proc: subprocess.Popen[bytes], limits: Limits) -> bytes:
        """The child's answer line, or :class:`SandboxError` once it used its CPU time (or
        ten times that in wall time)."""
        assert proc.stdout is not None
        cpu_start, wall_start = _cpu_seconds(proc.pid), time.monotonic()
        while True:
            ready, _, _ = select.select([proc.stdout], [], [], _POLL)
            if ready:
                line = proc.stdout.readline()
                if line.endswith(b"\n"):
                    return line
                self._kill()
                raise LimitError(
                    "the evaluator process died evaluating it (its memory is limited to "
                    f"{self.memory // 2**20} MiB)"
                )
            cpu = _cpu_seconds(proc.pid) - cpu_start
            wall = time.monotonic() - wall_start
            if cpu > limits.seconds or wall > limits.seconds * WALL_FACTOR:
                self._kill()
                spent = f"{cpu:.1f} s of CPU time" if cpu > limits.seconds else f"{wall:.1f} s"
                raise LimitError(
                    f"the expression took longer than {limits.seconds:g} s (stopped after {spent})"
                )

    def _kill(self) -> None:
        proc, self._proc = self._proc, None
        if proc is not None and proc.poll() is None:
            proc.kill()
        if proc is not None:
            proc.wait()
            own_helpers.discard(proc.pid)
            for stream in (proc.stdin, proc.stdout):
                if stream is not None:
                    stream.close()

    def close(self) -> None:
        """Stop the evaluator process (its stdin ends; it exits)."""
        with self._lock:
            if self._owner == os.getpid():
                self._kill()


def _cpu_seconds(pid: int) -> float:
    """CPU time ``pid`` has used so far (user and system), by the kernel's account."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as stat:
            fields = stat.read().rsplit(b")", 1)[1].split()
    except (OSError, IndexError):
        return 0.0
    return (int(fields[11]) + int(fields[12])) / _TICKS


_evaluator: Evaluator | None = None
_evaluator_lock = threading.Lock()


def evaluate(expression: str, modules: list[str], limits: Limits | None = None) -> str:
    """``str()`` of ``expression``'s value, evaluated in the launcher's evaluator process."""
    global _evaluator
    with _evaluator_lock:
        if _evaluator is None:
            _evaluator = Evaluator()
            atexit.register(_evaluator.close)
        evaluator = _evaluator
    return evaluator.evaluate(expression, modules, limits or Limits())
