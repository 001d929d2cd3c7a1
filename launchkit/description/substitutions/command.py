"""``$(command CMD [ON_STDERR])``: the standard output of a program."""

from __future__ import annotations

import os
import re
import selectors
import shlex
import signal
import subprocess
from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext

ON_STDERR = ("fail", "ignore", "warn", "capture")
QUOTED_LINES = 4  # of a failing program's stderr: its last words, not a whole traceback

#: A line that says what went wrong (``error: No such file ...``, ``XML parsing error: ...``,
#: ``FileNotFoundError: ...``, ``[ERROR] ...``): a program may write warnings before it (xacro's
#: deprecations) and context after it (xacro's "when processing file" chain).
_ERROR_LINE = re.compile(r"(?i)(\b\w*(error|exception)\b\s*:|^\s*fatal\b|\[error\])")


def last_words(stderr: str) -> tuple[str, list[str]]:
    """How to show a program's stderr in an error: one line inline (``": oops"``), or lines to
    quote under a headline that says which they are: the first line that names an error, when
    the last :data:`QUOTED_LINES` lines do not hold it, then those last lines."""
    lines = [line.rstrip() for line in stderr.strip().splitlines() if line.strip()]
    if not lines:
        return "", []
    if len(lines) == 1:
        return f": {lines[0].strip()}", []
    if len(lines) <= QUOTED_LINES:
        return "; on stderr:", lines
    tail = lines[-QUOTED_LINES:]
    first = next((line for line in lines if _ERROR_LINE.search(line)), None)
    if first is None or first in tail:
        return f"; the last {QUOTED_LINES} of its {len(lines)} lines on stderr:", tail
    return (
        f"; its first error and the last {QUOTED_LINES} of its {len(lines)} lines on stderr:",
        [first, "...", *tail],
    )


#: What a command may write (stdout and stderr together) before it is stopped as runaway.
MAX_OUTPUT = 64 * 1024 * 1024


class Command(Call):
    """Run CMD (split like a shell, no shell) and return its stdout verbatim.

    ON_STDERR says what output on stderr means: ``fail`` (default, as ROS), ``ignore``,
    ``warn`` (logged) or ``capture`` (appended to the result).

    The command runs in its own process group, which is killed if the launcher is interrupted
    while it waits (Ctrl-C, SIGTERM), if it writes more than :data:`MAX_OUTPUT`, and after it
    exits if anything of it is left running (no orphans; ROS would leave them).
    """

    NAME = "command"
    MIN_ARGS = 1
    MAX_ARGS = 2
    USAGE = "COMMAND [fail|ignore|warn|capture]"

    def perform(self, context: LaunchContext) -> str:
        """The command's output; an error with its stderr when it fails."""
        text = self.arg(0, context)
        on_stderr = self.arg(1, context, "fail")
        if on_stderr not in ON_STDERR:
            raise self.fail(
                f"unknown ON_STDERR '{on_stderr}' for $(command)",
                expected="one of " + ", ".join(ON_STDERR),
            )
        try:
            argv = shlex.split(text)
        except ValueError as error:
            raise self.fail(f"cannot split command {text!r}: {error}") from None
        if not argv:
            raise self.fail("$(command) got an empty command")
        try:
            code, out, err = _run(argv, context)
        except OSError as error:
            raise self.fail(f"command {text!r} could not run: {error.strerror}") from None
        if code is None:
            raise self.fail(f"command {text!r} wrote more than {MAX_OUTPUT >> 20} MB: stopped")
        stdout = out.decode(errors="replace")
        stderr = err.decode(errors="replace").strip()
        said, quoted = last_words(stderr)
        if code != 0:
            raise self.fail(f"command {text!r} failed with exit code {code}{said}", quoted=quoted)
        if stderr:
            if on_stderr == "fail":
                raise self.fail(
                    f"command {text!r} wrote to stderr{said}",
                    expected="no stderr output, or $(command '...' warn|ignore|capture)",
                    quoted=quoted,
                )
            if on_stderr == "warn":
                context.log("WARNING", f"command {text!r} wrote to stderr: {stderr}")
            if on_stderr == "capture":
                return stdout + err.decode(errors="replace")
        return stdout


def _run(argv: list[str], context: LaunchContext) -> tuple[int | None, bytes, bytes]:
    """Run ``argv`` in its own session; its exit code (None: stopped for writing too much),
    stdout and stderr. Whatever interrupts the wait kills its group first."""
    groups = context.child_groups
    process: subprocess.Popen[bytes] | None = None
    out = err = b""
    complete = False
    returncode = 0
    try:
        # A signal raised inside Popen (after the fork) would lose the child: it is held
        # until the child is known here and to the orphan guard, then raised below.
        with context.uninterrupted():
            process = subprocess.Popen(
                argv,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                env=dict(context.environment),
                start_new_session=True,
            )
            if groups is not None:
                groups.watch(process.pid)
        out, err, complete = _collect(process)
        if complete:
            # wait without reaping: while the leader is a zombie, its group id cannot be reused
            # by another process, so killing what is left in the group is safe
            os.waitid(os.P_PID, process.pid, os.WEXITED | os.WNOWAIT)
    finally:
        if process is not None:
            _kill_group(process.pid)
            returncode = process.wait()
            for stream in (process.stdout, process.stderr):
                if stream is not None:
                    stream.close()
    assert process is not None  # Popen raised otherwise
    if not complete:
        return None, out, err
    if groups is not None:
        groups.forget(process.pid)
    return returncode, out, err


def _collect(process: subprocess.Popen[bytes]) -> tuple[bytes, bytes, bool]:
    """Read both pipes to their ends, or until :data:`MAX_OUTPUT` (then complete is False)."""
    assert process.stdout is not None and process.stderr is not None
    chunks: dict[int, list[bytes]] = {process.stdout.fileno(): [], process.stderr.fileno(): []}
    total = 0
    with selectors.DefaultSelector() as selector:
        for fd in chunks:
            selector.register(fd, selectors.EVENT_READ)
        while selector.get_map():
            for key, _ in selector.select():
                data = os.read(key.fd, 65536)
                if not data:
                    selector.unregister(key.fd)
                    continue
                chunks[key.fd].append(data)
                total += len(data)
                if total > MAX_OUTPUT:
                    return b"", b"", False
    out, err = (b"".join(parts) for parts in chunks.values())
    return out, err, True


def _kill_group(pgid: int) -> None:
    try:
        os.killpg(pgid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
