"""Run at interpreter start (the face is first on ``PYTHONPATH``): launchkit's message packages
shadow any installed ones (``from std_msgs.msg import String``), then the next
``sitecustomize`` on ``sys.path`` (a user's, the distribution's) runs as it would have."""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import sys


def _own_prefix_on_ament_path() -> None:
    """Put this interpreter's prefix on ``AMENT_PREFIX_PATH`` where ROS packages were installed
    into it with pip (the ros-jazzy wheels keep an ament index there): their interface packages
    then come from launchkit's message layer like any other, never as the wheels' own rosidl
    classes beside launchkit's rclpy."""
    index = os.path.join(sys.prefix, "share", "ament_index", "resource_index", "packages")
    if not os.path.isdir(index):
        return
    paths = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    if sys.prefix not in paths:
        os.environ["AMENT_PREFIX_PATH"] = os.pathsep.join([*paths, sys.prefix])


def _install_message_packages() -> None:
    try:
        from launchkit.ros.msgs import install
    except ImportError:  # an interpreter without launchkit: `import rclpy` will say so
        return
    install()


def _chain() -> None:
    """Run the ``sitecustomize`` that this one shadows, if any."""
    here = os.path.dirname(os.path.abspath(__file__))
    entries = [p for p in sys.path if os.path.abspath(p or ".") != here]
    spec = importlib.machinery.PathFinder.find_spec("sitecustomize", entries)
    if spec is None or spec.loader is None or spec.origin == os.path.abspath(__file__):
        return
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)


_own_prefix_on_ament_path()
_install_message_packages()
_chain()
