"""Finding a component class by its plugin name."""

from __future__ import annotations

import importlib
from importlib.metadata import entry_points
from typing import Any

from launchkit.errors import UserError

GROUP = "launchkit.components"


class PluginError(UserError):
    """A plugin name that names no loadable component."""


def find_component(package: str, plugin: str) -> Any:
    """The class ``plugin`` names: a registered plugin name, else ``module:Class`` or
    ``module.Class``; :class:`PluginError` saying what was tried."""
    for entry in entry_points(group=GROUP):
        if entry.name == plugin:
            return entry.load()
    module_name, sep, attribute = plugin.partition(":")
    if not sep:
        module_name, _, attribute = plugin.rpartition(".")
    if "::" in plugin or not module_name or not attribute:
        raise PluginError(
            f"no launchkit component '{plugin}' (package '{package}')",
            expected=f"a plugin name registered in the '{GROUP}' entry-point group, "
            "or module:Class of a launchkit Python node",
            hint="C++ components load only into a real rclcpp_components container",
        )
    try:
        module = importlib.import_module(module_name)
        return getattr(module, attribute)
    except (ImportError, AttributeError) as error:
        raise PluginError(
            f"cannot load component '{plugin}': {error}", expected="module:Class"
        ) from None
