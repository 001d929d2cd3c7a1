"""Fixtures of the hostile-input tests."""

from __future__ import annotations

import pytest


@pytest.fixture(autouse=True)
def _private_log_root(
    tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Runs log below a temporary folder, never in the user's ``~/.launchkit/log``."""
    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path_factory.mktemp("ros_log")))
