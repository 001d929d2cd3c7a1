"""Helpers for the hostile-input tests: run the ``launchkit`` command line on a bad file and
check the promise of docs/reliability.md ("Bad input"): exit status 2, one located line, no
traceback, nothing left running."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import uuid
from pathlib import Path

CORPUS = Path(__file__).parent / "corpus"


def processes_with(token: str) -> list[int]:
    """The processes whose environment holds ``token`` (everything a run started inherits it)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            environ = (entry / "environ").read_bytes()
        except OSError:
            continue  # gone, or not ours to read
        if token.encode() in environ:
            found.append(int(entry.name))
    return found


def launchkit(
    *args: str | Path, cwd: Path | None = None, python: bool = False
) -> subprocess.CompletedProcess[str]:
    """Run the ``launchkit`` command line (``python``: the interpreter with ``args``, a stock
    node's module say) to completion, output captured; fail if anything it started is still
    running afterwards."""
    token = f"LAUNCHKIT_HOSTILE_TEST={uuid.uuid4().hex}"
    name, value = token.split("=")
    result = subprocess.run(
        [sys.executable, *([] if python else ["-m", "launchkit"]), *map(str, args)],
        cwd=cwd or CORPUS,
        capture_output=True,
        text=True,
        errors="replace",
        timeout=120,
        check=False,
        env={**os.environ, name: value},
    )
    assert processes_with(token) == [], f"left running after launchkit {args}"
    return result


def assert_located_error(
    result: subprocess.CompletedProcess[str], where: str, message: str
) -> None:
    """Exit status 2, no traceback, and stderr's first line is ``WHERE...: error: ...MESSAGE``
    (``where`` and ``message`` are regular expressions)."""
    output = result.stdout + result.stderr
    assert "Traceback" not in output, output
    assert result.returncode == 2, output
    first = result.stderr.splitlines()[0]
    assert re.match(rf"^(\S+: )?\S*{where}\S*: error: .*{message}", first), first
