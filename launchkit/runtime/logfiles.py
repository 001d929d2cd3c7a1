"""The log files of one run, bounded: each file rotated at a size, the whole run capped.

A file that reaches ``file_bytes`` is renamed ``NAME.1`` (replacing an older ``NAME.1``) and
started again, so a file never takes more than twice that on disk and the latest output is kept.
Once the run folder holds ``run_bytes``, child output is no longer logged (one line in
``launch.log`` says so); the launcher's own lines still are.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import BinaryIO

from launchkit.runtime.logdir import LogLimits


class _LogFile:
    """One rotating log file."""

    def __init__(self, path: Path, limit: int) -> None:
        self.path = path
        self.limit = limit
        self.size = 0
        self.rotated_size = 0  # what NAME.1 holds
        self._handle: BinaryIO = open(path, "ab")
        self.size = self._handle.tell()

    def write(self, data: bytes) -> int:
        """Append ``data``; how many bytes the run folder grew by (negative after a rotation
        that dropped an older ``NAME.1``)."""
        growth = len(data)
        if self.limit and self.size and self.size + len(data) > self.limit:
            self._handle.close()
            os.replace(self.path, self.path.with_name(self.path.name + ".1"))
            growth -= self.rotated_size
            self.rotated_size, self.size = self.size, 0
            self._handle = open(self.path, "ab")
        self._handle.write(data)
        self.size += len(data)
        return growth

    def flush(self) -> None:
        """Push buffered lines to the file."""
        self._handle.flush()

    def close(self) -> None:
        """Flush and close."""
        self._handle.close()


class RunLogs:
    """``launch.log`` and the per-process ``own_log`` files of a run folder."""

    def __init__(self, run_dir: Path, limits: LogLimits) -> None:
        self.run_dir = run_dir
        self.limits = limits
        self.total = 0
        self.capped = False
        self._files: dict[str, _LogFile] = {}

    def write(self, name: str, lines: list[str], *, child: bool) -> None:
        """Append ``lines`` to the file ``name`` (``launch.log`` or ``LABEL-STREAM.log``);
        ``child``: the lines are a child's output, which the run's cap may refuse."""
        if not lines:
            return
        data = "".join(line + "\n" for line in lines).encode("utf-8", errors="replace")
        if child and self._over_cap(len(data)):
            return
        file = self._files.get(name)
        if file is None:
            file = self._files[name] = _LogFile(self.run_dir / name, self.limits.file_bytes)
        self.total += file.write(data)
        file.flush()

    def _over_cap(self, size: int) -> bool:
        limit = self.limits.run_bytes
        if self.capped:
            return True
        if not limit or self.total + size <= limit:
            return False
        self.capped = True
        megabytes = limit / (1024 * 1024)
        self.write(
            "launch.log",
            [
                f"[WARNING] [launch]: this run's logs reached {megabytes:g} MB "
                "(LAUNCHKIT_LOG_RUN_MB): child output is no longer logged"
            ],
            child=False,
        )
        return True

    def close(self) -> None:
        """Close every file."""
        for file in self._files.values():
            file.close()
        self._files.clear()
