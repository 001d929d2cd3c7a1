"""Keep C libraries' stdout chatter out of a process's output.

PyBullet's EGL renderer plugin prints about nine lines when it loads and one line
(``ven = ...``) on every rendered frame, from C, to file descriptor 1.
"""

from __future__ import annotations

import os
import sys


def silence_c_stdout() -> None:
    """Point file descriptor 1 at /dev/null; Python's ``sys.stdout`` keeps the original."""
    sys.stdout.flush()
    original = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.close(devnull)
    sys.stdout = os.fdopen(original, "w", buffering=1)
