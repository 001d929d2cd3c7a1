"""Turning a ``cmd``/``args`` attribute into argv, quote-aware across substitutions.

Literal text follows POSIX shell word rules (whitespace splits, quotes group, ``\\`` escapes);
text produced by a substitution is never split and never re-interpreted, but it stays inside
whatever word or quotes surround it. So ``sh -c 'echo $(var msg)'`` is three words, and
``printf $(var s)`` passes ``s`` as one argument even when it contains spaces (ROS 2 fails on
the first and agrees on the second).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Text, Value
from launchkit.errors import RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext
    from launchkit.errors import Location


def split_command(value: Value, context: LaunchContext, location: Location | None) -> list[str]:
    """Perform ``value`` and split it into argv words."""
    pieces = [(p.text, True) if isinstance(p, Text) else (p.perform(context), False) for p in value]
    return split_pieces(pieces, location)


def split_pieces(pieces: list[tuple[str, bool]], location: Location | None = None) -> list[str]:
    """Split ``(text, is_literal)`` pieces into words; only literal text is lexed."""
    words: list[str] = []
    word: list[str] = []
    in_word = False
    quote = ""
    for text, is_literal in pieces:
        if not is_literal:
            word.append(text)
            in_word = True
            continue
        index = 0
        while index < len(text):
            char = text[index]
            if quote == "'":
                if char == "'":
                    quote = ""
                else:
                    word.append(char)
            elif quote == '"':
                if char == '"':
                    quote = ""
                elif char == "\\" and index + 1 < len(text) and text[index + 1] in '"\\$`':
                    index += 1
                    word.append(text[index])
                else:
                    word.append(char)
            elif char in "'\"":
                quote = char
                in_word = True
            elif char == "\\" and index + 1 < len(text):
                index += 1
                word.append(text[index])
                in_word = True
            elif char.isspace():
                if in_word:
                    words.append("".join(word))
                    word.clear()
                    in_word = False
            else:
                word.append(char)
                in_word = True
            index += 1
    if quote:
        raise RuntimeLaunchError(
            f"unbalanced {quote} quote in command", location, expected=f"a closing {quote}"
        )
    if in_word:
        words.append("".join(word))
    return words
