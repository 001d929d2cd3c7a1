"""Run at interpreter start (the face is first on ``PYTHONPATH``): launchkit's message packages
shadow any installed ones (``from std_msgs.msg import String``), then the next
``sitecustomize`` on ``sys.path`` (a user's, the distribution's) runs as it would have."""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import sys


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


_install_message_packages()
_chain()
