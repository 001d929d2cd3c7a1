"""Who listens on a local TCP port, read from the kernel's socket tables (Linux ``/proc``).

A router port on a shared machine may be held by another user's process; joining it would
hand that user every topic and service. ``/proc/net/tcp`` and ``tcp6`` list every socket of
this network namespace with its owner's uid and inode, whoever owns it; the processes holding
an inode are found through ``/proc/PID/fd`` (only those we may read). Elsewhere (no ``/proc``)
nothing is known and :func:`find_listener` returns None.
"""

from __future__ import annotations

import ipaddress
import os
import pwd
from dataclasses import dataclass
from pathlib import Path

_PROC = Path("/proc")
_LISTEN = "0A"
_ESTABLISHED = "01"


@dataclass(frozen=True)
class Listener:
    """A listening TCP socket: its owner's ``uid``, its ``inode`` and local ``address``."""

    uid: int
    inode: int
    address: str
    port: int

    @property
    def user(self) -> str:
        """The owner's user name (the uid as text when it has none)."""
        return user_name(self.uid)


def user_name(uid: int) -> str:
    """The name of ``uid``, or the number as text."""
    try:
        return pwd.getpwuid(uid).pw_name
    except KeyError:
        return str(uid)


def _decode_address(hex_address: str) -> tuple[ipaddress.IPv4Address | ipaddress.IPv6Address, int]:
    """``0100007F:1D27`` (or its 32-digit IPv6 form) as (address, port); the kernel writes
    each 32-bit word in host (little-endian) order."""
    hex_ip, hex_port = hex_address.split(":")
    raw = bytes.fromhex(hex_ip)
    words = b"".join(raw[i : i + 4][::-1] for i in range(0, len(raw), 4))
    address = ipaddress.ip_address(words)
    return address, int(hex_port, 16)


def _rows(state: str) -> list[tuple[ipaddress.IPv4Address | ipaddress.IPv6Address, int, int, int]]:
    """(address, port, uid, inode) of every socket in ``state`` of this network namespace."""
    rows = []
    for table in ("tcp", "tcp6"):
        try:
            lines = (_PROC / "net" / table).read_text().splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            fields = line.split()
            if len(fields) < 10 or fields[3] != state:
                continue
            address, port = _decode_address(fields[1])
            rows.append((address, port, int(fields[7]), int(fields[9])))
    return rows


def _matches(bound: ipaddress.IPv4Address | ipaddress.IPv6Address, wanted: set[str]) -> bool:
    if bound.is_unspecified:
        return True  # 0.0.0.0 or :: accept connections to any local address
    if isinstance(bound, ipaddress.IPv6Address) and bound.ipv4_mapped is not None:
        bound = bound.ipv4_mapped
    return str(bound) in wanted


def _addresses(host: str) -> set[str]:
    """The numeric addresses ``host`` stands for (names other than localhost: none)."""
    if host == "localhost":
        return {"127.0.0.1", "::1"}
    try:
        return {str(ipaddress.ip_address(host))}
    except ValueError:
        return set()


def proc_available() -> bool:
    """Whether the kernel's socket tables can be read here (Linux)."""
    return (_PROC / "net" / "tcp").exists()


def find_listener(host: str, port: int) -> Listener | None:
    """The socket listening for connections to ``host:port`` on this machine, if any."""
    wanted = _addresses(host)
    if not wanted:
        return None
    for address, bound_port, uid, inode in _rows(_LISTEN):
        if bound_port == port and _matches(address, wanted):
            return Listener(uid, inode, str(address), port)
    return None


def connections_to(port: int) -> int:
    """How many established TCP connections this machine accepted on ``port`` (a router's
    sessions: each session holds one connection to it)."""
    return sum(
        1 for _address, local_port, _uid, _inode in _rows(_ESTABLISHED) if local_port == port
    )


def pids_holding(inode: int) -> list[int]:
    """The processes (that we may inspect) holding the socket ``inode``."""
    target = f"socket:[{inode}]"
    found = []
    for entry in _PROC.iterdir():
        if not entry.name.isdigit():
            continue
        try:
            for fd in (entry / "fd").iterdir():
                if os.readlink(fd) == target:
                    found.append(int(entry.name))
                    break
        except OSError:
            continue
    return sorted(found)


def command_line(pid: int, limit: int = 200) -> str:
    """The command line of ``pid`` as one printable line of at most ``limit`` characters (""
    when it cannot be read)."""
    try:
        raw = (_PROC / str(pid) / "cmdline").read_bytes()
    except OSError:
        return ""
    text = " ".join(part.decode(errors="replace") for part in raw.split(b"\0") if part)
    text = " ".join(text.split())  # newlines and tabs of a `python -c` script, say
    return text if len(text) <= limit else text[: limit - 3] + "..."
