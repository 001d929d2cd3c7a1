"""Shared paths for the test plugin's self-tests."""

from __future__ import annotations

from pathlib import Path

import pytest

LAUNCH_DIR = Path(__file__).parent / "launch"


@pytest.fixture
def launch_dir() -> Path:
    """The folder of the self-tests' launch files."""
    return LAUNCH_DIR
