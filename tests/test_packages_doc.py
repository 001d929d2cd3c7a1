"""docs/packages.md, built and run from its own text: the worked example package is written
out file by file, built and installed with pip into a folder of its own (``--target``, put on
``PYTHONPATH``: the test's environment stays as it was), found by launchkit through its entry
point, and its process test passes; the hand-made ROS layout works as shown."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

DOC = Path(__file__).resolve().parents[1] / "docs" / "packages.md"
# "`my_talker/pyproject.toml`:", a blank line, then the fenced block holding the file
FILE_BLOCK = re.compile(r"^`([^`\s]+)`:\n\n```[a-z]*\n(.*?)^```$", re.MULTILINE | re.DOTALL)


def _run(argv: list[str], cwd: Path, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    result = subprocess.run(
        argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=300, check=False
    )
    assert result.returncode == 0, f"{argv} failed:\n{result.stdout}\n{result.stderr}"
    return result


def test_the_worked_example_builds_installs_runs_and_passes_its_test(tmp_path: Path) -> None:
    text = DOC.read_text()
    files = FILE_BLOCK.findall(text)
    assert {name for name, _ in files} >= {
        "my_talker/pyproject.toml",
        "my_talker/my_talker/__init__.py",
        "my_talker/tests/test_talk.py",
    }
    for name, body in files:
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(body)
    site = tmp_path / "site"
    env = {**os.environ, "PIP_NO_INDEX": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    pip = [sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--no-build-isolation"]
    # a home of its own: pip asks `rustc --version` for its user agent, and rustup's rustc
    # writes its settings into a home that has none
    pip_env = {**env, "HOME": str(tmp_path / "home")}
    _run([*pip, "--target", str(site), str(tmp_path / "my_talker")], tmp_path, pip_env)
    env["PYTHONPATH"] = os.pathsep.join([str(site), os.environ.get("PYTHONPATH", "")])
    pkg = [sys.executable, "-m", "launchkit", "pkg"]
    listed = _run([*pkg, "executables", "my_talker"], tmp_path, env)
    assert listed.stdout == "my_talker listener\nmy_talker talker\n"
    share = _run([*pkg, "share", "my_talker"], tmp_path, env)
    assert Path(share.stdout.strip()).is_relative_to(site)
    tested = _run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "my_talker/tests"],
        tmp_path,
        env,
    )
    assert "1 passed" in tested.stdout


def test_the_hand_made_ros_layout_works_as_shown(tmp_path: Path) -> None:
    (script,) = [
        block
        for block in re.findall(r"^```sh\n(.*?)^```$", DOC.read_text(), re.MULTILINE | re.DOTALL)
        if "ament_index" in block
    ]
    launchkit = Path(sys.executable).parent  # the environment's `launchkit` command
    env = {**os.environ, "PATH": f"{launchkit}{os.pathsep}{os.environ.get('PATH', '')}"}
    env.pop("AMENT_PREFIX_PATH", None)
    ran = _run(["bash", "-euc", script], tmp_path, env)
    assert ran.stdout.splitlines()[0] == "my_tools hello"
    assert "[hello-1] hello from my_tools" in ran.stdout.splitlines()
