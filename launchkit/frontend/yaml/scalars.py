"""YAML scalars as text and in error messages."""

from __future__ import annotations

import math

from launchkit.safe_yaml import Node


def describe(node: Node) -> str:
    """What a YAML value is, for errors: ``the float 1.5``, ``a list``, ``empty``."""
    if node.kind == "map":
        return "a mapping"
    if node.kind == "seq":
        return "a list"
    value = node.value
    if value is None:
        return "empty"
    if isinstance(value, str):
        return f"the text {value!r}"
    kind = {bool: "boolean", int: "integer", float: "float"}.get(type(value), type(value).__name__)
    return f"the {kind} {node.written or node_text(node)}"


def node_text(node: Node) -> str:
    """A typed scalar as text that YAML's rules read back as the same value."""
    value = node.value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isnan(value):
            return ".nan"
        if math.isinf(value):
            return ".inf" if value > 0 else "-.inf"
        text = repr(value)
        # PyYAML reads "1e+20" as text: YAML 1.1 floats need a dot
        return text if "." in text or "e" not in text else text.replace("e", ".0e", 1)
    return str(value)


def quoted(text: str) -> str:
    """``text`` as a double-quoted YAML scalar that reads back as exactly ``text``."""
    out = []
    for char in text:
        code = ord(char)
        if char in '"\\':
            out.append("\\" + char)
        elif code < 0x20 or 0x7F <= code <= 0x9F or code in (0x2028, 0x2029, 0xFEFF):
            out.append(f"\\u{code:04x}")  # line breaks YAML would fold, control characters
        else:
            out.append(char)
    return '"' + "".join(out) + '"'
