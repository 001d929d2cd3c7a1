"""Linux ``prctl`` settings a process makes about its own life, through ``ctypes``.

Elsewhere (no Linux, no libc to load) each function does nothing and says so by returning
False: callers then rely on what they do without it.
"""

from __future__ import annotations

import ctypes
import sys

PR_SET_PDEATHSIG = 1
PR_SET_CHILD_SUBREAPER = 36


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
