"""``$(command CMD [ON_STDERR])``: the standard output of a program."""

from __future__ import annotations

import shlex
import subprocess
from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call

if TYPE_CHECKING:
    from launchkit.description.context import LaunchContext

ON_STDERR = ("fail", "ignore", "warn", "capture")
QUOTED_LINES = 4  # of a failing program's stderr: its last words, not a whole traceback


def last_words(stderr: str) -> tuple[str, list[str]]:
    """How to show a program's stderr in an error: one line inline (``": oops"``), or the
    last :data:`QUOTED_LINES` lines to quote under a headline that says how many there were."""
    lines = [line.rstrip() for line in stderr.strip().splitlines() if line.strip()]
    if not lines:
        return "", []
    if len(lines) == 1:
        return f": {lines[0].strip()}", []
    if len(lines) <= QUOTED_LINES:
        return "; on stderr:", lines
    return f"; the last {QUOTED_LINES} of its {len(lines)} lines on stderr:", lines[-QUOTED_LINES:]


class Command(Call):
    """Run CMD (split like a shell, no shell) and return its stdout verbatim.

    ON_STDERR says what output on stderr means: ``fail`` (default, as ROS), ``ignore``,
    ``warn`` (logged) or ``capture`` (appended to the result).
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
            result = subprocess.run(
                argv,
                capture_output=True,
                text=True,
                env=dict(context.environment),
                stdin=subprocess.DEVNULL,
                check=False,
            )
        except OSError as error:
            raise self.fail(f"command {text!r} could not run: {error.strerror}") from None
        stderr = result.stderr.strip()
        said, quoted = last_words(stderr)
        if result.returncode != 0:
            raise self.fail(
                f"command {text!r} failed with exit code {result.returncode}{said}", quoted=quoted
            )
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
                return result.stdout + result.stderr
        return result.stdout
