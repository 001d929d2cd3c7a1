"""What ``wait_output`` accepts: a substring, a compiled regex, a predicate on a line, or
:func:`in_order` of those for a sequence of lines."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Union


class InOrder:
    """Lines matching each of several matchers, in that order (other lines may come between);
    made by :func:`in_order`."""

    def __init__(self, *matchers: Matcher) -> None:
        if not matchers:
            raise ValueError("in_order() needs at least one matcher")
        self.matchers = matchers


Matcher = Union[str, "re.Pattern[str]", Callable[[str], bool], InOrder]


def in_order(*matchers: Matcher) -> InOrder:
    """A matcher for a sequence: ``wait_output(in_order("starting", re.compile("ready")))``
    returns the line that completes it."""
    return InOrder(*matchers)


def compile_matcher(matcher: Matcher) -> tuple[Callable[[str], bool], str]:
    """A line predicate for ``matcher`` and words for it in failure messages. The predicate
    must see each line once, in order (an :func:`in_order` predicate counts its progress)."""
    if isinstance(matcher, InOrder):
        return _sequence(matcher)
    if isinstance(matcher, str):
        text = matcher
        return (lambda line: text in line), f"a line containing {text!r}"
    if isinstance(matcher, re.Pattern):
        pattern = matcher
        return (lambda line: pattern.search(line) is not None), (
            f"a line matching /{pattern.pattern}/"
        )
    if callable(matcher):
        name = getattr(matcher, "__name__", repr(matcher))
        return (lambda line: bool(matcher(line))), f"a line accepted by {name}"
    raise TypeError(
        f"cannot match output with {matcher!r}: expected a str (substring), "
        "a re.Pattern, a callable taking a line, or in_order(...) of those"
    )


def _sequence(sequence: InOrder) -> tuple[Callable[[str], bool], str]:
    parts = [compile_matcher(matcher) for matcher in sequence.matchers]
    found = 0

    def accepts(line: str) -> bool:
        nonlocal found
        if found < len(parts) and parts[found][0](line):
            found += 1
        return found == len(parts)

    def words() -> str:
        steps = ", then ".join(words for _, words in parts)
        return f"{steps} (in this order)"

    return accepts, words()
