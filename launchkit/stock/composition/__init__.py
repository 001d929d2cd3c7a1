"""The ``composition`` demo stand-in (ros2/demos): ``composition::Talker`` and
``composition::Listener`` as launchkit components, to load into a ``component_container``."""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="composition", share=Path(__file__).resolve().parent, executables={}, stand_in=True
)
