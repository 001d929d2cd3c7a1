"""Which topics a recorder or player takes: rosbag2's topic filter options."""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from launchkit.bag.metadata import BagError


def absolute(topic: str) -> str:
    """A topic name as the graph and bags hold it (``chatter`` -> ``/chatter``)."""
    return topic if topic.startswith("/") else "/" + topic


def is_hidden(topic: str) -> bool:
    """ROS's hidden names: a token starting with ``_`` (``/_private``, ``/a/_b``)."""
    return any(token.startswith("_") for token in topic.split("/"))


def compile_regex(pattern: str, option: str) -> re.Pattern[str] | None:
    """``pattern`` compiled, None if empty; a bad one is a user error naming the option."""
    if not pattern:
        return None
    try:
        return re.compile(pattern)
    except re.error as exc:
        raise BagError(f"{option} {pattern!r}: {exc}", expected="a regular expression") from None


@dataclass(frozen=True)
class TopicSelection:
    """``-a``, topic names, ``--regex``, the exclusions and ``--include-hidden-topics``.

    A regular expression matches anywhere in the name (rosbag2 searches, it does not anchor).
    Topics named explicitly are taken even when hidden.
    """

    all: bool = False
    topics: frozenset[str] = frozenset()
    regex: re.Pattern[str] | None = None
    exclude_regex: re.Pattern[str] | None = None
    exclude_topics: frozenset[str] = frozenset()
    include_hidden: bool = False

    @classmethod
    def build(
        cls,
        *,
        all_topics: bool = False,
        topics: Iterable[str] = (),
        regex: str = "",
        exclude_regex: str = "",
        exclude_topics: Iterable[str] = (),
        include_hidden: bool = False,
    ) -> TopicSelection:
        """A selection from command-line values (names made absolute, regexes compiled)."""
        return cls(
            all=all_topics,
            topics=frozenset(absolute(t) for t in topics),
            regex=compile_regex(regex, "--regex"),
            exclude_regex=compile_regex(exclude_regex, "--exclude-regex"),
            exclude_topics=frozenset(absolute(t) for t in exclude_topics),
            include_hidden=include_hidden,
        )

    @property
    def empty(self) -> bool:
        """True when nothing was asked for (rosbag2 refuses to record then)."""
        return not (self.all or self.topics or self.regex)

    def wants(self, topic: str) -> bool:
        """Whether ``topic`` is taken."""
        if topic in self.exclude_topics:
            return False
        if self.exclude_regex is not None and self.exclude_regex.search(topic):
            return False
        if topic in self.topics:
            return True
        if is_hidden(topic) and not self.include_hidden:
            return False
        return self.all or bool(self.regex is not None and self.regex.search(topic))
