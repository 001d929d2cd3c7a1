"""A Ctrl-C that reaches a launchkit node while it is still starting: held until it can take it.

Python turns SIGINT into ``KeyboardInterrupt`` from its first instant, so a Ctrl-C while a node
imports (a second or two of numpy, zenoh, the message types) printed a traceback from inside
``import``, or from ``runpy`` itself, and ended the node with status 1. So the launcher starts
the processes that run launchkit's own node modules (``python -m launchkit.stock...``, which
all end in :func:`launchkit.stock._entry.run`) with SIGINT *blocked*; a blocked signal waits,
it is not lost. The node's entry point releases it (:func:`release_sigint`) once its modules
are imported, inside the ``try`` that turns ``KeyboardInterrupt`` into a clean exit: a Ctrl-C
during the imports then ends the node the moment they are done, with status 0 and no output.
Any other program starts with SIGINT as the launcher got it (unblocked): only code launchkit
controls may be trusted to release it.
"""

from __future__ import annotations

import signal
import sys
from collections.abc import Iterator, Sequence
from contextlib import contextmanager

#: The modules of launchkit whose processes take SIGINT only once started.
_OWN_MODULES = ("launchkit.stock.", "launchkit.bridge")


def holds_sigint(cmd: Sequence[str]) -> bool:
    """Whether ``cmd`` runs one of launchkit's node modules with this interpreter (which
    releases SIGINT itself once imported)."""
    return (
        len(cmd) >= 3
        and cmd[0] == sys.executable
        and cmd[1] == "-m"
        and cmd[2].startswith(_OWN_MODULES)
    )


@contextmanager
def sigint_blocked(block: bool = True) -> Iterator[None]:
    """SIGINT blocked in the calling thread within the body (a process started in it inherits
    the block); one that arrives meanwhile is delivered when the body ends."""
    if not block:
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def release_sigint() -> None:
    """Unblock SIGINT in this process (a Ctrl-C held since the start is raised now)."""
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
