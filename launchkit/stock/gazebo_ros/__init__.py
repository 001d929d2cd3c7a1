"""gazebo_ros stand-in: a PyBullet server, ``spawn_entity.py``, the diff drive and camera nodes.

The share directory holds ``launch/gazebo.launch.py`` (as gazebo_ros ships it) and ``worlds/``.
See ``docs/simulation.md``.
"""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

SHARE = Path(__file__).resolve().parent / "share"

PACKAGE = PythonPackage(
    name="gazebo_ros",
    share=SHARE,
    executables={
        "gzserver": "launchkit.stock.gazebo_ros.gzserver",
        "gazebo": "launchkit.stock.gazebo_ros.gzserver",
        "spawn_entity.py": "launchkit.stock.gazebo_ros.spawn_entity",
        "diff_drive": "launchkit.stock.gazebo_ros.diff_drive_node",
        "camera": "launchkit.stock.gazebo_ros.camera_node",
        "gzclient": "launchkit.stock.gazebo_ros.gzclient",
    },
    # what `ExecuteProcess(cmd=['gazebo', ...])` runs where Gazebo is not installed
    programs={"gazebo": "gazebo", "gzserver": "gzserver", "gzclient": "gzclient"},
    stand_in=True,
)
