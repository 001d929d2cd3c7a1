"""The ``robot_state_publisher`` stand-in: URDF in; ``/tf`` and ``/tf_static`` out."""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="robot_state_publisher",
    share=Path(__file__).resolve().parent,
    executables={"robot_state_publisher": "launchkit.stock.robot_state_publisher.node"},
    stand_in=True,
)
