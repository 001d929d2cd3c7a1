"""The two XML readers agree: expat (a plain launch file, for start-up: no lxml import) and
lxml (any other file) give the same tags, attributes and locations, and a file expat does not
read as lxml would is left to lxml (its entities, encodings and error messages).

Every XML file of the repository and of the ROS corpus is read both ways, and so are files made
to differ: character references, attribute whitespace, comments, processing instructions,
CDATA, UTF-16 and Latin-1, a BOM, a DOCTYPE with entities, a namespace, an unknown encoding,
malformed ones.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from launchkit.errors import LaunchFileError
from launchkit.frontend.base_entity import Entity
from launchkit.frontend.xml.entity import SourceFile, XmlEntity
from launchkit.frontend.xml.expat_tree import read_plain
from launchkit.frontend.xml.parser import _decoded, _read_with_lxml

ROOT = Path(__file__).resolve().parents[2]
FILES = sorted(
    p
    for p in [*ROOT.glob("launchkit/**/*.xml"), *ROOT.glob("tests/**/*.xml")]
    if p.name.endswith(".launch.xml") or p.parent.name.startswith("launch")
)


def shape(entity: Entity) -> list[object]:
    """Tag, location, each attribute with its text and location, then the children's."""
    assert isinstance(entity, XmlEntity)
    attributes = [
        (name, entity.attribute_text(name), str(entity.attribute_location(name)))
        for name in entity.attribute_names()
    ]
    return [entity.tag, str(entity.location), attributes, [shape(c) for c in entity.children()]]


def both(data: bytes) -> tuple[list[object] | None, list[object]]:
    """The shape expat reads (None: left to lxml) and the one lxml reads."""
    path = Path("f.launch.xml")
    plain = read_plain(data)
    expat = None
    if plain is not None:
        expat = shape(XmlEntity(plain[0], SourceFile(path, _decoded(data, plain[1]))))
    root, encoding = _read_with_lxml(data, path)
    return expat, shape(XmlEntity(root, SourceFile(path, _decoded(data, encoding))))


def test_the_corpus_has_files() -> None:
    assert len(FILES) > 15


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_launch_file_reads_the_same_both_ways(path: Path) -> None:
    data = path.read_bytes()
    try:
        expat, lxml = both(data)
    except LaunchFileError:
        assert read_plain(data) is None  # malformed for lxml: expat left it to lxml too
        return
    assert expat is None or expat == lxml


PLAIN = {
    "references": '<launch>\n  <arg name="a&#65;&lt;&amp;" default="&#x263A;&quot;"/>\n</launch>',
    "whitespace": '<launch><arg name="a"\n     default="x\ty\n z  "/>\n</launch>',
    "comments": "<?xml version='1.0'?>\n<!-- c -->\n<launch><?pi x?><!-- <arg/> -->\n"
    "<group><![CDATA[<not/>]]><let name='x' value='1'/></group></launch>",
    "multi-line tags": '<launch>\n<node\n  pkg="p"\n  exec="e"/>\n'
    '<node pkg="q"\n exec="f"/>\n</launch>',
    "non-ascii": '<launch>\n  <arg name="é" default="日本"/><log message="ü"/>\n</launch>',
}
ENCODED = {
    "utf-16 with a BOM": (
        '<?xml version="1.0" encoding="UTF-16"?>\n<launch><arg name="ä"/></launch>'
    ).encode("utf-16"),
    "latin-1 declared": '<?xml version="1.0" encoding="ISO-8859-1"?>\n<launch>\n<arg name="ä"/>'
    "</launch>".encode("latin-1"),
    "utf-8 BOM": b'\xef\xbb\xbf<launch>\n<arg name="\xc3\xa4"/></launch>',
}
LXML_ONLY = {
    "entities": '<!DOCTYPE launch [<!ENTITY e "v">]>\n<launch><arg name="&e;"/></launch>',
    "namespace": '<launch xmlns:x="urn:x"><x:arg name="a"/></launch>',
    "other encoding": '<?xml version="1.0" encoding="windows-1252"?>\n<launch><arg name="a"/>'
    "</launch>",
    "deep": "<launch>" + "<group>" * 300 + "</group>" * 300 + "</launch>",
    "malformed": '<launch>\n  <arg name="a">\n</launch>',
    "duplicate attribute": '<launch><arg name="a" name="b"/></launch>',
    "undefined entity": '<launch><arg name="&nope;"/></launch>',
    "two roots": "<launch/><launch/>",
    "large": "<launch>" + '<let name="a" value="b"/>\n' * 6000 + "</launch>",
}


@pytest.mark.parametrize("text", PLAIN.values(), ids=list(PLAIN))
def test_a_plain_file_is_read_by_expat_as_lxml_reads_it(text: str) -> None:
    expat, lxml = both(text.encode())
    assert expat is not None
    assert expat == lxml


@pytest.mark.parametrize("data", ENCODED.values(), ids=list(ENCODED))
def test_the_encodings_expat_reads_give_lxml_s_text(data: bytes) -> None:
    expat, lxml = both(data)
    assert expat is not None
    assert expat == lxml


@pytest.mark.parametrize("text", LXML_ONLY.values(), ids=list(LXML_ONLY))
def test_what_expat_would_read_otherwise_is_left_to_lxml(text: str) -> None:
    assert read_plain(text.encode()) is None


def test_expat_locates_a_tag_where_it_begins() -> None:
    # lxml gives the line where a start tag ends, and the search back for "<node" from there
    # finds the second tag; expat gives the line where it begins.
    text = '<launch>\n<node\n  pkg="p"/><node pkg="q"/>\n</launch>'
    expat, lxml = both(text.encode())
    assert expat is not None
    assert [child[1] for child in expat[3]] == ["f.launch.xml:2:1", "f.launch.xml:3:12"]
    assert [child[1] for child in lxml[3]] == ["f.launch.xml:3:12", "f.launch.xml:3:12"]


def _located_by_the_pattern(entity: XmlEntity, name: str) -> str:
    """Where ``name``'s value begins as the pattern alone finds it (the first NAME = " after
    a blank; XmlEntity finds the usual NAME=" without it)."""
    pattern = re.compile(re.escape(name) + r"\s*=\s*([\"'])")
    text, position = entity.source.text, entity._start
    while True:
        match = pattern.search(text, position)
        if match is None:
            return str(entity.location)
        if text[match.start() - 1].isspace():
            return str(entity.source.location(match.end()))
        position = match.start() + 1


TAGS = [
    '<let name="a" value="b"/>',
    "<let name='a'\tvalue='b'/>",
    '<let name = "a" value\n = \n"b"/>',
    '<let xname="a" name="b" value="c"/>',
    '<let value="name=\'x\'" name="a"/>',  # the pattern's first match is in another value
    '<let value="x name=\'y\'" name="a"/>',
    '<let value="b"\n     name="a"/>',
    '<let value="xname="/>',
]


@pytest.mark.parametrize("tag", TAGS)
def test_attribute_locations_are_the_patterns(tag: str) -> None:
    text = f"<launch>\n  {tag}\n</launch>\n"
    path = Path("f.launch.xml")
    root, encoding = _read_with_lxml(text.encode(), path)
    entity = XmlEntity(root, SourceFile(path, _decoded(text.encode(), encoding)))
    (child,) = entity.children()
    assert isinstance(child, XmlEntity)
    for name in ("name", "value", "missing"):
        assert str(child.attribute_location(name)) == _located_by_the_pattern(child, name)
