"""A process as the description says to run it, fully evaluated."""

from __future__ import annotations

from launchkit._record import Record
from launchkit.errors import Location

OUTPUT_MODES = ("log", "screen", "both", "own_log", "full")


class ProcessSpec(Record):
    """Everything the supervisor needs to start, watch and stop one process."""

    __slots__ = (
        "cmd",
        "cwd",
        "emulate_tty",
        "env",
        "env_changes",
        "files",
        "is_node",
        "location",
        "machine",
        "name",
        "on_exit_shutdown",
        "origin",
        "output",
        "respawn",
        "respawn_delay",
        "respawn_max_retries",
        "sigkill_timeout",
        "sigterm_timeout",
    )
    name: str
    cmd: list[str]
    env: dict[str, str]
    cwd: str | None
    output: str
    emulate_tty: bool
    sigterm_timeout: float
    sigkill_timeout: float
    respawn: bool
    respawn_delay: float
    respawn_max_retries: int
    on_exit_shutdown: bool
    is_node: bool
    location: Location | None
    env_changes: dict[str, str | None]
    files: dict[str, str]
    machine: str  # the agent (host) that runs it; "" for this host
    #: The action that started it (what event handlers' ``target_action`` names).
    origin: object | None

    def __init__(
        self,
        name: str,
        cmd: list[str],
        env: dict[str, str],
        cwd: str | None = None,
        output: str = "log",
        emulate_tty: bool = False,
        sigterm_timeout: float = 5.0,
        sigkill_timeout: float = 5.0,
        respawn: bool = False,
        respawn_delay: float = 0.0,
        respawn_max_retries: int = -1,
        on_exit_shutdown: bool = False,
        is_node: bool = False,
        location: Location | None = None,
        env_changes: dict[str, str | None] | None = None,
        files: dict[str, str] | None = None,
        machine: str = "",
        origin: object | None = None,
    ) -> None:
        self.name = name
        self.cmd = cmd
        self.env = env
        self.cwd = cwd
        self.output = output
        self.emulate_tty = emulate_tty
        self.sigterm_timeout = sigterm_timeout
        self.sigkill_timeout = sigkill_timeout
        self.respawn = respawn
        self.respawn_delay = respawn_delay
        self.respawn_max_retries = respawn_max_retries
        self.on_exit_shutdown = on_exit_shutdown
        self.is_node = is_node
        self.location = location
        self.env_changes = {} if env_changes is None else env_changes
        self.files = {} if files is None else files
        self.machine = machine
        self.origin = origin

    def command_line(self) -> str:
        """The command as a shell would need it typed."""
        import shlex  # only for --print and messages

        return shlex.join(self.cmd)
