"""What a participant tells the time authority, and where on the transport it goes."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

#: Zenoh keys of a domain's lockstep traffic (outside the ROS key space: no ROS tool sees it).
REPORT_KEY = "launchkit_lockstep/{domain}/report/{participant}"
REPORTS = "launchkit_lockstep/{domain}/report/*"
WAKE_KEY = "launchkit_lockstep/{domain}/wake/{participant}"
CONTROL_KEY = "launchkit_lockstep/{domain}/control"
STATUS_KEY = "launchkit_lockstep/{domain}/status"

#: A publisher's sequence numbers (its GID in hex -> (topic, last sequence number sent)).
Sent = dict[str, tuple[str, int]]
#: A publisher's GID in hex -> the GIDs of the subscriptions to its topic it has discovered.
Matched = dict[str, list[str]]
#: A subscription's GID in hex -> (topic, publisher GID in hex -> last sequence number handled).
Handled = dict[str, tuple[str, dict[str, int]]]


@dataclass
class Report:
    """One participant's state when it last went idle (or left).

    ``time_ns`` is the simulated time it has reached; ``idle`` says that nothing due up to it
    is left to do (no queued message, request or timer, no service call awaiting its reply);
    ``next_ns`` is when its next timer (or clock sleep) is due. ``sent`` and ``handled`` count
    messages per publisher and per subscription, so the authority can tell whether a message
    is still on its way; ``matched`` says which subscriptions each publisher has discovered
    (a message reaches a subscription only once its publisher's side knows of it).
    """

    participant: str
    pids: tuple[int, ...]
    name: str
    time_ns: int
    idle: bool
    next_ns: int | None = None
    sent: Sent = field(default_factory=dict)
    handled: Handled = field(default_factory=dict)
    matched: Matched = field(default_factory=dict)
    leaving: bool = False

    def to_bytes(self) -> bytes:
        """The JSON form sent on the transport."""
        return json.dumps(
            {
                "participant": self.participant,
                "pids": list(self.pids),
                "name": self.name,
                "time_ns": self.time_ns,
                "idle": self.idle,
                "next_ns": self.next_ns,
                "sent": {gid: list(entry) for gid, entry in self.sent.items()},
                "handled": {gid: [t, seqs] for gid, (t, seqs) in self.handled.items()},
                "matched": self.matched,
                "leaving": self.leaving,
            }
        ).encode()

    @classmethod
    def from_bytes(cls, data: bytes) -> Report:
        """Parse :meth:`to_bytes`'s form (``ValueError`` if it is not one)."""
        raw: Any = json.loads(data)
        try:
            return cls(
                participant=str(raw["participant"]),
                pids=tuple(int(p) for p in raw["pids"]),
                name=str(raw["name"]),
                time_ns=int(raw["time_ns"]),
                idle=bool(raw["idle"]),
                next_ns=None if raw["next_ns"] is None else int(raw["next_ns"]),
                sent={gid: (str(t), int(s)) for gid, (t, s) in raw["sent"].items()},
                handled={
                    gid: (str(t), {p: int(s) for p, s in seqs.items()})
                    for gid, (t, seqs) in raw["handled"].items()
                },
                matched={gid: [str(s) for s in subs] for gid, subs in raw["matched"].items()},
                leaving=bool(raw["leaving"]),
            )
        except (KeyError, TypeError, AttributeError) as error:
            raise ValueError(f"not a lockstep report: {error}") from None

    def same_state(self, other: Report | None) -> bool:
        """Whether ``other`` says the same (a participant does not repeat itself)."""
        return self == other
