"""What ``wait_output`` accepts: a substring, a compiled regex, or a predicate on a line."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Union

Matcher = Union[str, "re.Pattern[str]", Callable[[str], bool]]


def compile_matcher(matcher: Matcher) -> tuple[Callable[[str], bool], str]:
    """A line predicate for ``matcher`` and words for it in failure messages."""
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
        "a re.Pattern or a callable taking a line"
    )
