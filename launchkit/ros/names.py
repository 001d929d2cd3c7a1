"""ROS 2 name validation, expansion (``/abs``, ``rel``, ``~/private``, ``{node}``) and remapping."""

from __future__ import annotations

import re
from dataclasses import dataclass

from launchkit.errors import UserError

_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*|[A-Za-z0-9_]+")
_NODE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


class InvalidNameError(UserError):
    """A node, namespace, topic or service name that ROS 2 would reject."""


def validate_node_name(name: str) -> str:
    """``name`` if it is a valid node name (letters, digits, ``_``; not starting with a digit)."""
    if not _NODE_NAME.fullmatch(name):
        raise InvalidNameError(
            f"invalid node name {name!r}",
            expected="letters, digits and '_', not starting with a digit",
        )
    return name


def normalize_namespace(namespace: str) -> str:
    """A namespace made absolute (``""`` and ``"/"`` are the root ``/``), validated."""
    if not namespace or namespace == "/":
        return "/"
    if not namespace.startswith("/"):
        namespace = "/" + namespace
    namespace = namespace.rstrip("/")
    _validate_absolute(namespace, "namespace")
    return namespace


def node_fqn(name: str, namespace: str) -> str:
    """The fully qualified node name: ``/ns/name``."""
    return f"{namespace.rstrip('/')}/{name}"


def expand(name: str, node_name: str, namespace: str, kind: str = "topic") -> str:
    """Expand a topic or service name for a node, exactly as rcl does.

    ``/abs`` stays, ``rel`` goes under the node's namespace, ``~`` is the node's own name,
    ``{node}`` and ``{ns}`` (``{namespace}``) are substituted.
    """
    if not name:
        raise InvalidNameError(f"empty {kind} name", expected=f"a {kind} name such as 'chatter'")
    ns = namespace.rstrip("/")
    fqn = f"{ns}/{node_name}"
    if name == "~":
        expanded = fqn
    elif name.startswith("~/"):
        expanded = fqn + name[1:]
    elif name.startswith("~"):
        raise InvalidNameError(f"invalid {kind} name {name!r}", expected="'~' or '~/name'")
    else:
        expanded = name
    expanded = (
        expanded.replace("{node}", node_name)
        .replace("{namespace}", ns or "/")
        .replace("{ns}", ns or "/")
    )
    if not expanded.startswith("/"):
        expanded = f"{ns}/{expanded}"
    _validate_absolute(expanded, kind)
    return expanded


def _validate_absolute(name: str, kind: str) -> None:
    if name == "/":
        return
    tokens = name[1:].split("/")
    if name.endswith("/") or any(not t or not _TOKEN.fullmatch(t) for t in tokens):
        raise InvalidNameError(
            f"invalid {kind} name {name!r}",
            expected="tokens of letters, digits and '_' separated by single '/'",
        )
    if any(t[0].isdigit() for t in tokens):
        raise InvalidNameError(
            f"invalid {kind} name {name!r}", expected="no token starting with a digit"
        )


@dataclass(frozen=True)
class RemapRule:
    """One ``[node:]from:=to`` rule from ``--ros-args -r``."""

    node: str | None
    src: str
    dst: str

    @classmethod
    def parse(cls, text: str) -> RemapRule:
        """Parse ``from:=to`` or ``node:from:=to``."""
        src, sep, dst = text.partition(":=")
        if not sep or not src or not dst:
            raise InvalidNameError(
                f"invalid remapping rule {text!r}", expected="'from:=to' or 'node:from:=to'"
            )
        node: str | None = None
        if ":" in src:
            node, _, src = src.partition(":")
        return cls(node, src, dst)

    def applies_to(self, node_name: str) -> bool:
        """Whether this rule is for every node or for ``node_name`` (the name before remap)."""
        return self.node is None or self.node == node_name


def remap_node_name(rules: list[RemapRule], name: str) -> str:
    """The node name after ``__node:=`` / ``__name:=`` rules (first matching rule wins)."""
    for rule in rules:
        if rule.src in ("__node", "__name") and rule.applies_to(name):
            return validate_node_name(rule.dst)
    return name


def remap_namespace(rules: list[RemapRule], name: str, namespace: str) -> str:
    """The namespace after ``__ns:=`` rules."""
    for rule in rules:
        if rule.src == "__ns" and rule.applies_to(name):
            return normalize_namespace(rule.dst)
    return namespace


def remap_name(
    rules: list[RemapRule],
    expanded: str,
    original_node_name: str,
    node_name: str,
    namespace: str,
    kind: str = "topic",
) -> str:
    """Apply the first rule whose expanded ``from`` equals ``expanded``; return the result."""
    for rule in rules:
        if rule.src.startswith("__") or not rule.applies_to(original_node_name):
            continue
        if expand(rule.src, node_name, namespace, kind) == expanded:
            return expand(rule.dst, node_name, namespace, kind)
    return expanded
