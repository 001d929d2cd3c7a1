"""The ``condition`` attribute of package.xml (format 3, REP 149): ``$ROS_VERSION == 2``.

The grammar is catkin_pkg's: a comparison is two terms (``$NAME``, a variable, or a bare word of
letters, digits, ``_`` and ``-``) around ``==``, ``!=``, ``<``, ``<=``, ``>`` or ``>=``, compared
as strings; comparisons combine with ``and`` (binding tighter) and ``or``, and group with
parentheses. An unset variable is the empty string.
"""

from __future__ import annotations

import operator
import re
from collections.abc import Callable, Mapping

#: What a package is built for when the environment does not say: launchkit stands in for
#: ROS 2 Jazzy on Python 3.
DEFAULT_CONTEXT = {"ROS_VERSION": "2", "ROS_DISTRO": "jazzy", "ROS_PYTHON_VERSION": "3"}

_COMPARISONS: dict[str, Callable[[str, str], bool]] = {
    "==": operator.eq,
    "!=": operator.ne,
    "<=": operator.le,
    "<": operator.lt,
    ">=": operator.ge,
    ">": operator.gt,
}
_TOKEN = re.compile(r"\s*(==|!=|<=|>=|<|>|\(|\)|\$[A-Za-z0-9_]+|[A-Za-z0-9_-]+)")


class ConditionError(ValueError):
    """A condition that does not parse; the message says where and what was expected."""


def condition_context(environ: Mapping[str, str]) -> dict[str, str]:
    """The variables a condition sees: the environment, with ROS 2 Jazzy's defaults for
    ``ROS_VERSION``, ``ROS_DISTRO`` and ``ROS_PYTHON_VERSION`` where it has none."""
    return {**DEFAULT_CONTEXT, **{k: v for k, v in environ.items() if v}}


def evaluate(condition: str, context: Mapping[str, str]) -> bool:
    """Whether ``condition`` holds in ``context``; :class:`ConditionError` if malformed."""
    tokens = _tokenize(condition)
    parser = _Parser(tokens, context, condition)
    value = parser.disjunction()
    if parser.position != len(tokens):
        raise ConditionError(f"unexpected {tokens[parser.position]!r} in condition {condition!r}")
    return value


def _tokenize(text: str) -> list[str]:
    tokens: list[str] = []
    position = 0
    while position < len(text):
        if text[position:].strip() == "":
            break
        match = _TOKEN.match(text, position)
        if match is None:
            raise ConditionError(
                f"unexpected {text[position:].strip()[0]!r} in condition {text!r} "
                "(expected $VARIABLE, a word, a comparison, and, or, parentheses)"
            )
        tokens.append(match.group(1))
        position = match.end()
    return tokens


class _Parser:
    """Recursive descent over the tokens: ``or`` of ``and`` of comparisons."""

    def __init__(self, tokens: list[str], context: Mapping[str, str], text: str) -> None:
        self.tokens = tokens
        self.context = context
        self.text = text
        self.position = 0

    def _peek(self) -> str | None:
        return self.tokens[self.position] if self.position < len(self.tokens) else None

    def _take(self) -> str:
        token = self._peek()
        if token is None:
            raise ConditionError(f"condition {self.text!r} ends too early")
        self.position += 1
        return token

    def disjunction(self) -> bool:
        return any(self._joined("or", self.conjunction))

    def conjunction(self) -> bool:
        return all(self._joined("and", self.comparison))

    def _joined(self, word: str, operand: Callable[[], bool]) -> list[bool]:
        # every operand is evaluated (no short cut), so a malformed right side is reported
        values = [operand()]
        while self._peek() == word:
            self._take()
            values.append(operand())
        return values

    def comparison(self) -> bool:
        if self._peek() == "(":
            self._take()
            value = self.disjunction()
            if self._take() != ")":
                raise ConditionError(f"missing ')' in condition {self.text!r}")
            return value
        left = self._term()
        compare = _COMPARISONS.get(self._take())
        if compare is None:
            raise ConditionError(
                f"expected a comparison (==, !=, <, <=, >, >=) in condition {self.text!r}"
            )
        return compare(left, self._term())

    def _term(self) -> str:
        token = self._take()
        if token.startswith("$"):
            return str(self.context.get(token[1:], ""))
        if token in _COMPARISONS or token in ("(", ")"):
            raise ConditionError(f"expected $VARIABLE or a word in condition {self.text!r}")
        return token
