"""The frontend's seams: tag parsers read any syntax's entities, and tags register explicitly.

A syntax other than XML (YAML, issue #10) plugs in by subclassing ``Entity``; these tests stand
in for it with entities built from plain Python data, and check that the same tag parsers give
the same actions, errors and locations as the XML frontend.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import pytest

from launchkit.description.actions import DeclareArgument, ExecuteNode, Group, Log
from launchkit.description.substitutions.base import Text
from launchkit.errors import LaunchFileError, Location
from launchkit.frontend.action_parser import ActionParser
from launchkit.frontend.base_entity import Entity
from launchkit.frontend.launch_loader import LaunchLoader
from launchkit.frontend.tags import composition, launch, ros, standard_parser


@dataclass
class Element:
    """A launch element as data: what a YAML mapping would hold."""

    tag: str
    attributes: dict[str, str] = field(default_factory=dict)
    children: list[Element] = field(default_factory=list)
    line: int = 1


class DataEntity(Entity):
    """An entity over :class:`Element` data, located by line in a made-up file."""

    def __init__(self, element: Element) -> None:
        super().__init__(element.tag)
        self.element = element

    @property
    def location(self) -> Location:
        return Location("data.launch", self.element.line, 1)

    def attribute_location(self, name: str) -> Location:
        if name not in self.element.attributes:
            return self.location
        index = list(self.element.attributes).index(name)
        return Location("data.launch", self.element.line, 10 + index)

    def attribute_names(self) -> list[str]:
        return list(self.element.attributes)

    def attribute_text(self, name: str) -> str | None:
        return self.element.attributes.get(name)

    def children(self) -> list[Entity]:
        return [DataEntity(child) for child in self.element.children]


def parse(element: Element) -> list[object]:
    return list(standard_parser().parse_actions(DataEntity(Element("launch", {}, [element]))))


def test_tag_parsers_read_entities_of_another_syntax() -> None:
    (group,) = parse(
        Element(
            "group",
            {"if": "true"},
            [
                Element("arg", {"name": "who", "default": "world"}, line=2),
                Element("log", {"message": "hello $(var who)"}, line=3),
                Element("node", {"pkg": "demo", "exec": "talker", "name": "t"}, line=4),
            ],
        )
    )
    assert isinstance(group, Group)
    assert group.condition is not None and group.condition.value == (Text("true"),)
    arg, log, node = group.actions
    assert isinstance(arg, DeclareArgument) and arg.name == "who"
    assert isinstance(log, Log) and log.location == Location("data.launch", 3, 1)
    assert isinstance(node, ExecuteNode)


def test_unread_attributes_are_errors_located_by_the_syntax() -> None:
    with pytest.raises(LaunchFileError) as caught:
        parse(Element("log", {"message": "m", "colour": "red"}, line=7))
    assert caught.value.location == Location("data.launch", 7, 11)
    assert "unknown attribute 'colour' on <log>" in caught.value.message


def test_the_same_tags_give_the_same_actions_in_xml(tmp_path: Path) -> None:
    path = tmp_path / "same.launch.xml"
    path.write_text('<launch><log message="hi" level="warning"/></launch>')
    (from_xml,) = LaunchLoader().load(path).actions
    (from_data,) = parse(Element("log", {"message": "hi", "level": "warning"}))
    assert isinstance(from_xml, Log) and isinstance(from_data, Log)
    assert (from_xml.message, from_xml.level) == (from_data.message, from_data.level)


def test_tags_are_registered_explicitly() -> None:
    empty = ActionParser()
    assert empty.tags() == []
    with pytest.raises(LaunchFileError, match="unknown tag <log>"):
        empty.parse_action(DataEntity(Element("log", {"message": "m"})))
    only_launch = ActionParser()
    launch.register(only_launch)
    assert "log" in only_launch.tags() and "node" not in only_launch.tags()
    assert standard_parser().tags() == sorted({*launch.TAGS, *ros.TAGS, *composition.TAGS})


def test_the_standard_parser_reads_every_tag_once() -> None:
    parser = standard_parser()
    (action,) = parser.parse_actions(
        DataEntity(Element("launch", {}, [Element("log", {"message": "m"})]))
    )
    assert isinstance(action, Log)
    with pytest.raises(ValueError, match="<node> registered twice"):
        parser.register("node", launch.parse_log)


def test_a_tag_registered_twice_is_refused() -> None:
    parser = ActionParser()
    launch.register(parser)
    with pytest.raises(ValueError, match="<arg> registered twice"):
        launch.register(parser)
