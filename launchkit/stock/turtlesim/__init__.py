"""The ``turtlesim`` stand-in: ROS 2 Jazzy's turtlesim, drawn in the browser viewer.

Executables ``turtlesim_node``, ``turtle_teleop_key``, ``draw_square`` and ``mimic``; the share
directory holds the package's interfaces (``msg/Pose.msg``, ``msg/Color.msg``, ``srv/Spawn.srv``,
..., ``action/RotateAbsolute.action``: ``from turtlesim.msg import Pose`` works through the
message import hook) and ``launch/multisim.launch.py``. See ``docs/stock-nodes.md``.
"""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

SHARE = Path(__file__).resolve().parent / "share"

PACKAGE = PythonPackage(
    name="turtlesim",
    share=SHARE,
    executables={
        "turtlesim_node": "launchkit.stock.turtlesim.turtlesim_node",
        "turtle_teleop_key": "launchkit.stock.turtlesim.turtle_teleop_key",
        "draw_square": "launchkit.stock.turtlesim.draw_square",
        "mimic": "launchkit.stock.turtlesim.mimic",
    },
)
