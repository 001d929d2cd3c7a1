"""A process as the description says to run it, fully evaluated."""

from __future__ import annotations

import shlex
from dataclasses import dataclass, field

from launchkit.errors import Location

OUTPUT_MODES = ("log", "screen", "both", "own_log", "full")


@dataclass
class ProcessSpec:
    """Everything the supervisor needs to start, watch and stop one process."""

    name: str
    cmd: list[str]
    env: dict[str, str]
    cwd: str | None = None
    output: str = "log"
    emulate_tty: bool = False
    sigterm_timeout: float = 5.0
    sigkill_timeout: float = 5.0
    respawn: bool = False
    respawn_delay: float = 0.0
    respawn_max_retries: int = -1
    on_exit_shutdown: bool = False
    is_node: bool = False
    location: Location | None = None
    env_changes: dict[str, str | None] = field(default_factory=dict)
    files: dict[str, str] = field(default_factory=dict)
    machine: str = ""  # the agent (host) that runs it; "" for this host
    #: The action that started it (what event handlers' ``target_action`` names).
    origin: object | None = None

    def command_line(self) -> str:
        """The command as a shell would need it typed."""
        return shlex.join(self.cmd)
