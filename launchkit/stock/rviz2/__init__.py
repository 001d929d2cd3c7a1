"""The ``rviz2`` stand-in: a browser viewer of the robot and a Foxglove server, on one port."""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="rviz2",
    share=Path(__file__).resolve().parent,
    executables={"rviz2": "launchkit.stock.rviz2.node"},
    programs={"rviz2": "rviz2"},
    stand_in=True,
)
