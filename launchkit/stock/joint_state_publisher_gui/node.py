"""The ``joint_state_publisher_gui`` executable: a headless joint_state_publisher."""

from __future__ import annotations

import sys

import launchkit.ros as ros
from launchkit.stock import _entry
from launchkit.stock.joint_state_publisher import node as jsp

NOTE = (
    "no slider window in launchkit: publishing joint states as joint_state_publisher does "
    "(set positions with zeros.<joint> or a source_list topic)"
)


def main(argv: list[str]) -> int:
    """Say there are no sliders, then run joint_state_publisher under this node's name."""
    ros.get_logger("joint_state_publisher_gui").warn(NOTE)
    return jsp.main(argv, name="joint_state_publisher_gui")


if __name__ == "__main__":
    sys.exit(_entry.run(main, "joint_state_publisher_gui"))
