"""The three-wheeled robot package: where its launch files and URDF live.

In a source checkout the share directory is the repository root (``launch/`` with the
tutorials' Python launch files, ``launch_xml/``, ``urdf/`` and ``config/`` beside this
package); in an installed wheel they are packed under ``robot_wheel/share/``.
"""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

_HERE = Path(__file__).resolve().parent


def _share_dir() -> Path:
    packed = _HERE / "share"
    return packed if (packed / "launch_xml").is_dir() else _HERE.parent


PACKAGE = PythonPackage(name="robot_wheel", share=_share_dir(), executables={})
