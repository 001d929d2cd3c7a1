"""Stand-in for ``launch.utilities.type_utils``: typed values that may hold substitutions
(``normalize_typed_substitution`` when an action is built, ``perform_typed_substitution``
when it runs), and coercing text to ``int``, ``float``, ``bool``, ``str`` or a uniform list of
one of them by YAML's rules, with ROS's behaviour and error messages.
"""

from __future__ import annotations

import typing
from collections.abc import Iterable
from typing import Any

import yaml

from launchkit.frontend.python.utilities_api import (
    ensure_argument_type,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)
from launchkit.frontend.python.values import SubstitutionLike

ScalarTypesTuple = (int, float, bool, str)
# ROS names list types with typing.List; list[int] is accepted as well
ListTypesTuple = (typing.List[int], typing.List[float], typing.List[bool], typing.List[str])  # noqa: UP006
AllowedTypesTuple = ScalarTypesTuple + ListTypesTuple


def is_typing_list(data_type: Any) -> bool:
    """Whether ``data_type`` is ``typing.List`` or ``List[x]`` (or ``list[x]``)."""
    if data_type is typing.List:  # noqa: UP006
        return True
    origin = getattr(data_type, "__origin__", None)
    return hasattr(data_type, "__args__") and origin in (list, typing.List)  # noqa: UP006


def is_valid_scalar_type(data_type: Any) -> bool:
    """Whether ``data_type`` is one of ``int``, ``float``, ``bool``, ``str``."""
    return data_type in ScalarTypesTuple


def extract_type(data_type: Any) -> tuple[Any, bool]:
    """``(scalar type, is a list)`` of ``data_type``; ValueError for anything else."""
    scalar, is_list = data_type, False
    if is_typing_list(data_type) and getattr(data_type, "__args__", None):
        scalar, is_list = data_type.__args__[0], True
    if not is_valid_scalar_type(scalar):
        raise ValueError(f"Unrecognized data type: {data_type}")
    return scalar, is_list


def _element_type(data_type: Any) -> tuple[Any, bool]:
    """:func:`extract_type`, with None (no type asked for) as ``(None, True)``: a list of any
    allowed type."""
    return (None, True) if data_type is None else extract_type(data_type)


def is_instance_of_valid_type(value: Any, *, can_be_str: bool = False) -> bool:
    """Whether ``value`` is a scalar of an allowed type or a uniform list of one (an empty
    list is; ``can_be_str``: strings may be mixed in)."""
    if not isinstance(value, list):
        return isinstance(value, ScalarTypesTuple)
    if not value:
        return True
    member = next((type(item) for item in value if type(item) is not str), str)
    if member not in ScalarTypesTuple:
        return False
    accepted: tuple[type, ...] = (member, str) if can_be_str else (member,)
    return all(isinstance(item, accepted) for item in value)


def is_instance_of(value: Any, data_type: Any = None, *, can_be_str: bool = False) -> bool:
    """Whether ``value`` is an instance of ``data_type`` (None: of any allowed type)."""
    if data_type is None:
        return is_instance_of_valid_type(value, can_be_str=can_be_str)
    scalar, is_list = extract_type(data_type)
    accepted: tuple[type, ...] = (str, scalar) if can_be_str else (scalar,)
    if not is_list:
        return isinstance(value, accepted)
    return isinstance(value, list) and all(isinstance(item, accepted) for item in value)


def _as_yaml(value: str, error: str, can_be_str: bool) -> Any:
    if not value:
        return value
    try:
        output = yaml.safe_load(value)
    except Exception as failure:
        if can_be_str:
            return value
        raise ValueError(f"{error}: yaml.safe_load() failed\n{failure}") from None
    if not is_instance_of_valid_type(output, can_be_str=can_be_str):
        raise ValueError(f"{error}: output type is not allowed, got {type(output)}")
    return output


def coerce_to_type(value: str, data_type: Any = None, *, can_be_str: bool = False) -> Any:
    """``value`` (text) as ``data_type``; None: the best YAML reading. ValueError when it is
    not one; ``can_be_str``: the text itself instead."""
    ensure_argument_type(value, str, "value", "coerce_to_type")
    if data_type is None:
        return _as_yaml(value, f"Failed to convert '{value}' using yaml rules", can_be_str)
    scalar, is_list = extract_type(data_type)
    accepted: Any = (str, scalar) if can_be_str else scalar
    if is_list:
        error = f"Cannot convert value '{value}' to a list of '{accepted}'"
        output = _as_yaml(value, error, can_be_str)
        if not isinstance(output, list):
            raise ValueError(error)
        if not all(isinstance(item, accepted) for item in output):
            raise ValueError(f"{error}, got {output}")
        return output
    if scalar is str:
        return value
    if scalar in (int, float):
        try:
            return scalar(value)
        except ValueError:
            if can_be_str:
                return value
            raise
    value = {"1": "true", "0": "false"}.get(value, value)  # bool: 1 and 0 as well
    output = _as_yaml(value, f"Failed to convert '{value}' to '{scalar}'", can_be_str)
    if isinstance(output, accepted):
        return output
    raise ValueError(f"Cannot convert value '{value}' to '{scalar}'")


def coerce_list(value: list[str], data_type: Any = None, *, can_be_str: bool = False) -> Any:
    """A list of texts, each coerced to ``data_type``; the result must be uniform."""
    ensure_argument_type(value, list, "value", "coerce_list")
    output = [coerce_to_type(item, data_type, can_be_str=can_be_str) for item in value]
    if not is_instance_of_valid_type(output, can_be_str=can_be_str):
        raise ValueError(f"cannot convert value to {data_type}. Got value=`{value}`")
    return output


def get_typed_value(value: Any, data_type: Any, *, can_be_str: bool = False) -> Any:
    """A text, or a list of texts, coerced to ``data_type``."""
    if not isinstance(value, list):
        return coerce_to_type(value, data_type, can_be_str=can_be_str)
    if data_type is not None:
        data_type, is_list = extract_type(data_type)
        if not is_list:
            raise TypeError(
                f"Cannot convert input '{value}' of type '{type(value)}' to '{data_type}'"
            )
    return coerce_list(value, data_type, can_be_str=can_be_str)


def is_substitution(x: Any) -> bool:
    """Whether ``x`` is a substitution, or a non-empty list of substitutions and strings with
    at least one substitution."""
    if isinstance(x, SubstitutionLike):
        return True
    if not isinstance(x, Iterable) or isinstance(x, str):
        return False
    items = list(x)
    return (
        bool(items)
        and all(isinstance(item, SubstitutionLike | str) for item in items)
        and any(isinstance(item, SubstitutionLike) for item in items)
    )


def _list_kind(value: Iterable[Any]) -> set[type]:
    kinds: set[type] = set()
    for item in value:
        if isinstance(item, ScalarTypesTuple):
            kinds.add(type(item))
        elif is_substitution(item):
            kinds.add(SubstitutionLike)
        else:
            raise TypeError(
                "value is a list, and one of the items is not a scalar, a Substitution "
                f"or a list of substitutions. Got value='{value}'"
            )
    return kinds


def normalize_typed_substitution(value: Any, data_type: Any) -> Any:
    """A scalar, a substitution or a list mixing both, normalized for
    :func:`perform_typed_substitution` (TypeError when it cannot become ``data_type``)."""
    if isinstance(value, ScalarTypesTuple):
        if not is_instance_of(value, data_type):
            raise TypeError(f"value='{value}' is not an instance of {data_type}")
        return value
    if is_substitution(value):
        return normalize_to_list_of_substitutions(value)
    if not isinstance(value, Iterable):
        raise TypeError(
            "value should be either a scalar, a substitutions, or a mixed list of scalars and "
            f"substitutions. Got `value={value}` of type `{type(value)}`. "
        )
    kinds = _list_kind(value)
    data_type, is_list = _element_type(data_type)
    if not is_list:
        raise TypeError(
            "The provided value resolves to a list, though the required type is a scalar. "
            f"Got value='{value}', data_type='{data_type}'."
        )

    def normalized(item: Any) -> Any:
        return normalize_to_list_of_substitutions(item) if is_substitution(item) else item

    if kinds == {SubstitutionLike}:
        return [normalize_to_list_of_substitutions(item) for item in value]
    for kind, allowed in ((str, {str}), (bool, {bool}), (int, {int}), (float, {int, float})):
        if kinds <= allowed | {SubstitutionLike}:
            if data_type not in (None, kind):
                raise TypeError(
                    f"Got a list of '{kind}', expected a list of '{data_type}'. value='{value}'"
                )
            if kind is float:
                return [
                    normalized(item) if is_substitution(item) else float(item) for item in value
                ]
            return [normalized(item) for item in value]
    raise TypeError(f"Input value is not an acceptable 'SomeValueType'.Got value='{value}'")


def is_normalized_substitution(x: Any) -> bool:
    """Whether ``x`` is a non-empty list of substitutions."""
    return isinstance(x, list) and bool(x) and all(isinstance(i, SubstitutionLike) for i in x)


def perform_typed_substitution(context: Any, value: Any, data_type: Any) -> Any:
    """A value :func:`normalize_typed_substitution` made, performed in ``context`` and
    coerced to ``data_type``."""
    if isinstance(value, ScalarTypesTuple):
        if data_type is not None and not is_instance_of(value, data_type):
            raise TypeError(f"value=`{value}` is a scalar and not an instance of `{data_type}`")
        return value
    if is_normalized_substitution(value):
        return coerce_to_type(perform_substitutions(context, value), data_type)
    if not isinstance(value, list):
        raise TypeError(
            f"Input value is not an acceptable 'NormalizedValueType'.Got value='{value}'"
        )
    scalar, is_list = _element_type(data_type)
    if not is_list:
        raise ValueError(
            "The input value is a list, cannot convert it to a scalar. "
            f"Got value='{value}', expected type {scalar}."
        )
    output = [
        coerce_to_type(perform_substitutions(context, item), scalar)
        if is_normalized_substitution(item)
        else item
        for item in value
    ]
    if not is_instance_of(output, data_type):
        raise ValueError(
            "The output list does not match the expected type "
            f"Got value='{value}', expected type {scalar}."
            if scalar is not None
            else "The output list is not uniform"
        )
    return output
