"""Parse YAML launch files (``*.launch.yaml``) into :class:`LaunchDescription`s.

The file is one mapping with the single key ``launch``, whose value is the list of actions, or
a mapping with ``children`` (that list) and ``deprecated`` (a message), as ROS reads it.
"""

from __future__ import annotations

from pathlib import Path

from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.yaml.entity import YamlEntity
from launchkit.frontend.yaml.scalars import describe
from launchkit.safe_yaml import compose, read_text


class YamlParser:
    """Parses YAML launch text; the tags are read by ``actions``."""

    def __init__(self, actions: ActionParser) -> None:
        self.actions = actions

    def parse_file(self, path: Path, included_from: Location | None = None) -> LaunchDescription:
        """Read and parse ``path``; ``included_from`` locates an error in reading it."""
        return self.parse_text(read_text(path, included_from), path)

    def parse_text(self, text: str, path: Path) -> LaunchDescription:
        """Parse launch YAML ``text`` as if read from ``path``."""
        expected = "a YAML launch file: 'launch:' followed by a list of actions"
        root = compose(text, path)
        if root is None:
            raise LaunchFileError("the YAML file is empty", Location(str(path)), expected=expected)
        if root.kind != "map" or not root.pairs:
            raise LaunchFileError(
                f"the YAML document is {describe(root)}", root.location, expected=expected
            )
        key, value = root.pairs[0]
        if key.value != "launch":
            raise LaunchFileError(
                f"the top-level key is {describe(key)}", key.location, expected="'launch:'"
            )
        if len(root.pairs) > 1:
            extra = root.pairs[1][0]
            raise LaunchFileError(
                f"a second top-level key ({describe(extra)}) beside 'launch'",
                extra.location,
                expected="'launch:' as the only top-level key",
            )
        entity = YamlEntity("launch", value, key.location)
        deprecated = entity.raw("deprecated")
        actions = self.actions.parse_actions(entity)
        entity.assert_fully_read()
        return LaunchDescription(path, actions, deprecated)
