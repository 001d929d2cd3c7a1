"""Reading a launch file of any syntax: the frontend is chosen by the file's suffix.

XML (``*.launch.xml``, ``*.xml``, ``*.launch``) goes to :mod:`launchkit.frontend.xml`, Python
(``*.launch.py``) to :mod:`launchkit.frontend.python`; a frontend for another syntax adds its
suffixes to :meth:`LaunchLoader.load`. Each file is read once per loader.
"""

from __future__ import annotations

from pathlib import Path

from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.tags import standard_parser
from launchkit.frontend.xml.parser import XML_SUFFIXES, XmlParser


class LaunchLoader:
    """Loads launch files into descriptions, caching each by path."""

    def __init__(self, actions: ActionParser | None = None) -> None:
        self.actions = actions or standard_parser()
        self.xml = XmlParser(self.actions)
        self._cache: dict[Path, LaunchDescription] = {}

    def load(self, path: Path, included_from: Location | None = None) -> LaunchDescription:
        """The description of ``path``; errors carry the file, line and column."""
        path = path.resolve()
        cached = self._cache.get(path)
        if cached is not None:
            return cached
        if path.suffix == ".py" and path.is_file():
            from launchkit.frontend.python import load_python_launch

            description = load_python_launch(path, included_from)
        elif path.suffix in XML_SUFFIXES:
            description = self.xml.parse_file(path, included_from)
        else:
            raise LaunchFileError(
                f"cannot read launch file '{path.name}'",
                included_from or Location(str(path)),
                expected="an XML launch file (*.launch.xml, *.xml, *.launch) "
                "or a Python one (*.launch.py)",
                hint="YAML launch files are not supported",
            )
        self._cache[path] = description
        return description
