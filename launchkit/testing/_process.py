"""A handle on one process of a launch, found by name, with its waits."""

from __future__ import annotations

from typing import Protocol

from launchkit.testing._errors import LaunchTestError
from launchkit.testing._evidence import process_status
from launchkit.testing._matchers import Matcher, compile_matcher
from launchkit.testing._state import LaunchState, ProcessRecord
from launchkit.testing._waits import Impossible, Waits


class LaunchView(Protocol):
    """What a process handle uses of its launch (:class:`launchkit.testing.LaunchHandle`)."""

    title: str
    state: LaunchState
    waits: Waits

    def process_names(self) -> str:
        """The labels of the processes started so far."""


DEFAULT_TIMEOUT = 10.0
STREAMS = ("any", "stdout", "stderr")


class ProcessHandle:
    """One process of a launch, named as in the launch file: its ``name`` attribute, its
    executable's name or its ROS node name, or the ``name-N`` label launchkit prints.

    The handle may name a process that has not started yet (one a ``<timer>`` starts later):
    :meth:`wait_running` waits for it; the properties raise until it has started.
    """

    def __init__(self, launch: LaunchView, query: str) -> None:
        self._launch = launch
        self.query = query

    def __repr__(self) -> str:
        return f"<ProcessHandle {self.query!r} of {self._launch.title}>"

    # -- what is known now ---------------------------------------------------------------------

    def _find(self) -> ProcessRecord | None:
        """The process this handle names (call with the state's condition held)."""
        __tracebackhide__ = True
        found = self._launch.state.find(self.query)
        if len(found) > 1:
            exact = [record for record in found if record.label == self.query]
            if exact:
                return exact[0]
            labels = ", ".join(record.label for record in found)
            raise LaunchTestError(
                f"'{self.query}' names several processes of {self._launch.title}: {labels} "
                "(name one by its label)"
            )
        return found[0] if found else None

    def _started(self) -> ProcessRecord:
        record = self._find()
        if record is None:
            raise LaunchTestError(
                f"no process '{self.query}' has started in {self._launch.title} "
                f"(processes: {self._launch.process_names() or 'none'}); "
                "use wait_running() for one that starts later"
            )
        return record

    @property
    def label(self) -> str:
        """The ``name-N`` label launchkit gives the process."""
        __tracebackhide__ = True
        with self._launch.state.condition:
            return self._started().label

    @property
    def pid(self) -> int:
        """The pid of the process (of its latest incarnation when it respawns)."""
        __tracebackhide__ = True
        with self._launch.state.condition:
            pid = self._started().pid
        assert pid is not None
        return pid

    @property
    def cmdline(self) -> list[str]:
        """The command line the launcher ran."""
        __tracebackhide__ = True
        with self._launch.state.condition:
            return list(self._started().cmd)

    @property
    def returncode(self) -> int | None:
        """The exit code once it has exited (negative: the signal that killed it), else None.

        Reading an exit code takes note of it: the exit then no longer fails the test.
        """
        __tracebackhide__ = True
        with self._launch.state.condition:
            record = self._started()
            if record.running or record.returncode is None:
                return None
            record.noted = True
            return record.returncode

    @property
    def running(self) -> bool:
        """Whether the process is running now."""
        with self._launch.state.condition:
            record = self._find()
            return record is not None and record.running

    @property
    def output(self) -> list[str]:
        """Every line it wrote so far, stdout and stderr in the order they arrived."""
        return self._lines("any")

    @property
    def stdout(self) -> list[str]:
        """The lines it wrote on stdout (a pty, with ``emulate_tty``, counts as stdout)."""
        return self._lines("stdout")

    @property
    def stderr(self) -> list[str]:
        """The lines it wrote on stderr."""
        return self._lines("stderr")

    def _lines(self, stream: str) -> list[str]:
        with self._launch.state.condition:
            record = self._started()
            return [line.text for line in record.lines if stream in ("any", line.stream)]

    # -- waits -----------------------------------------------------------------------------

    def wait_running(self, timeout: float = DEFAULT_TIMEOUT) -> int:
        """Wait until the process has started; its pid."""
        __tracebackhide__ = True

        def check() -> int | None:
            record = self._find()
            return record.pid if record is not None else None

        return self._launch.waits.until(f"process '{self.query}' to start", timeout, check)

    def wait_output(
        self, matcher: Matcher, timeout: float = DEFAULT_TIMEOUT, *, stream: str = "any"
    ) -> str:
        """Wait for a line, already written or to come, that ``matcher`` accepts: a ``str``
        (substring), a compiled ``re.Pattern`` (searched) or a callable; the line.

        ``stream`` is ``"any"``, ``"stdout"`` or ``"stderr"``.
        """
        __tracebackhide__ = True
        if stream not in STREAMS:
            raise ValueError(f"stream={stream!r}: expected one of {', '.join(STREAMS)}")
        accepts, words = compile_matcher(matcher)
        where = "" if stream == "any" else f" on {stream}"
        checked = 0

        def check() -> str | None:
            nonlocal checked
            record = self._find()
            if record is None:
                return None
            for line in record.lines[checked:]:
                if stream in ("any", line.stream) and accepts(line.text):
                    return line.text
            checked = len(record.lines)
            if not record.running and not record.respawn:
                raise Impossible(f"process {record.label} {process_status(record)}{where}")
            return None

        # a line it printed before dying still counts; a line it never printed is reported by
        # ``check`` as impossible once it has exited
        return self._launch.waits.until(
            f"{words} from process '{self.query}'{where}", timeout, check, subject=self.query
        )

    def wait_exit(self, timeout: float = DEFAULT_TIMEOUT) -> int:
        """Wait until the process exits; its exit code (negative: killed by that signal).

        This takes note of its exit: it is then neither named as a likely cause of later
        failures nor fails the test at teardown.
        """
        __tracebackhide__ = True

        def check() -> int | None:
            record = self._find()
            if record is None or record.running or record.returncode is None:
                return None
            record.noted = True
            return record.returncode

        return self._launch.waits.until(
            f"process '{self.query}' to exit", timeout, check, subject=self.query
        )
