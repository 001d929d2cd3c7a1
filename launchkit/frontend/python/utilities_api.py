"""Stand-in for ``launch.utilities``: the helpers third-party launch code calls (nav2_common's
``RewrittenYaml`` normalizes its arguments and performs them with these), with ROS's behaviour
and error messages.
"""

from __future__ import annotations

import inspect
from collections.abc import Iterable
from typing import Any

from launchkit.description.actions.base import Action
from launchkit.frontend.python.launch_substitutions import TextSubstitution
from launchkit.frontend.python.values import SubstitutionLike, context_view

_TYPE_ERROR = "{}xpected '{}' to be one of [{}], but got '{}' of type '{}'"


def isclassinstance(obj: Any) -> bool:
    """``launch.utilities.isclassinstance``: whether ``obj`` is an instance of a class."""
    return hasattr(obj, "__class__")


def is_a(obj: Any, entity_type: Any) -> bool:
    """``launch.utilities.is_a``: ``isinstance``, refusing a ``entity_type`` that is not a
    class (RuntimeError, as ROS)."""
    if not isclassinstance(obj):
        raise RuntimeError(f"obj '{obj}' is not a class instance")
    if not inspect.isclass(entity_type):
        raise RuntimeError(f"entity_type '{obj}' is not a class")  # ROS names obj here too
    return isinstance(obj, entity_type)


def is_a_subclass(obj: Any, entity_type: Any) -> bool:
    """``launch.utilities.is_a_subclass``: an instance of ``entity_type``, or a subclass."""
    if is_a(obj, entity_type):
        return True
    try:
        return issubclass(obj, entity_type)
    except TypeError:
        return False


def ensure_argument_type(
    argument: Any, types: Any, argument_name: str, caller: str | None = None
) -> None:
    """``launch.utilities.ensure_argument_type``: TypeError unless ``argument`` is an instance
    of one of ``types`` (a type or an iterable of types)."""
    own = "'ensure_argument_type()' e"
    if not isinstance(types, Iterable | type):
        kinds = "type, collections.abc.Iterable of type"
        raise TypeError(_TYPE_ERROR.format(own, "types", kinds, types, type(types)))
    if not isinstance(argument_name, str):
        raise TypeError(
            _TYPE_ERROR.format(own, "argument_name", "str", argument_name, type(argument_name))
        )
    if caller is not None and not isinstance(caller, str):
        raise TypeError(_TYPE_ERROR.format(own, "caller", "str, None", caller, type(caller)))
    candidates = list(types) if isinstance(types, Iterable) else [types]
    if any(isinstance(argument, kind) for kind in candidates):
        return
    who = "E" if caller is None else f"'{caller}' e"
    names = ", ".join(str(kind) for kind in candidates)
    raise TypeError(_TYPE_ERROR.format(who, argument_name, names, argument, type(argument)))


def normalize_to_list_of_substitutions(subs: Any) -> list[Any]:
    """``launch.utilities.normalize_to_list_of_substitutions``: a str, a substitution or an
    iterable of both as a list of substitutions (text as ``TextSubstitution``)."""
    if isinstance(subs, str):
        return [TextSubstitution(text=subs)]
    if is_a_subclass(subs, SubstitutionLike):
        return [subs]

    def one(item: Any) -> Any:
        if isinstance(item, SubstitutionLike):
            return item
        if isinstance(item, str):
            return TextSubstitution(text=item)
        raise TypeError(
            f"Failed to normalize given item of type '{type(item)}', when only "
            "'str' or 'launch.Substitution' were expected."
        )

    return [one(item) for item in subs]


def normalize_to_list_of_entities(entities: Iterable[Any]) -> list[Any]:
    """``launch.utilities.normalize_to_list_of_entities``: actions, and iterables of them,
    as one flat list (one level, as ROS)."""
    flat: list[Any] = []
    for entity in entities:
        if isinstance(entity, Action):
            flat.append(entity)
        else:
            flat.extend(entity)
    return flat


def perform_substitutions(context: Any, subs: Iterable[Any]) -> str:
    """``launch.utilities.perform_substitutions``: each substitution performed in
    ``context``, concatenated (a plain str is refused, as in ROS)."""
    view = context_view(context)
    return "".join([sub.perform(view) for sub in subs])
