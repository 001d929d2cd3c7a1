"""What processes of a launch announce for the user (the viewer's address, say), printed as the
last line of the bring-up: held until the launch's console has been quiet for a moment, then
written bold on a terminal, so it is not lost among the nodes' start-up messages."""

from __future__ import annotations

from launchkit.runtime.output import Output

#: Seconds without a console line after which the launch counts as up.
SETTLE = 1.5
#: Seconds after an announcement at which it is printed anyway (a node that logs all the time).
LATEST = 10.0


class Announcements:
    """Announcements waiting for the console to settle (times on the supervisor's clock)."""

    def __init__(self, output: Output) -> None:
        self._output = output
        self._held: list[tuple[float, str, str]] = []  # (when announced, logger, text)
        self._lines_seen = output.screen_writes
        self._quiet_since = 0.0

    def hold(self, logger: str, text: str, now: float) -> None:
        """Print ``text`` under ``logger`` once the console has settled."""
        self._held.append((now, logger, text))
        self._quiet_since = now

    def deadline(self) -> float | None:
        """When the held announcements are due if nothing is printed meanwhile; None if none."""
        if not self._held:
            return None
        return min(self._quiet_since + SETTLE, self._held[0][0] + LATEST)

    def print_due(self, now: float, shutting_down: bool) -> None:
        """Note whether the console moved since the last call; print what is held once it has
        been quiet for :data:`SETTLE` seconds (or :data:`LATEST` passed). A launch shutting
        down drops them: the address of a viewer being stopped helps nobody."""
        if self._output.screen_writes != self._lines_seen:
            self._lines_seen = self._output.screen_writes
            self._quiet_since = now
        deadline = self.deadline()
        if deadline is None or (now < deadline and not shutting_down):
            return
        if not shutting_down:
            for _, logger, text in self._held:
                self._output.launch_line("INFO", logger, text, bold=True)
            self._lines_seen = self._output.screen_writes
        self._held.clear()
