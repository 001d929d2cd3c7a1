"""What a launchkit process settles about its own life: Linux ``prctl`` settings through
``ctypes`` (die with the parent, be the subreaper of orphaned descendants), and the helper
processes it runs for itself (which the launch's containment must not take for strays).

Elsewhere (no Linux, no libc to load) each prctl function does nothing and says so by
returning False: callers then rely on what they do without it.
"""

from __future__ import annotations

import contextlib
import ctypes
import sys
from collections.abc import Iterator

PR_SET_PDEATHSIG = 1
PR_SET_CHILD_SUBREAPER = 36

#: Children a launcher runs for itself (the orphan guard, the ``$(eval)`` evaluator): never
#: strays of its launch.
own_helpers: set[int] = set()

_subreaper = False


def set_prctl(option: int, value: int) -> bool:
    """``prctl(option, value)``; whether it succeeded."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return int(libc.prctl(option, value, 0, 0, 0)) == 0
    except (OSError, AttributeError):
        return False


def die_with_parent(signum: int) -> bool:
    """Have the kernel send this process ``signum`` when the thread that started it exits.
    The caller must then check that its parent is still the one it expects (it may have
    died before this call)."""
    return set_prctl(PR_SET_PDEATHSIG, signum)


def become_subreaper() -> bool:
    """Make this process the one its orphaned descendants are re-parented to (instead of
    init), so that it can find and reap them."""
    global _subreaper
    _subreaper = set_prctl(PR_SET_CHILD_SUBREAPER, 1)
    return _subreaper


def is_subreaper() -> bool:
    """Whether :func:`become_subreaper` made this process one."""
    return _subreaper


@contextlib.contextmanager
def not_subreaper() -> Iterator[None]:
    """Within the body, orphans go to init, not to this process (for a daemon it starts on
    purpose, such as the shared router)."""
    if not is_subreaper():
        yield
        return
    set_prctl(PR_SET_CHILD_SUBREAPER, 0)
    try:
        yield
    finally:
        set_prctl(PR_SET_CHILD_SUBREAPER, 1)
