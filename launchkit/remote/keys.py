"""The agent key: a secret shared by an agent and the launchers allowed to use it.

An agent runs whatever a request names, as its user; anyone who can reach its router (every
local user can reach a loopback port) could otherwise ask. So every request and event is
sealed with an HMAC of this key (:mod:`launchkit.remote.protocol`). ``launchkit agent`` makes
the key file on first use (``$XDG_CONFIG_HOME/launchkit/agent.key``, mode 0600); copy it to
the machines that launch on it, as one copies an ssh key.
"""

from __future__ import annotations

import os
import secrets
import stat
from pathlib import Path

from launchkit.envvars import AGENT_KEY
from launchkit.errors import UserError


class AgentKeyError(UserError):
    """The agent key is missing or unsafe."""


def default_key_path() -> Path:
    """``$LAUNCHKIT_AGENT_KEY``, else ``$XDG_CONFIG_HOME/launchkit/agent.key`` (~/.config)."""
    given = os.environ.get(AGENT_KEY)
    if given:
        return Path(given).expanduser()
    config = os.environ.get("XDG_CONFIG_HOME") or str(Path.home() / ".config")
    return Path(config) / "launchkit" / "agent.key"


def load_key(path: Path | None = None, *, create: bool = False) -> bytes:
    """The key in ``path`` (default :func:`default_key_path`); made first when ``create``."""
    path = path or default_key_path()
    if create and not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        descriptor = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(descriptor, "w") as stream:
            stream.write(secrets.token_hex(32) + "\n")
    try:
        info = path.stat()
        text = path.read_text().strip()
    except OSError as error:
        raise AgentKeyError(
            f"no agent key at {path} ({error.strerror})",
            expected=f"the key file of the agent's machine copied there, or ${AGENT_KEY}",
            hint="`launchkit agent` makes one on first start (docs/multi-host.md)",
        ) from None
    if info.st_mode & (stat.S_IRWXG | stat.S_IRWXO):
        raise AgentKeyError(
            f"agent key {path} is readable by others", expected="mode 0600 (chmod 600)"
        )
    if len(text) < 32:
        raise AgentKeyError(f"agent key {path} is too short", expected="32 bytes or more")
    return text.encode()
