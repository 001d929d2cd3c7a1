"""The ``tf2_ros`` stand-in: its command-line tools ``static_transform_publisher`` and
``tf2_echo`` (the Python API of ``tf2_ros`` is :mod:`launchkit.ros.tf2`)."""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="tf2_ros",
    share=Path(__file__).resolve().parent,
    executables={
        "static_transform_publisher": "launchkit.stock.tf2_ros.static_transform_publisher",
        "tf2_echo": "launchkit.stock.tf2_ros.tf2_echo",
    },
    stand_in=True,
)
