"""Installed distributions' ``launchkit.packages`` entry points are read once per process (a
``launchkit run`` makes two package indexes) and read again after an install."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

import pytest

from launchkit import packages
from launchkit.packages import PackageIndex


def _install(folder: Path, dist: str, package: str) -> None:
    """A distribution in ``folder`` whose entry point registers the package ``package``."""
    module = folder / f"{dist}_pkg.py"
    module.write_text(
        "from pathlib import Path\n"
        "from launchkit.packages import PythonPackage\n"
        f"PACKAGE = PythonPackage(name={package!r}, share=Path(__file__).parent,"
        " executables={})\n"
    )
    info = folder / f"{dist}-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(
        textwrap.dedent(f"""\
            [launchkit.packages]
            {package} = {dist}_pkg:PACKAGE
            """)
    )


@pytest.fixture
def site(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A folder of installed distributions on ``sys.path``, with the standard library only.

    The entry points are read again when a ``sys.path`` folder changes; the clone's own folders
    change while the suite runs (another test builds a wheel beside the sources), so they are
    left out here, and loading an entry point's module writes no ``__pycache__`` into the
    folder (which would change it)."""
    standard = [entry for entry in sys.path if entry.startswith(sys.base_prefix)]
    monkeypatch.setattr(sys, "path", [str(tmp_path), *standard])
    monkeypatch.setattr(sys, "dont_write_bytecode", True)
    return tmp_path


def test_a_second_index_does_not_read_the_entry_points_again(
    site: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _install(site, "first_dist", "first_pkg")
    reads: list[int] = []
    real = packages._read_entry_points
    monkeypatch.setattr(packages, "_read_entry_points", lambda: (reads.append(1), real())[1])
    assert "first_pkg" in PackageIndex(ament_prefix_path="").python_packages()
    assert "first_pkg" in PackageIndex(ament_prefix_path="").python_packages()
    assert len(reads) == 1


def test_an_install_is_seen_by_the_next_index(site: Path) -> None:
    _install(site, "early_dist", "early_pkg")
    before = PackageIndex(ament_prefix_path="")
    assert "early_pkg" in before.python_packages()
    _install(site, "late_dist", "late_pkg")
    after = PackageIndex(ament_prefix_path="").python_packages()
    assert {"early_pkg", "late_pkg"} <= set(after)
    assert after["late_pkg"].share == site
    assert "late_pkg" not in before.python_packages()  # an index keeps what it read


def test_an_index_cannot_change_what_the_next_one_finds(site: Path) -> None:
    _install(site, "kept_dist", "kept_pkg")
    first = PackageIndex(ament_prefix_path="").python_packages()
    assert isinstance(first, dict)
    first.pop("kept_pkg")
    assert "kept_pkg" in PackageIndex(ament_prefix_path="").python_packages()
    assert sys.path[0] == str(site)
