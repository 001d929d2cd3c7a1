"""docs/api.md: its example runs as written and prints what the page says; ``launchkit.run()``
off the main thread refuses before it creates anything."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import threading
from pathlib import Path

import pytest

import launchkit

ROOT = Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "api.md"


def example() -> str:
    """The first Python block under the page's "Example" heading."""
    text = PAGE.read_text().split("## Example", 1)[1]
    match = re.search(r"```python\n(.*?)```", text, re.DOTALL)
    assert match is not None, "docs/api.md has no Python block under its Example heading"
    return match.group(1)


def test_the_example_runs_as_the_page_says(tmp_path: Path) -> None:
    script = tmp_path / "example.py"
    script.write_text(example())
    logs = tmp_path / "logs"
    result = subprocess.run(
        [sys.executable, str(script)],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=tmp_path,
        env={**os.environ, "ROS_LOG_DIR": str(logs)},
    )
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "1 file(s) checked\n" in out
    assert "process talker  (" in out and "env: LAUNCHKIT_HELLO=Salut" in out
    assert "hello.launch.xml:7:3: error: argument 'verbose' got 'maybe' (expected one of " in out
    assert "'true', 'false') -> 2\n" in out
    lines = out.splitlines()
    said = [line for line in lines if line.startswith("[talker-1] Salut number")]
    assert said == ["[talker-1] Salut number 1", "[talker-1] Salut number 2"], out
    assert out.endswith("exit status 0\n")
    assert (logs / "latest" / "launch.log").is_file()  # the run's logs went where it was told


def test_run_off_the_main_thread_refuses_before_it_creates_anything(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    logs = tmp_path / "logs"
    monkeypatch.setenv("ROS_LOG_DIR", str(logs))
    marker = tmp_path / "started"
    path = tmp_path / "a.launch.xml"
    path.write_text(f'<launch><executable cmd="touch {marker}"/></launch>')
    raised: list[BaseException] = []

    def worker() -> None:
        try:
            launchkit.run(path)
        except BaseException as error:  # whatever it is, the test reports it
            raised.append(error)

    thread = threading.Thread(target=worker)
    thread.start()
    thread.join(60)
    assert not thread.is_alive()
    assert len(raised) == 1 and isinstance(raised[0], launchkit.UserError), raised
    assert raised[0].format() == (
        "error: launchkit.run() was called from a thread other than the main thread (expected "
        "a call from the main thread, which alone receives signals (Ctrl-C))\n"
        "  hint: to launch from a worker thread, start `launchkit run FILE` as a subprocess"
    )
    assert not logs.exists() and not marker.exists()
