"""What a launch needs of launching on other hosts, loaded only when it has a remote process:
the supervisor's factory for processes with a ``machine`` (:mod:`launchkit.remote.hosts`)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from launchkit.envvars import AGENT_TIMEOUT, REMOTE_GRACE
from launchkit.errors import UserError

if TYPE_CHECKING:
    from launchkit.description.launch_context import Runner
    from launchkit.description.process_spec import ProcessSpec
    from launchkit.remote.hosts import RemoteHosts
    from launchkit.runtime.network import NodeNetwork

DEFAULT_GRACE = 10.0
DEFAULT_AGENT_TIMEOUT = 30.0


def seconds(value: str | None, name: str, default: float) -> float:
    """``value`` (or ``$name``) as seconds >= 0, else ``default``; a user error if not one."""
    text = value if value is not None else os.environ.get(name, "")
    try:
        number = float(text) if text else default
    except ValueError:
        number = -1.0
    if not number >= 0:
        raise UserError(f"{name}={text!r}", expected="a number of seconds >= 0")
    return number


class RemoteLaunch:
    """The launch's remote processes, their session made on the first one."""

    def __init__(
        self, network: NodeNetwork, key: str | None = None, grace: str | None = None
    ) -> None:
        self.network = network
        self.key_path = Path(key).expanduser() if key else None
        self.grace = seconds(grace, REMOTE_GRACE, DEFAULT_GRACE)
        self.agent_timeout = seconds(None, AGENT_TIMEOUT, DEFAULT_AGENT_TIMEOUT)
        self._runner: Runner | None = None
        self._hosts: RemoteHosts | None = None

    def bind(self, runner: Runner) -> None:
        """The runner whose log lines and router the remote processes use."""
        self._runner = runner

    def factory(self, spec: ProcessSpec, label: str, index: int) -> Any:
        """The supervisor's factory for a process with a ``machine``."""
        if self._hosts is None:
            from launchkit.remote.hosts import RemoteHosts

            self._hosts = RemoteHosts(self.network, self.key_path, self.grace, self.agent_timeout)
            assert self._runner is not None
            self._hosts.bind(self._runner)
        return self._hosts.factory(spec, label, index)

    def close(self) -> None:
        """Leave the graph, if the launch ever joined it for remote processes."""
        if self._hosts is not None:
            self._hosts.close()
            self._hosts = None
