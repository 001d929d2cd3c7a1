"""Reading a launch file of any syntax: the frontend is chosen by the file's suffix.

XML (``*.launch.xml``, ``*.xml``) goes to :mod:`launchkit.frontend.xml`, YAML (``*.launch.yaml``,
``*.yaml``, ``*.yml``) to :mod:`launchkit.frontend.yaml`, Python (``*.launch.py``) to
:mod:`launchkit.frontend.python`. ROS reads ``*.launch`` as XML or YAML; so does launchkit, by
its first character. An include may ask for a syntax whatever the suffix (a Python file's
``PythonLaunchDescriptionSource`` reads any file as Python, a ``FrontendLaunchDescriptionSource``
only XML or YAML). Each file is read once per loader and syntax.
"""

from __future__ import annotations

from pathlib import Path

from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.python import load_python_launch
from launchkit.frontend.tags import standard_parser
from launchkit.frontend.xml.parser import XmlParser
from launchkit.frontend.yaml.parser import YamlParser
from launchkit.packages import is_file

XML_SUFFIXES = (".xml", ".launch")
YAML_SUFFIXES = (".yaml", ".yml")

#: The syntaxes an include may ask for: None (by suffix), "python", "frontend" (XML or YAML).
SYNTAXES = (None, "python", "frontend")


class LaunchLoader:
    """Loads launch files into descriptions, caching each by path."""

    def __init__(self, actions: ActionParser | None = None) -> None:
        self.actions = actions or standard_parser()
        self.xml = XmlParser(self.actions)
        self.yaml = YamlParser(self.actions)
        self._cache: dict[tuple[Path, str | None], LaunchDescription] = {}

    def load(
        self, path: Path, included_from: Location | None = None, syntax: str | None = None
    ) -> LaunchDescription:
        """The description of ``path``; errors carry the file, line and column."""
        path = path.resolve()
        cached = self._cache.get((path, syntax))
        if cached is not None:
            return cached
        description = self._read(path, self._frontend(path, syntax), syntax, included_from)
        self._cache[(path, syntax)] = description
        return description

    def _read(
        self, path: Path, frontend: str | None, syntax: str | None, included_from: Location | None
    ) -> LaunchDescription:
        if frontend == "python":
            description = load_python_launch(path, included_from)
        elif frontend == "yaml":
            description = self.yaml.parse_file(path, included_from)
        elif frontend == "xml":
            description = self.xml.parse_file(path, included_from)
        else:
            raise LaunchFileError(
                f"cannot read launch file '{path.name}'"
                + (" as XML or YAML" if syntax == "frontend" else ""),
                included_from or Location(str(path)),
                expected="an XML (*.launch.xml, *.xml), YAML (*.launch.yaml, *.yaml, *.yml)"
                + (" launch file" if syntax == "frontend" else " or Python (*.launch.py) one"),
            )
        return description

    def _frontend(self, path: Path, syntax: str | None) -> str | None:
        suffix = path.suffix
        if syntax == "python" or (syntax is None and suffix == ".py" and is_file(path)):
            return "python"
        if suffix in YAML_SUFFIXES:
            return "yaml"
        if suffix in XML_SUFFIXES:
            return "yaml" if suffix == ".launch" and not _looks_like_xml(path) else "xml"
        return None


def _looks_like_xml(path: Path) -> bool:
    """Whether a ``*.launch`` file starts (after blanks) with ``<``, as XML does."""
    try:
        with path.open("rb") as stream:
            head = stream.read(512)
    except OSError:
        return True  # the XML reader reports it
    if head.startswith((b"\xff\xfe", b"\xfe\xff")):  # a UTF-16 byte order mark: XML
        return True
    return head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"<")
