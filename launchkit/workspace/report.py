"""What ``launchkit build`` prints, in colcon's shapes: ``Starting >>> PKG``,
``Finished <<< PKG [1.2s]``, ``Failed   <<< PKG`` with the reasons under it,
``Skipped  --- PKG: why``, then ``Summary: N packages finished [T s]`` with the failed and
skipped packages listed."""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from typing import TextIO

from launchkit.errors import printable

FINISHED, FAILED, SKIPPED = "finished", "failed", "skipped"


@dataclass(frozen=True)
class Result:
    """How one package's build ended; ``details`` are the lines shown under a failure."""

    name: str
    state: str
    seconds: float = 0.0
    reason: str = ""
    details: tuple[str, ...] = field(default=())


class Report:
    """Prints the build's progress and its summary to ``stream`` (stdout by default)."""

    def __init__(self, stream: TextIO | None = None) -> None:
        self.stream = stream if stream is not None else sys.stdout

    def _line(self, text: str) -> None:
        print(printable(text), file=self.stream, flush=True)

    def note(self, text: str) -> None:
        """A line about the build as a whole."""
        self._line(text)

    def started(self, name: str) -> None:
        """A package's build began."""
        self._line(f"Starting >>> {name}")

    def ended(self, result: Result) -> None:
        """A package's build ended, or it was decided against."""
        if result.state == FINISHED:
            self._line(f"Finished <<< {result.name} [{result.seconds:.2f}s]")
        elif result.state == SKIPPED:
            self._line(f"Skipped  --- {result.name}: {result.reason}")
        else:
            timing = f" [{result.seconds:.2f}s]" if result.seconds else ""
            self._line(f"Failed   <<< {result.name}{timing}: {result.reason}")
            for detail in result.details:
                for line in detail.splitlines():
                    self._line(f"  {line}")

    def summary(self, results: list[Result], seconds: float) -> None:
        """The closing lines: how many finished, which failed, which were skipped."""
        finished = [r.name for r in results if r.state == FINISHED]
        self._line("")
        self._line(f"Summary: {_count(len(finished))} finished [{seconds:.2f}s]")
        for state in (FAILED, SKIPPED):
            names = [r.name for r in results if r.state == state]
            if names:
                self._line(f"  {_count(len(names))} {state}: {', '.join(names)}")


def _count(number: int) -> str:
    return f"{number} package" + ("" if number == 1 else "s")
