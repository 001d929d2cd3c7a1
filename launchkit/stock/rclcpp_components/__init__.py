"""The ``rclcpp_components`` stand-in: a component container that loads launchkit Python nodes
(``component_container``, ``component_container_mt``, ``component_container_isolated``), so
``ComposableNodeContainer`` and ``<node_container>`` put several components in one process.

A component is a :class:`launchkit.ros.Node` subclass whose ``__init__`` accepts ``**kwargs``
and passes them on to ``Node.__init__`` (name, namespace, remaps and parameters come that way,
as rclcpp's NodeOptions do). It is named by its plugin name, registered in the
``launchkit.components`` entry-point group (``"demo::Talker" = "demo.talker:Talker"``), or
directly as ``module:Class``. See docs/launch-files.md.
"""

from __future__ import annotations

from pathlib import Path

from launchkit.packages import PythonPackage

_CONTAINER = "launchkit.stock.rclcpp_components.container"

PACKAGE = PythonPackage(
    name="rclcpp_components",
    share=Path(__file__).resolve().parent,
    executables={
        "component_container": _CONTAINER,
        "component_container_mt": _CONTAINER,
        "component_container_isolated": _CONTAINER,
    },
    stand_in=True,
)
