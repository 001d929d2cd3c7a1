"""The ``teleop_twist_keyboard`` stand-in: keys in a terminal to ``/cmd_vel`` twists."""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="teleop_twist_keyboard",
    share=Path(__file__).resolve().parent,
    executables={"teleop_twist_keyboard": "launchkit.stock.teleop_twist_keyboard.node"},
    stand_in=True,
)
