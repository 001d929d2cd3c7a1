"""Hypothesis strategies for hostile launch files and params files: generated from the
frontends' vocabulary (tags, attributes, substitutions, YAML anchors), in several encodings,
and byte-level mutations of real files.

Nothing generated runs a program: ``$(command)`` is left out of the vocabulary and a mutant that
spells it is discarded (``check`` evaluates the file, and would run it), and ``check`` starts
no process.
"""

from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import quoteattr

import yaml
from hypothesis import assume
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[2]

TAGS = [
    "launch", "let", "arg", "executable", "node", "group", "include", "log", "timer", "set_env",
    "unset_env", "append_env", "push_ros_namespace", "param", "remap", "env", "set_parameter",
    "set_remap", "node_container", "composable_node", "load_composable_node", "reset_env",
]  # fmt: skip
ATTRIBUTES = [
    "name", "value", "default", "cmd", "pkg", "exec", "file", "if", "unless", "message",
    "period", "namespace", "ns", "from", "output", "respawn", "scoped", "description",
    "choices", "args", "launch-prefix", "cwd", "sep", "type", "level", "prepend", "plugin",
]  # fmt: skip
#: Every substitution but ``command`` (which would run a program during the check).
SUBSTITUTIONS = [
    "var", "env", "optenv", "dirname", "filename", "find-pkg-share", "find-pkg-prefix",
    "find-exec", "exec-in-pkg", "anon", "eval", "not", "and", "or", "equals", "not-equals",
]  # fmt: skip
PIECES = [
    "$(", ")", " ", "'", '"', "\\", "$", "(", "x", "true", "false", "1", "-2.5", "/", "a b",
    "$(var x)", "$(var x y)", "$(eval '1+1')", "$(dirname)", "&", "<", "\x1b", "\r", "\n",
    "é", "\u202e", "\U0001f600", "\t", "{", "}", ":", "*", "**", "~",
]  # fmt: skip

value_text = st.lists(
    st.one_of(
        st.sampled_from(PIECES),
        st.sampled_from(SUBSTITUTIONS),
        st.text(max_size=6),
    ),
    max_size=14,
).map("".join)


@st.composite
def element(draw: st.DrawFn, depth: int = 0) -> str:
    """One XML element of the launch vocabulary, with children up to a few levels."""
    tag = draw(st.sampled_from(TAGS) if draw(st.integers(0, 9)) else st.text(min_size=1))
    names = draw(st.lists(st.sampled_from(ATTRIBUTES), max_size=5, unique=True))
    attributes = "".join(f" {name}={quoteattr(draw(value_text))}" for name in names)
    children = draw(st.lists(element(depth + 1), max_size=4)) if depth < 3 else []
    if not children and draw(st.booleans()):
        return f"<{tag}{attributes}/>"
    return f"<{tag}{attributes}>{''.join(children)}</{tag}>"


@st.composite
def xml_launch_file(draw: st.DrawFn) -> bytes:
    """An XML launch file in one of several encodings (declared or not, rightly or not)."""
    body = "".join(draw(st.lists(element(1), max_size=6)))
    if draw(st.integers(0, 4)) == 0:  # deep nesting: of elements, of substitutions
        depth = draw(st.integers(0, 300))
        tag = draw(st.sampled_from(["group", "timer", "launch", "let"]))
        body = f"<{tag}>" * depth + body + f"</{tag}>" * depth
        nested = "$(var " * depth + "x" + ")" * depth
        body += f"<let name='x' value={quoteattr(nested)}/>"
    text = f"<launch>\n{body}\n</launch>\n"
    encoding = draw(st.sampled_from(["utf-8", "utf-16", "latin-1", "utf-8-sig", "cp1252"]))
    declare = draw(st.sampled_from([None, encoding, "UTF-8", "UTF-16", "ISO-8859-1", "bogus"]))
    if declare is not None:
        text = f'<?xml version="1.0" encoding="{declare}"?>\n' + text
    return text.encode(encoding, errors="xmlcharrefreplace")


def yaml_entity(depth: int = 0) -> st.SearchStrategy[object]:
    """One YAML launch action: ``{tag: {attribute: value, children: [...]}}``."""
    scalar = st.one_of(value_text, st.integers(), st.floats(allow_nan=True), st.booleans())
    attributes = st.dictionaries(st.sampled_from(ATTRIBUTES), scalar, max_size=5)
    if depth < 3:
        children = st.lists(st.deferred(lambda: yaml_entity(depth + 1)), max_size=3)
        attributes = st.builds(lambda a, c: {**a, "children": c} if c else a, attributes, children)
    return st.dictionaries(st.sampled_from(TAGS), attributes, min_size=1, max_size=1)


@st.composite
def yaml_launch_file(draw: st.DrawFn) -> bytes:
    """A YAML launch file, sometimes with anchors and aliases spliced into its text."""
    actions = draw(st.lists(yaml_entity(), max_size=6))
    text = yaml.safe_dump({"launch": actions}, allow_unicode=True)
    return draw(spliced(text.encode()))


ANCHOR_PIECES = [
    b"&a ", b"*a", b"&b [*a, *a, *a]", b"<<: *a", b"!!python/object:os.system", b"!!binary",
    b"---\n", b"[", b"{", b"? ", b"1:0:0:0:0", b"0x" + b"f" * 40, b"\xff\xfe", b"\xe9",
    b"\x00", b"%YAML 1.1\n", b"|\n  ", b'"\\x1b"', b"9" * 2000,
]  # fmt: skip


@st.composite
def spliced(draw: st.DrawFn, data: bytes) -> bytes:
    """``data`` with a few hostile pieces inserted, bytes flipped or removed."""
    out = bytearray(data)
    for _ in range(draw(st.integers(0, 4))):
        at = draw(st.integers(0, len(out)))
        operation = draw(st.integers(0, 3))
        if operation == 0:
            out[at:at] = draw(st.sampled_from(ANCHOR_PIECES))
        elif operation == 1:
            out[at:at] = draw(st.binary(min_size=1, max_size=4))
        elif operation == 2 and out:
            del out[at : at + draw(st.integers(1, 20))]
        elif out:
            out[min(at, len(out) - 1)] = draw(st.integers(0, 255))
    result = bytes(out)
    assume(b"command" not in result)
    return result


def seeds(*patterns: str) -> list[bytes]:
    """The repository's files matching ``patterns`` (relative to its root), as bytes."""
    found = sorted({p for pattern in patterns for p in ROOT.glob(pattern)})
    texts = [path.read_bytes() for path in found]
    return [text for text in texts if b"command" not in text]


def mutant_of(files: list[bytes]) -> st.SearchStrategy[bytes]:
    """A byte-level mutant of one of ``files``."""
    return st.sampled_from(files).flatmap(spliced)


@st.composite
def params_file(draw: st.DrawFn) -> bytes:
    """A ROS params file: nested parameters under node patterns, then spliced."""
    leaf = st.one_of(
        value_text,
        st.integers(),
        st.floats(allow_nan=True),
        st.booleans(),
        st.lists(st.integers(), max_size=4),
        st.none(),
    )
    tree = st.recursive(
        leaf, lambda inner: st.dictionaries(st.sampled_from(ATTRIBUTES), inner, max_size=3)
    )
    sections = draw(
        st.dictionaries(
            st.sampled_from(["/**", "/ns/node", "node", "/*/node", "/other", "ros__parameters"]),
            st.one_of(st.fixed_dictionaries({"ros__parameters": tree}), tree),
            max_size=3,
        )
    )
    return draw(spliced(yaml.safe_dump(sections, allow_unicode=True).encode()))
