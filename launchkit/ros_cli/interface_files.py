"""Packages' interface files (``share/PKG/msg/*.msg``, ``srv/*.srv``, ``action/*.action``) as
``ros2 interface`` reads and shows them.

``ros2 interface show`` prints a file's own lines, comments and blank lines included, and under
each field of another message type that type's lines, indented by a tab, without their comments
(``--all-comments`` keeps them, ``--no-comments`` drops them everywhere). Which lines count as
comments and how a trailing comment is cut off follow what ros2interface does with
rosidl_adapter's parser in Jazzy, quirks included (a trailing ``# text`` leaves its ``#``; a
line of ``#`` alone is not a comment), so the output is the one a ROS 2 install prints.
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Iterator
from pathlib import Path

from launchkit.errors import PackageNotFoundError
from launchkit.packages import PackageIndex

KINDS = ("msg", "srv", "action")
SEPARATOR = "---"
_PRIMITIVES = {
    "bool",
    "byte",
    "char",
    "float32",
    "float64",
    "int8",
    "uint8",
    "int16",
    "uint16",
    "int32",
    "uint32",
    "int64",
    "uint64",
    "string",
    "wstring",
}
_UNIT = re.compile(r"(\s*\[([^,\]]+)\])")


def interface_file(type_name: str, index: PackageIndex) -> Path | None:
    """The file of ``pkg/kind/Name`` in its package's share folder, or None."""
    package, kind, name = type_name.split("/")
    try:
        share = index.share_dir(package)
    except PackageNotFoundError:
        return None
    path = share / kind / f"{name}.{kind}"
    return path if path.is_file() else None


class Line:
    """One line of an interface file, read as ``ros2 interface show`` reads it."""

    def __init__(self, package: str, text: str) -> None:
        self.text = text.rstrip()
        self.is_comment = False
        self.trailing_comment = ""
        self.nested_type: str | None = None
        if self.text == SEPARATOR:
            return
        if self.text.startswith("#"):
            self.is_comment = bool(_comment(self.text.lstrip("#")))
            return
        code = self.text.replace("\t", " ")
        cut = code.find("#")
        if cut >= 0:
            comment, code = code[cut:].lstrip("#"), code[:cut]
            if code and not code.strip():  # an indented comment: neither comment nor field
                return
            self.trailing_comment = _comment(comment)
        type_text, _, rest = code.strip().partition(" ")
        if rest.strip() and "=" not in rest:  # a field (not a constant)
            self.nested_type = _nested_type(type_text, package)

    def shown(self, comments: bool) -> str | None:
        """The text to print (None: nothing), comments kept or cut."""
        if comments:
            return self.text
        if not self.text or self.is_comment:
            return None
        if self.trailing_comment:
            return self.text[: self.text.find(self.trailing_comment) - 1].strip()
        return self.text


def _comment(text: str) -> str:
    """A comment's text as rosidl_adapter keeps it: a single ``[unit]`` taken out, dedented;
    "" when nothing is left."""
    units = _UNIT.findall(text)
    if len(units) == 1:
        text = text.replace(units[0][0], "")
    return textwrap.dedent(text) if text else ""


def _nested_type(type_text: str, package: str) -> str | None:
    base = type_text.split("[", 1)[0].split("<=", 1)[0]
    if base in _PRIMITIVES:
        return None
    if "/" in base:
        owner, name = base.split("/", 1)
        return f"{owner}/msg/{name}"
    return f"{package}/msg/{base}"


def file_lines(path: Path, package: str) -> Iterator[Line]:
    """The lines of an interface file."""
    for text in path.read_text(encoding="utf-8").splitlines():
        yield Line(package, text)
