"""launchkit's public surface: what ``import launchkit`` offers, pinned."""

from __future__ import annotations

import subprocess
import sys

import pytest

import launchkit
from launchkit import errors

PUBLIC = [
    "CheckedTree",
    "LaunchArgumentError",
    "LaunchFileError",
    "LaunchkitError",
    "Location",
    "PackageIndex",
    "PackageNotFoundError",
    "RuntimeLaunchError",
    "SupervisorHooks",
    "UserError",
    "__version__",
    "check",
    "describe",
    "resolve_launch_file",
    "run",
    "show_arguments",
]


def test_all_is_the_public_surface() -> None:
    assert launchkit.__all__ == PUBLIC
    for name in PUBLIC:
        assert getattr(launchkit, name) is not None, name
    assert set(PUBLIC) <= set(dir(launchkit))


def test_the_whole_error_tree_is_exported() -> None:
    tree = {
        name
        for name, value in vars(errors).items()
        if isinstance(value, type) and issubclass(value, errors.LaunchkitError)
    }
    assert tree <= set(launchkit.__all__)
    assert launchkit.UserError is errors.UserError


def test_unknown_names_are_attribute_errors() -> None:
    with pytest.raises(AttributeError, match="not_a_thing"):
        launchkit.not_a_thing  # type: ignore[attr-defined]  # noqa: B018


def test_importing_launchkit_does_not_load_the_launch_engine() -> None:
    # Every node process imports launchkit (through launchkit.ros); the engine loads on use.
    code = (
        "import sys, launchkit, launchkit.errors; "
        "print(sorted(m for m in ('launchkit.api', 'launchkit.frontend', 'lxml') "
        "if m in sys.modules))"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=60
    )
    assert result.stdout.strip() == "[]"
