"""The ``joint_state_publisher`` stand-in: a position for every moving joint of the robot."""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="joint_state_publisher",
    share=Path(__file__).resolve().parent,
    executables={"joint_state_publisher": "launchkit.stock.joint_state_publisher.node"},
    stand_in=True,
)
