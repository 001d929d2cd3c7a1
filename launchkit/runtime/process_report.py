"""What the launcher says about its processes: ROS's console lines, and the observers' events.

The wording is ``ros2 launch``'s (``process started with pid [N]``, ``process has died [...]``,
``failed to terminate ... escalating to 'SIGTERM'``), so users recognise it.
"""

from __future__ import annotations

from launchkit.runtime.hooks import SupervisorHooks
from launchkit.runtime.lifecycle import ExitOutcome, SendSignal
from launchkit.runtime.output import Output
from launchkit.runtime.process import SupervisedProcess, describe_exit


class ProcessReport:
    """Reports process events on ``output`` (screen and log) and to ``hooks``."""

    def __init__(self, output: Output, hooks: SupervisorHooks) -> None:
        self._output = output
        self._hooks = hooks

    def _line(self, level: str, process: SupervisedProcess, message: str) -> None:
        self._output.launch_line(level, process.label, message)

    def started(self, process: SupervisedProcess) -> None:
        """A new incarnation runs."""
        self._line("INFO", process, f"process started with pid [{process.pid}]")
        self._hooks.process_started(process)

    def could_not_start(self, process: SupervisedProcess, error: OSError) -> None:
        """Spawning failed (the launch then shuts down, unless the working folder is missing)."""
        spec = process.spec
        where = f" ({spec.location})" if spec.location else ""
        what = error.filename if error.filename is not None else spec.cmd[0]
        message = f"could not start process: {error.strerror}: '{what}'{where}"
        if spec.cwd and what == spec.cwd:
            message = f"could not start process: its working folder '{what}' does not exist{where}"
        self._line("ERROR", process, message)
        self._hooks.launch_error(f"{process.label}: {message}")

    def exited(self, process: SupervisedProcess, code: int, outcome: ExitOutcome) -> None:
        """The incarnation exited: cleanly, because we stopped it, or it died."""
        pid = process.pid
        if code == 0:
            self._line("INFO", process, f"process has finished cleanly [pid {pid}]")
        elif outcome.expected:
            self._line("INFO", process, f"process has finished [pid {pid}, {describe_exit(code)}]")
        else:
            cmd = process.spec.command_line()
            message = f"process has died [pid {pid}, {describe_exit(code)}, cmd '{cmd}']."
            self._line("ERROR", process, message)
        self._hooks.process_exited(process, code)

    def respawn(self, process: SupervisedProcess, outcome: ExitOutcome) -> None:
        """What the respawn policy decided after an exit, if it decided anything."""
        if outcome.respawn_in is not None:
            message = f"respawning in {outcome.respawn_in:g} s"
            if outcome.respawn_in > process.spec.respawn_delay:
                count = outcome.quick_exits
                message += f" (backing off: {count} exit{'s' * (count > 1)} soon after start)"
            self._line("INFO", process, message)
        elif outcome.gave_up_after is not None:
            self._line("WARNING", process, f"not respawning: {outcome.gave_up_after} retries used")

    def signal(self, process: SupervisedProcess, effect: SendSignal) -> None:
        """A signal is about to be sent (after an escalation, why)."""
        label = process.label
        if effect.escalated_from is not None:
            self._line(
                "ERROR",
                process,
                f"process[{label}] failed to terminate '{effect.waited:g}' seconds after "
                f"receiving '{effect.escalated_from.name}', escalating to '{effect.signum.name}'",
            )
        self._line("INFO", process, f"sending signal '{effect.signum.name}' to process[{label}]")
