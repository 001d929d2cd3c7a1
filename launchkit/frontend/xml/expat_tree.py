"""A plain launch file read with the standard library's expat, into elements lxml would give.

Loading lxml imports ``inspect`` (with ``ast``, ``dis``, ``tokenize``), ``typing`` and ``gzip``:
about a fifth of ``launchkit run``'s own start-up for an XML file (docs/benchmarks.md, issue
15). Expat reads the common case, a well-formed file of at most 128 KiB in UTF-8, UTF-16 (with
its byte order mark), ISO-8859-1 or US-ASCII, with no document type declaration, no namespaces
and at most lxml's 255 levels, into the same tags, attributes (character references resolved, values
normalised as XML says) and lines. Anything else returns None and the caller reads the file
with lxml as before: entities, other encodings, and every error message stay lxml's.
"""

from __future__ import annotations

from collections.abc import Iterator
from xml.parsers import expat

#: Encodings expat reads itself (any other goes to lxml, which knows many more).
_NATIVE = {"utf-8": "UTF-8", "utf-16": "UTF-16", "iso-8859-1": "ISO-8859-1", "us-ascii": "ASCII"}
#: Deeper documents are refused by lxml ("Excessive depth"): they go to lxml for its error.
_MAX_DEPTH = 255
#: Larger files go to lxml: it builds a tree in C, where expat calls Python for each element
#: (a few microseconds each); beyond about this size that costs more than importing lxml.
MAX_PLAIN_SIZE = 128 * 1024


class Element:
    """One element: what :class:`~launchkit.frontend.xml.entity.XmlEntity` reads of lxml's."""

    __slots__ = ("attrib", "children", "sourceline", "tag")

    def __init__(self, tag: str, attrib: dict[str, str], sourceline: int) -> None:
        self.tag = tag
        self.attrib = attrib
        self.sourceline = sourceline  # the line of the start tag's "<"
        self.children: list[Element] = []

    def keys(self) -> list[str]:
        """The attribute names, in document order."""
        return list(self.attrib)

    def items(self) -> list[tuple[str, str]]:
        """The attributes' names and values, in document order."""
        return list(self.attrib.items())

    def get(self, name: str) -> str | None:
        """An attribute's value."""
        return self.attrib.get(name)

    def __len__(self) -> int:
        return len(self.children)

    def __iter__(self) -> Iterator[Element]:
        return iter(self.children)


class _NotPlain(Exception):
    """The document needs lxml (a declaration, a namespace, an encoding or a depth)."""


def read_plain(data: bytes) -> tuple[Element, str] | None:
    """The root element of ``data`` and its encoding's name, or None when the document is
    not a plain one (see the module's docstring) or not well-formed."""
    if len(data) > MAX_PLAIN_SIZE:
        return None
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        encoding = "UTF-16"
    elif data.startswith(b"\xef\xbb\xbf"):
        encoding = "UTF-8"
    else:
        encoding = ""  # the declaration's, else UTF-8
    parser = expat.ParserCreate()
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    stack: list[Element] = []
    roots: list[Element] = []

    def declaration(_version: str, declared: str | None, _standalone: int) -> None:
        nonlocal encoding
        name = _NATIVE.get((declared or "utf-8").lower())
        if name is None:
            raise _NotPlain(declared)
        encoding = encoding or name

    def start(tag: str, attrib: dict[str, str]) -> None:
        if ":" in tag or any(":" in name for name in attrib) or len(stack) >= _MAX_DEPTH:
            raise _NotPlain(tag)
        element = Element(tag, attrib, parser.CurrentLineNumber)
        (stack[-1].children if stack else roots).append(element)
        stack.append(element)

    def end(_tag: str) -> None:
        stack.pop()

    def doctype(*_args: object) -> None:
        raise _NotPlain("DOCTYPE")

    parser.XmlDeclHandler = declaration
    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.StartDoctypeDeclHandler = doctype
    try:
        parser.Parse(data, True)
    except Exception:  # _NotPlain, ExpatError, a codec's error: lxml reads it (or says why)
        return None
    if len(roots) != 1:
        return None
    return roots[0], encoding or "UTF-8"
