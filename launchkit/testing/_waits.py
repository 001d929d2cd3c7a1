"""How a wait decides, and which deaths a test must take note of.

The rules (``docs/testing.md`` states them for users):

- a wait succeeds as soon as its condition holds, on what was already received too, whatever
  else happened in the launch;
- it fails before its deadline only when its condition can no longer hold: the process it is
  about has exited (its check raises :class:`Impossible`), the launch reported an error, is
  being stopped or has ended, or a ``required`` (``on_exit="shutdown"``) process died;
- another process's unexpected death is evidence, not a verdict: later failures name it as a
  likely cause, and a death the test never took note of fails the test at teardown.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from pathlib import Path
from typing import TypeVar

from launchkit.runtime.process import describe_exit
from launchkit.testing._deadline import Deadline
from launchkit.testing._errors import ProcessDied, WaitTimeout
from launchkit.testing._evidence import describe_launch, process_status
from launchkit.testing._state import LaunchState, ProcessRecord

T = TypeVar("T")

#: ``launch(..., allow_exit=...)``: names of processes that may exit with any code, or
#: ``{name: code or codes}``; ``"*"`` names every process.
AllowExit = Mapping[str, int | Collection[int]] | Collection[str]


class Impossible(Exception):
    """Raised by a wait's check when what it awaits can no longer happen."""


class AllowedExits:
    """The exits a test declared expected up front with ``launch(..., allow_exit=...)``."""

    def __init__(self, allow: AllowExit | None) -> None:
        self._rules: dict[str, set[int] | None] = {}
        if allow is None:
            return
        if isinstance(allow, str):
            raise TypeError(
                f"allow_exit={allow!r}: expected process names (a list) or "
                "{name: exit code(s)}, not one string"
            )
        if isinstance(allow, Mapping):
            for name, codes in allow.items():
                self._rules[name] = {codes} if isinstance(codes, int) else set(codes)
        else:
            self._rules = dict.fromkeys(allow)

    def allows(self, record: ProcessRecord) -> bool:
        """Whether the test allowed ``record``'s exit (with the code it exited with)."""
        for name, codes in self._rules.items():
            if name == "*" or record.matches(name):
                return codes is None or record.returncode in codes
        return False


class Waits:
    """The waits of one launch: they run on its :class:`LaunchState` and describe failures
    with its evidence."""

    def __init__(
        self, state: LaunchState, title: str, launcher_log: Path, allowed: AllowedExits
    ) -> None:
        self.state = state
        self.title = title
        self.launcher_log = launcher_log
        self.allowed = allowed

    def until(
        self,
        what: str,
        timeout: float,
        check: Callable[[], T | None],
        *,
        subject: str | None = None,
    ) -> T:
        """Wait until ``check()`` (called with the state locked, after every event) returns
        something other than None; that value.

        Raises :class:`ProcessDied` at once when ``check`` raises :class:`Impossible` or the
        launch can no longer deliver (see :meth:`launch_over`), and :class:`WaitTimeout` at
        the deadline. Both say what was awaited, name unexpected deaths of other processes
        than ``subject`` as likely causes, and show every process.
        """
        __tracebackhide__ = True
        deadline = Deadline(timeout)
        state = self.state
        with state.condition:
            while True:
                try:
                    value = check()
                except Impossible as why:
                    # the process exited; if the launch is over (an error, a required death,
                    # its end), that is the cause of the exit: name it first
                    over = self.launch_over()
                    problem = f"{why} before it came"
                    if over is not None:
                        problem = f"{over} ({problem})"
                    raise ProcessDied(self.failure(what, problem, subject)) from None
                if value is not None:
                    return value
                over = self.launch_over()
                if over is not None:
                    raise ProcessDied(self.failure(what, over, subject))
                if deadline.expired():
                    timed_out = f"timed out after {deadline.seconds:g} s"
                    raise WaitTimeout(self.failure(what, timed_out, subject))
                state.condition.wait(deadline.remaining())

    def launch_over(self) -> str | None:
        """Why no wait on this launch can succeed any more, or None (call with the lock)."""
        state = self.state
        if state.errors and not state.stopping:
            return f"the launch failed: {state.errors[-1]}"
        if state.stopping:
            return "the launch is being stopped"
        for record in state.processes.values():
            if record.required and record.died_unexpectedly() and not record.noted:
                return (
                    f"process {record.label}, which the launch requires "
                    f'(on_exit="shutdown"), died: {process_status(record)}'
                )
        if state.channel_closed:
            why = f"; {state.shutdown_reason}" if state.shutdown_reason else ""
            code = state.launcher_returncode
            status = "" if code is None else f", launcher {describe_exit(code)}"
            return f"the launch has ended{why}{status}"
        return None

    def unnoted_deaths(self, subject: str | None = None) -> list[ProcessRecord]:
        """Processes that died unexpectedly, that the test neither took note of nor allowed
        (leaving out the one ``subject`` names). Call with the lock held."""
        return [
            record
            for record in self.state.processes.values()
            if record.died_unexpectedly()
            and not record.noted
            and not self.allowed.allows(record)
            and not (subject is not None and record.matches(subject))
        ]

    def failure(self, what: str, problem: str, subject: str | None = None) -> str:
        """A wait's failure message: the problem, what was awaited, likely causes, and every
        process's status and last lines. Call with the lock held."""
        lines = [f"{problem} waiting for {what} in {self.title}"]
        deaths = self.unnoted_deaths(subject)
        if deaths:
            label = "a likely cause" if len(deaths) == 1 else "likely causes"
            lines.append(f"{label}: " + "; ".join(_death(record) for record in deaths))
        lines.append(describe_launch(self.state, self.launcher_log))
        return "\n".join(lines)

    def teardown_verdict(self) -> str | None:
        """The message that fails a test at teardown for deaths it never took note of, or
        None. Call with the lock held."""
        deaths = self.unnoted_deaths()
        if not deaths:
            return None
        names = ", ".join(repr(record.name) for record in deaths)
        return (
            "; ".join(_death(record) for record in deaths)
            + f", and the test never took note of it in {self.title} (check it with "
            "wait_exit(), returncode, or the result's exit_codes or assert_exit_codes(); "
            f"or declare it with launch(..., allow_exit=[{names}]))\n"
            + describe_launch(self.state, self.launcher_log)
        )


def _death(record: ProcessRecord) -> str:
    return f"process {record.label} died unexpectedly: {process_status(record)}"
