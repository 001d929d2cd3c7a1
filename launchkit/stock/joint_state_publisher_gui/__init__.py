"""The ``joint_state_publisher_gui`` stand-in: joint_state_publisher whose sliders are in the
browser viewer the ``rviz2`` stand-in serves (see its node module)."""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="joint_state_publisher_gui",
    share=Path(__file__).resolve().parent,
    executables={"joint_state_publisher_gui": "launchkit.stock.joint_state_publisher_gui.node"},
    stand_in=True,
)
