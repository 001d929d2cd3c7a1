"""Turning what Python launch files pass around (str, substitutions, lists of both) into
launchkit values, finding the line of the launch file that built an action, and running the
file's own functions later (OpaqueFunction, event handler callbacks) with the stand-in modules
installed again."""

from __future__ import annotations

import sys
import types
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any, TypeVar

from launchkit.description.substitutions.base import Substitution, Text, Value
from launchkit.errors import LaunchFileError, LaunchkitError, Location

#: The files being loaded, innermost last, with the stand-in modules installed for them.
_loading: list[tuple[Path, dict[str, types.ModuleType]]] = []
#: Every Python launch file loaded in this process (actions built later by their functions
#: get locations in them too).
_known_files: set[str] = set()

T = TypeVar("T")


class SubstitutionLike:
    """Base of the stand-in substitution classes: each wraps one launchkit substitution."""

    def __init__(self, inner: Substitution) -> None:
        self.inner = inner

    def perform(self, context: Any) -> str:
        """The text in ``context`` (a user function's context, or launchkit's own)."""
        return self.inner.perform(getattr(context, "real", context))

    def describe(self) -> str:
        """How it was written."""
        return self.inner.describe()

    def __add__(self, other: object) -> list[object]:
        return [self, other]

    def __radd__(self, other: object) -> list[object]:
        return [other, self]


def to_value(item: Any) -> Value:
    """A str, a stand-in substitution, or a (nested) list of them, as one launchkit value."""
    kind = type(item)
    if kind is str:
        return (Text(item),)
    if kind is list or kind is tuple:  # the common cases first: launch files build thousands
        parts: list[Substitution] = []
        for element in item:
            parts.extend(to_value(element))
        return tuple(parts)
    if item is None:
        return ()
    if isinstance(item, SubstitutionLike):
        return (item.inner,)
    if isinstance(item, str):
        return (Text(str(item)),)
    if isinstance(item, Substitution):
        return (item,)
    if isinstance(item, Path):
        return (Text(str(item)),)
    if isinstance(item, int | float | bool):
        return (Text(str(item).lower() if isinstance(item, bool) else str(item)),)
    if isinstance(item, Iterable):
        return to_value(list(item))
    raise LaunchFileError(
        f"cannot use a {type(item).__name__} as text in a launch file",
        here(),
        expected="a str, a substitution or a list of them",
    )


def optional_value(item: Any) -> Value | None:
    """Like :func:`to_value`, keeping None as "not given"."""
    return None if item is None else to_value(item)


def here() -> Location | None:
    """Where in a Python launch file the current call comes from (the innermost frame of a
    known launch file), or None outside of one."""
    frame: types.FrameType | None = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_filename in _known_files:
            return Location(frame.f_code.co_filename, frame.f_lineno)
        frame = frame.f_back
    return Location(str(_loading[-1][0])) if _loading else None


@contextmanager
def loading(path: Path, modules: dict[str, types.ModuleType]) -> Iterator[None]:
    """Run the body as the load of ``path``, with ``modules`` installed."""
    _known_files.add(str(path))
    _loading.append((path, modules))
    try:
        with installed(modules):
            yield
    finally:
        _loading.pop()


def current_modules() -> dict[str, types.ModuleType]:
    """The stand-in modules of the file being loaded (what its functions will import)."""
    return _loading[-1][1] if _loading else {}


@contextmanager
def installed(modules: dict[str, types.ModuleType]) -> Iterator[None]:
    """Install ``modules`` in ``sys.modules`` (hiding any real ``launch``) for the body."""
    saved = {name: sys.modules.get(name) for name in modules}
    sys.modules.update(modules)
    try:
        yield
    finally:
        for name, module in saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module


def call_user(
    function: Callable[..., T],
    what: str,
    modules: dict[str, types.ModuleType],
    *args: Any,
    **kwargs: Any,
) -> T:
    """Call a function of a launch file (an OpaqueFunction, an event handler's callback) with
    the stand-in modules installed; its exception becomes one error naming the function, the
    file and line where it was raised, and its text."""
    try:
        with installed(modules):
            return function(*args, **kwargs)
    except LaunchkitError:
        raise
    except Exception as error:
        name = getattr(function, "__qualname__", None) or repr(function)
        raise LaunchFileError(
            f"{what} {name}() raised {type(error).__name__}: {error}",
            error_location(error, function),
        ) from None


def error_location(error: BaseException, function: object = None) -> Location | None:
    """The deepest line of a known launch file in the error's traceback, else the line where
    ``function`` is defined."""
    found = None
    trace = error.__traceback__
    while trace is not None:
        if trace.tb_frame.f_code.co_filename in _known_files:
            found = Location(trace.tb_frame.f_code.co_filename, trace.tb_lineno)
        trace = trace.tb_next
    code = getattr(function, "__code__", None)
    if found is None and code is not None:
        found = Location(code.co_filename, code.co_firstlineno)
    return found


def unsupported(name: str, why: str = "") -> type:
    """A stand-in for a part of the API launchkit does not implement: using it is an error."""

    def refuse(*_args: object, **_kwargs: object) -> None:
        raise LaunchFileError(
            f"{name} is not supported in Python launch files run by launchkit"
            + (f": {why}" if why else ""),
            here(),
            expected="a class or function listed in docs/launch-files.md",
        )

    return type(name.rpartition(".")[2], (), {"__init__": refuse})


def argv_text(words: list[Value]) -> Value:
    """Argv words as one value, separated by spaces (what ``--print`` and the checks read of
    a command; the process itself is built word by word)."""
    parts: list[Substitution] = []
    for index, word in enumerate(words):
        if index:
            parts.append(Text(" "))
        parts.extend(word)
    return tuple(parts)
