"""The supervisor loop when one select() returns a process's exit before its last output.

Handling the exit drains and closes the process's streams; the output event that came back in
the same batch must then be skipped, not crash the launcher (seen once on a loaded machine)."""

from __future__ import annotations

import io
import selectors
import time
from pathlib import Path
from typing import Any

import pytest

from launchkit import api
from launchkit.runtime import supervisor


class ExitFirstSelector(selectors.DefaultSelector):  # type: ignore[misc,valid-type]
    """Lets events pile up, then hands every batch back in reverse order (exits first)."""

    def select(self, timeout: float | None = None) -> list[tuple[Any, int]]:
        time.sleep(0.05)
        return list(reversed(super().select(timeout)))


def test_output_event_after_the_exit_that_closed_its_stream(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(supervisor.selectors, "DefaultSelector", ExitFirstSelector)
    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path / "log"))
    path = tmp_path / "quick.launch.xml"
    path.write_text(
        "<launch>"
        + "".join(
            f'<executable name="quick{i}" output="screen" cmd="echo line {i}"/>' for i in range(20)
        )
        + "</launch>"
    )
    out = io.StringIO()
    assert api.run(path, stream=out) == 0
    text = out.getvalue()
    for i in range(20):
        assert f"[quick{i}-{i + 1}] line {i}" in text
