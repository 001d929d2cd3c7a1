"""The evidence a failure shows: which processes exist, their state and their last lines."""

from __future__ import annotations

import shlex
from pathlib import Path

from launchkit.runtime.process import describe_exit
from launchkit.testing._state import LaunchState, ProcessRecord

TAIL_LINES = 20


def process_status(record: ProcessRecord) -> str:
    """``running [pid 42]``, ``exited with exit code 3 [pid 42]``, ``killed by signal ...``."""
    pid = f"[pid {record.pid}]"
    if record.running:
        return f"running {pid}"
    if record.returncode is None:
        return f"gone, exit not reported {pid}"
    if record.returncode < 0:
        return f"killed by {describe_exit(record.returncode)} {pid}"
    return f"exited with {describe_exit(record.returncode)} {pid}"


def process_title(record: ProcessRecord) -> str:
    """``talker-1 (talker, node chatter)``: the label and the names a test may use."""
    names = [record.name] + ([f"node {record.node}"] if record.node else [])
    return f"{record.label} ({', '.join(names)})"


def tail(lines: list[str], count: int = TAIL_LINES) -> list[str]:
    """The last ``count`` lines, with a note of how many came before."""
    if len(lines) <= count:
        return list(lines)
    return [f"... {len(lines) - count} earlier lines ...", *lines[-count:]]


def launcher_lines(log: Path) -> list[str]:
    """What the launcher printed (its own lines, and any traceback)."""
    try:
        return log.read_text(errors="replace").splitlines()
    except OSError:
        return []


def describe_launch(state: LaunchState, launcher_log: Path, count: int = TAIL_LINES) -> str:
    """Every process of the launch with its status and last ``count`` lines, then the
    launcher's own last lines. Call with ``state.condition`` held."""
    parts: list[str] = []
    if not state.processes:
        parts.append("no process of the launch has started")
    else:
        parts.append("processes of the launch:")
    for record in state.processes.values():
        parts.append(f"  {process_title(record)}: {process_status(record)}")
        parts.append(f"    cmd: {shlex.join(record.cmd)}")
        lines = [line.text for line in record.lines]
        if not lines:
            parts.append("    (no output)")
        else:
            parts.append(f"    last lines of output ({len(lines)} in all):")
            parts.extend(f"    | {line}" for line in tail(lines, count))
    if state.launcher_returncode is not None:
        launcher = f"exited with {describe_exit(state.launcher_returncode)}"
    else:
        launcher = "running"
    parts.append(f"  launcher: {launcher}; log {launcher_log}")
    parts.extend(f"    | {line}" for line in tail(launcher_lines(launcher_log), count))
    return "\n".join(parts)


def report_sections(
    title: str, state: LaunchState, launcher_log: Path, notes: list[str], count: int
) -> list[tuple[str, str]]:
    """(title, text) per process and for the launcher, for a failing test's report: status,
    command line and up to ``count`` lines each. Call with ``state.condition`` held."""
    sections: list[tuple[str, str]] = []
    for record in state.processes.values():
        lines = [f"{process_status(record)}; cmd: {' '.join(record.cmd)}"]
        lines += tail([f"[{line.stream}] {line.text}" for line in record.lines], count)
        sections.append((f"{title}: {record.label}", "\n".join(lines)))
    printed = tail(launcher_lines(launcher_log), count)
    sections.append((f"{title}: launcher", "\n".join(notes + printed)))
    return sections
