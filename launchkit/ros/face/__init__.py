"""rclpy's face: the folder put first on ``PYTHONPATH`` so that ``import rclpy`` (and the message
packages, through ``sitecustomize``) get launchkit's ROS layer.

Its top-level packages (``rclpy``, later ``tf2_ros``...) are thin modules naming what
:mod:`launchkit.ros` provides, laid out as rclpy lays out its own; ``sitecustomize`` installs
the message-package import hook when the interpreter starts, then runs the next
``sitecustomize`` on ``sys.path``. This ``__init__`` is only for launchkit (the folder's path);
nothing imports the face's modules by their ``launchkit.ros.face`` names.
"""

from __future__ import annotations

from pathlib import Path


def path() -> Path:
    """The folder to put first on ``PYTHONPATH``."""
    return Path(__file__).resolve().parent
