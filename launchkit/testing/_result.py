"""What a stopped launch leaves for the test to check: exit codes and output."""

from __future__ import annotations

from collections.abc import Collection, Mapping

from launchkit.runtime.process import describe_exit
from launchkit.testing._errors import ExitCodeMismatch
from launchkit.testing._state import LaunchState

ExpectedCodes = int | Collection[int]


def _describe(code: int | None) -> str:
    return "no exit reported" if code is None else describe_exit(code)


class LaunchResult:
    """A stopped launch: exit codes by process name, the launcher's status, every line.

    Reading :attr:`exit_codes` (or calling :meth:`assert_exit_codes`) takes note of every
    exit: a process that died unexpectedly then no longer fails the test at teardown.
    """

    def __init__(
        self,
        exit_codes: dict[str, int | None],
        returncode: int | None,
        output: dict[str, list[str]] | None = None,
        evidence: str = "",
    ) -> None:
        self._exit_codes = exit_codes
        self.returncode = returncode  # the launcher's own exit status
        self.output = output or {}  # every line of every process, by label
        self.evidence = evidence  # the processes and their last lines, for failure messages
        self.noted = False  # the test looked at the exit codes

    def __repr__(self) -> str:
        return f"LaunchResult(exit_codes={self._exit_codes!r}, returncode={self.returncode!r})"

    @property
    def exit_codes(self) -> dict[str, int | None]:
        """Exit codes by process name (by label where names repeat); None: still running."""
        self.noted = True
        return self._exit_codes

    @classmethod
    def of(cls, state: LaunchState, returncode: int | None, evidence: str) -> LaunchResult:
        """The result of a stopped launch (call with ``state.condition`` held). Exit codes are
        keyed by process name, or by label where several processes share a name."""
        records = list(state.processes.values())
        names = [record.name for record in records]
        exit_codes = {
            (record.name if names.count(record.name) == 1 else record.label): (
                None if record.running else record.returncode
            )
            for record in records
        }
        output = {record.label: [line.text for line in record.lines] for record in records}
        return cls(exit_codes, returncode, output, evidence)

    def assert_exit_codes(self, expected: Mapping[str, ExpectedCodes]) -> None:
        """Check exit codes: ``{"talker": 0, "sim": {0, -2}, "*": 0}``.

        Keys are process names (as in :attr:`exit_codes`); ``"*"`` covers every process not
        named. A value is one code or a collection of accepted codes; a negative code is the
        signal that killed the process (``-2``: SIGINT). Unknown names are an error.
        """
        __tracebackhide__ = True
        self.noted = True
        unknown = [name for name in expected if name != "*" and name not in self._exit_codes]
        if unknown:
            raise ExitCodeMismatch(
                f"assert_exit_codes names no process of the launch: {', '.join(unknown)} "
                f"(the processes are: {', '.join(self._exit_codes) or 'none'})"
            )
        wrong: list[str] = []
        for name, code in self._exit_codes.items():
            accepted = expected.get(name, expected.get("*"))
            if accepted is None:
                continue
            allowed = {accepted} if isinstance(accepted, int) else set(accepted)
            if code not in allowed:
                wanted = " or ".join(describe_exit(c) for c in sorted(allowed))
                wrong.append(f"{name}: {_describe(code)}, expected {wanted}")
        if wrong:
            raise ExitCodeMismatch(
                "unexpected exit codes:\n  " + "\n  ".join(wrong) + "\n" + self.evidence
            )
