"""Stand-ins for the launch description sources a Python launch file hands to
``IncludeLaunchDescription``, and the modules that hold them.

Jazzy has ``PythonLaunchDescriptionSource``, ``FrontendLaunchDescriptionSource`` and
``AnyLaunchDescriptionSource`` in ``launch.launch_description_sources``, and
``XMLLaunchDescriptionSource`` / ``YAMLLaunchDescriptionSource`` in the ``launch_xml`` /
``launch_yaml`` packages (``launch_xml.launch_description_sources``). Each says how the included
file is read, which the include passes on to the loader:

* Python: as a Python launch file, whatever its name;
* Frontend, XML, YAML: as XML or YAML by the file's suffix (Jazzy's
  ``FrontendLaunchDescriptionSource`` drops the parser it is given, so an
  ``XMLLaunchDescriptionSource`` reads a YAML file too);
* Any: by the suffix, Python for ``*.py``.
"""

from __future__ import annotations

import types
from typing import Any

from launchkit.frontend.python.launch_api import LaunchDescriptionSource
from launchkit.frontend.python.values import to_value


class PythonLaunchDescriptionSource(LaunchDescriptionSource):
    """``launch.launch_description_sources.PythonLaunchDescriptionSource``."""

    syntax: str | None = "python"

    def __init__(self, launch_file_path: Any) -> None:
        self.location = to_value(launch_file_path)


class AnyLaunchDescriptionSource(LaunchDescriptionSource):
    """``launch.launch_description_sources.AnyLaunchDescriptionSource``."""

    syntax: str | None = None

    def __init__(self, launch_file_path: Any) -> None:
        self.location = to_value(launch_file_path)


class FrontendLaunchDescriptionSource(LaunchDescriptionSource):
    """``launch.launch_description_sources.FrontendLaunchDescriptionSource``."""

    syntax: str | None = "frontend"

    def __init__(self, launch_file_path: Any, *, method: str = "", parser: object = None) -> None:
        del method, parser  # ROS keeps neither (the parser is chosen by the file's suffix)
        self.location = to_value(launch_file_path)


class XMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    """``launch_xml.launch_description_sources.XMLLaunchDescriptionSource``."""

    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(launch_file_path)


class YAMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    """``launch_yaml.launch_description_sources.YAMLLaunchDescriptionSource``."""

    def __init__(self, launch_file_path: Any) -> None:
        super().__init__(launch_file_path)


def _module(name: str, **members: object) -> types.ModuleType:
    module = types.ModuleType(name)
    module.__dict__.update(members)
    return module


def source_modules() -> dict[str, types.ModuleType]:
    """``launch.launch_description_sources``, ``launch_xml``, ``launch_yaml`` and their
    ``launch_description_sources``, by module name."""
    sources = _module(
        "launch.launch_description_sources",
        PythonLaunchDescriptionSource=PythonLaunchDescriptionSource,
        FrontendLaunchDescriptionSource=FrontendLaunchDescriptionSource,
        AnyLaunchDescriptionSource=AnyLaunchDescriptionSource,
    )
    xml_sources = _module(
        "launch_xml.launch_description_sources",
        XMLLaunchDescriptionSource=XMLLaunchDescriptionSource,
    )
    yaml_sources = _module(
        "launch_yaml.launch_description_sources",
        YAMLLaunchDescriptionSource=YAMLLaunchDescriptionSource,
    )
    launch_xml = _module("launch_xml", launch_description_sources=xml_sources)
    launch_yaml = _module("launch_yaml", launch_description_sources=yaml_sources)
    return {m.__name__: m for m in (sources, xml_sources, yaml_sources, launch_xml, launch_yaml)}
