"""The ``joint_state_publisher_gui`` stand-in: joint_state_publisher without the slider window.

launchkit has no GUI toolkit; the executable publishes the same ``/joint_states`` as
``joint_state_publisher`` (``zeros.<joint>`` and ``source_list`` set positions) and says so.
"""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

PACKAGE = PythonPackage(
    name="joint_state_publisher_gui",
    share=Path(__file__).resolve().parent,
    executables={"joint_state_publisher_gui": "launchkit.stock.joint_state_publisher_gui.node"},
)
