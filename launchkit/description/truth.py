"""How launch files spell true and false.

Two rules, as in ROS 2 launch: ``if``/``unless`` accept only ``true``, ``1``, ``false``, ``0``
(any case, surrounding space ignored); typed boolean attributes and the boolean substitutions
also accept YAML's spellings (``yes``/``no``/``on``/``off``).
"""

from __future__ import annotations

CONDITION_EXPECTED = "one of true, 1, false, 0"
BOOL_EXPECTED = "a boolean: true/false, 1/0, yes/no, on/off"

_TRUE = {"true", "1", "yes", "on", "y"}
_FALSE = {"false", "0", "no", "off", "n"}


def condition_value(text: str) -> bool | None:
    """``if``/``unless`` rule: True, False, or None when ``text`` is not a valid condition."""
    value = text.strip().lower()
    if value in ("true", "1"):
        return True
    if value in ("false", "0"):
        return False
    return None


def bool_value(text: str) -> bool | None:
    """Typed-attribute rule (YAML booleans): True, False, or None when not a boolean."""
    value = text.strip().lower()
    if value in _TRUE:
        return True
    if value in _FALSE:
        return False
    return None


def bool_text(value: bool) -> str:
    """``true`` or ``false``, as boolean substitutions return them."""
    return "true" if value else "false"
