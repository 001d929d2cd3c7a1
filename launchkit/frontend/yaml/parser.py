"""Parse YAML launch files (``*.launch.yaml``) into :class:`LaunchDescription`s.

The file is one mapping with the single key ``launch``, whose value is the list of actions, or
a mapping with ``children`` (that list) and ``deprecated`` (a message), as ROS reads it.
"""

from __future__ import annotations

import itertools
from pathlib import Path

from launchkit.description.actions.base import Action
from launchkit.description.launch_description import LaunchDescription
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.yaml.entity import YamlEntity, action_entity
from launchkit.frontend.yaml.line_entity import line_entity
from launchkit.frontend.yaml.scalars import describe
from launchkit.safe_yaml import NotAList, compose, read_text
from launchkit.safe_yaml_fast import LineItem, list_items

#: How many items of a large ``launch:`` list are composed before their actions are built
#: (memory stays bounded; composing and building by turns one item at a time measured
#: 10-20 % slower than by batches, likely the processor's caches).
BATCH = 1000


class YamlParser:
    """Parses YAML launch text; the tags are read by ``actions``."""

    def __init__(self, actions: ActionParser) -> None:
        self.actions = actions

    def parse_file(self, path: Path, included_from: Location | None = None) -> LaunchDescription:
        """Read and parse ``path``; ``included_from`` locates an error in reading it."""
        return self.parse_text(read_text(path, included_from), path)

    def parse_text(self, text: str, path: Path) -> LaunchDescription:
        """Parse launch YAML ``text`` as if read from ``path``: ``launch: [...]`` one action
        at a time (a large file's nodes are not all held), any other shape as one tree."""
        try:
            return self._parse_list(text, path)
        except NotAList:
            return self.parse_tree(text, path)

    def _parse_list(self, text: str, path: Path) -> LaunchDescription:
        """``launch:`` and a list of actions, parsed :data:`BATCH` items at a time as they are
        composed. Errors keep the precedence they have when the file is read as a tree: a YAML
        error, then a document of another shape, then an item that is no entity, then an
        action's error."""
        parsed: list[Action] = []
        bad_item: LaunchFileError | None = None
        bad_action: LaunchFileError | None = None
        items = list_items(text, path, "launch")
        while batch := list(itertools.islice(items, BATCH)):
            for item in batch:
                if bad_item is not None:
                    break
                try:
                    entity = (
                        line_entity("launch", item)
                        if isinstance(item, LineItem)
                        else action_entity("launch", item)
                    )
                except LaunchFileError as error:
                    bad_item = error
                    break
                if bad_action is None:
                    try:
                        parsed.append(self.actions.parse_action(entity))
                    except LaunchFileError as error:
                        bad_action = error
        first = bad_item or bad_action
        if first is not None:
            raise first
        return LaunchDescription(path, parsed, None)

    def parse_tree(self, text: str, path: Path) -> LaunchDescription:
        """Parse launch YAML ``text`` composed as one tree."""
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
