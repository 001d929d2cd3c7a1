"""``.ci/run`` finds a real Python 3.12 for its second run of the suite, or says why not."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
FUNCTIONS = 'source <(sed -n "/^find_python312()/,/^}/p;/^require_python312()/,/^}/p" .ci/run)'
SYSTEM = [Path("/usr/bin/python3.12"), Path("/usr/local/bin/python3.12")]


def _call(function: str, tmp_path: Path, path: str) -> subprocess.CompletedProcess[str]:
    env = {"PATH": path, "HOME": str(tmp_path / "home")}
    return subprocess.run(
        ["/bin/bash", "-c", f"{FUNCTIONS}; {function}"],
        cwd=REPO,
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )


def test_a_python312_that_is_not_one_is_passed_over(tmp_path: Path) -> None:
    if sys.version_info[:2] == (3, 12):
        pytest.skip("the impostor is this test's own Python, which here is a 3.12")
    impostor = tmp_path / "bin" / "python3.12"  # a pyenv shim or a stale link, say
    impostor.parent.mkdir()
    impostor.write_text(f'#!/bin/sh\nexec {sys.executable} "$@"\n')
    impostor.chmod(0o755)
    found = _call("find_python312", tmp_path, f"{impostor.parent}:/usr/bin:/bin")
    assert str(impostor) not in found.stdout


def test_without_a_python312_it_says_where_it_looked(tmp_path: Path) -> None:
    if any(path.exists() for path in SYSTEM):
        pytest.skip("this machine has a system Python 3.12, which would be found")
    found = _call("require_python312", tmp_path, "/usr/bin:/bin")  # an empty home: no pyenv
    assert found.returncode == 1 and found.stdout == ""
    assert found.stderr.startswith(".ci/run: no Python 3.12 found (looked at $PYTHON312")


def test_pyenvs_python312_is_found(tmp_path: Path) -> None:
    real = sorted((Path.home() / ".pyenv" / "versions").glob("3.12*/bin/python3.12"))
    if not real or any(path.exists() for path in SYSTEM):
        pytest.skip("needs a pyenv Python 3.12 and none in /usr/bin or /usr/local/bin")
    versions = tmp_path / "home" / ".pyenv" / "versions" / "3.12.0" / "bin"
    versions.mkdir(parents=True)
    (versions / "python3.12").symlink_to(real[0])
    found = _call("require_python312", tmp_path, "/usr/bin:/bin")
    assert found.returncode == 0 and found.stdout.strip() == str(versions / "python3.12")
