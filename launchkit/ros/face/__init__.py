"""rclpy's face: the folder put first on ``PYTHONPATH`` so that ``import rclpy`` (and the message
packages, through ``sitecustomize``) get launchkit's ROS layer; and the choice of which rclpy a
process gets.

The folder's top-level packages (``rclpy``, later ``tf2_ros``...) are thin modules naming what
:mod:`launchkit.ros` provides, laid out as rclpy lays out its own; ``sitecustomize`` installs the
message-package import hook when the interpreter starts, then runs the next ``sitecustomize`` on
``sys.path``. This ``__init__`` is only for launchkit; nothing imports the face's modules by their
``launchkit.ros.face`` names.

Which rclpy a process gets is decided once, when it starts, from its environment
(:func:`choose`): ``LAUNCHKIT_RCLPY=launchkit`` or ``=ros`` says so; unset, a sourced ROS 2
install (``ROS_DISTRO`` set and an ``rclpy`` package in one of ``AMENT_PREFIX_PATH``'s prefixes)
means the real one, anything else launchkit's.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path

from launchkit.envvars import RCLPY
from launchkit.errors import UserError

LAUNCHKIT = "launchkit"
ROS = "ros"


class RclpyChoiceError(UserError):
    """A ``LAUNCHKIT_RCLPY`` value that is neither choice."""


def path() -> Path:
    """The folder to put first on ``PYTHONPATH``."""
    return Path(__file__).resolve().parent


def choose(environ: Mapping[str, str]) -> str:
    """``"launchkit"`` or ``"ros"``: which rclpy a process with environment ``environ`` gets."""
    value = environ.get(RCLPY, "").strip()
    if value.lower() in (LAUNCHKIT, ROS):
        return value.lower()
    if value:
        raise RclpyChoiceError(
            f"{RCLPY}={value!r} is not a choice", expected=f"{RCLPY}=launchkit or {RCLPY}=ros"
        )
    return ROS if sourced_ros(environ) else LAUNCHKIT


def sourced_ros(environ: Mapping[str, str]) -> bool:
    """Whether ``environ`` is a sourced ROS 2 install's: ``ROS_DISTRO`` set and an ``rclpy``
    package under one of the ``AMENT_PREFIX_PATH`` prefixes (``lib/pythonX.Y/site-packages``
    or Debian's ``local/lib/pythonX.Y/dist-packages``)."""
    if not environ.get("ROS_DISTRO", "").strip():
        return False
    for prefix in environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep):
        if not prefix:
            continue
        root = Path(prefix)
        for pattern in ("lib/python3*/*-packages/rclpy", "local/lib/python3*/*-packages/rclpy"):
            if any((found / "__init__.py").is_file() for found in root.glob(pattern)):
                return True
    return False


def environment(environ: Mapping[str, str]) -> dict[str, str]:
    """What a process started with ``environ`` must have changed: ``PYTHONPATH`` with the face
    first when it gets launchkit's rclpy, nothing when it gets the real one."""
    if choose(environ) == ROS:
        return {}
    folder = str(path())
    rest = [p for p in environ.get("PYTHONPATH", "").split(os.pathsep) if p and p != folder]
    return {"PYTHONPATH": os.pathsep.join([folder, *rest])}


def child_environment(cmd: Sequence[str], environ: Mapping[str, str]) -> dict[str, str]:
    """:func:`environment` for a process running ``cmd``, except launchkit's own programs
    (``python -m launchkit.…``: the stock nodes use :mod:`launchkit.ros` itself, and the
    bridge needs the real rclpy), which are started as they are."""
    if len(cmd) >= 3 and cmd[0] == sys.executable and cmd[1] == "-m":
        if cmd[2] == "launchkit" or cmd[2].startswith("launchkit."):
            return {}
    return environment(environ)
