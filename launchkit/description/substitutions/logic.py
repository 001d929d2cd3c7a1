"""Boolean and comparison substitutions: ``not and or any all equals not-equals if``."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call
from launchkit.description.truth import BOOL_EXPECTED, bool_text, bool_value

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class _Boolean(Call):
    def truth(self, index: int, context: LaunchContext) -> bool:
        text = self.arg(index, context)
        value = bool_value(text)
        if value is None:
            raise self.fail(
                f"$({self.NAME}) got {text!r}, which is not a boolean", expected=BOOL_EXPECTED
            )
        return value


class Not(_Boolean):
    """``true`` when X is false."""

    NAME = "not"
    MIN_ARGS = 1
    MAX_ARGS = 1
    USAGE = "X"

    def perform(self, context: LaunchContext) -> str:
        """``true`` or ``false``."""
        return bool_text(not self.truth(0, context))


class And(_Boolean):
    """``true`` when A and B are true."""

    NAME = "and"
    MIN_ARGS = 2
    MAX_ARGS = 2
    USAGE = "A B"

    def perform(self, context: LaunchContext) -> str:
        """``true`` or ``false``."""
        return bool_text(self.truth(0, context) and self.truth(1, context))


class Or(_Boolean):
    """``true`` when A or B is true."""

    NAME = "or"
    MIN_ARGS = 2
    MAX_ARGS = 2
    USAGE = "A B"

    def perform(self, context: LaunchContext) -> str:
        """``true`` or ``false``."""
        return bool_text(self.truth(0, context) or self.truth(1, context))


class AnyOf(_Boolean):
    """``true`` when any argument is true (works from XML, unlike ROS 2 Jazzy)."""

    NAME = "any"
    MIN_ARGS = 1
    USAGE = "A [B ...]"

    def perform(self, context: LaunchContext) -> str:
        """``true`` or ``false``."""
        return bool_text(any(self.truth(i, context) for i in range(len(self.args))))


class AllOf(_Boolean):
    """``true`` when every argument is true (works from XML, unlike ROS 2 Jazzy)."""

    NAME = "all"
    MIN_ARGS = 1
    USAGE = "A [B ...]"

    def perform(self, context: LaunchContext) -> str:
        """``true`` or ``false``."""
        return bool_text(all(self.truth(i, context) for i in range(len(self.args))))


def values_equal(left: str, right: str) -> bool:
    """ROS's comparison: as booleans if both are boolean-like, as floats if both parse, else
    as strings."""
    bools = {"true": True, "1": True, "false": False, "0": False}
    lb, rb = bools.get(left.lower()), bools.get(right.lower())
    if lb is not None and rb is not None:
        return lb == rb
    try:
        return math.isclose(float(left), float(right))
    except ValueError:
        return left == right


class Equals(Call):
    """``true`` when A equals B (booleans, then numbers, then strings)."""

    NAME = "equals"
    MIN_ARGS = 2
    MAX_ARGS = 2
    USAGE = "A B"

    def perform(self, context: LaunchContext) -> str:
        """``true`` or ``false``."""
        return bool_text(values_equal(self.arg(0, context), self.arg(1, context)))


class NotEquals(Equals):
    """``true`` when A differs from B."""

    NAME = "not-equals"

    def perform(self, context: LaunchContext) -> str:
        """``true`` or ``false``."""
        return bool_text(not values_equal(self.arg(0, context), self.arg(1, context)))


class IfElse(_Boolean):
    """THEN when COND is true, else ELSE (default empty)."""

    NAME = "if"
    MIN_ARGS = 2
    MAX_ARGS = 3
    USAGE = "COND THEN [ELSE]"

    def perform(self, context: LaunchContext) -> str:
        """The chosen branch, performed."""
        if self.truth(0, context):
            return self.arg(1, context)
        return self.arg(2, context, "")
