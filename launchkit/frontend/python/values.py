"""Turning what Python launch files pass around (str, substitutions, lists of both) into
launchkit values, finding the line of the launch file that built an action, and running the
file's own functions later (OpaqueFunction, event handler callbacks, its own substitution
classes) with the stand-in modules installed again and the ``context`` they receive
(:class:`LaunchContextView`)."""

from __future__ import annotations

import sys
import types
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any, TypeVar

from launchkit.description.launch_context import LaunchContext
from launchkit.description.substitutions.base import Substitution, Text, Value
from launchkit.errors import LaunchFileError, LaunchkitError, Location

#: The files being loaded, innermost last, with the stand-in modules installed for them.
_loading: list[tuple[Path, dict[str, types.ModuleType]]] = []
#: Every Python launch file loaded in this process (actions built later by their functions
#: get locations in them too).
_known_files: set[str] = set()

T = TypeVar("T")


class SubstitutionLike:
    """``launch.Substitution``: the base of every stand-in substitution class (each wraps one
    launchkit substitution, its ``inner``) and of a launch file's own substitution classes,
    which define ``perform(self, context)`` and call ``super().__init__()`` (or not: ROS's
    base has no state), as nav2_common's ``RewrittenYaml`` does."""

    _inner: Substitution | None = None

    def __init__(self, inner: Substitution | None = None) -> None:
        self._inner = inner

    @property
    def inner(self) -> Substitution:
        """The launchkit substitution this one performs as (a launch file's own class: one
        that calls its ``perform`` with the context launch files see)."""
        if self._inner is None:
            self._inner = LaunchFileSubstitution(self, here())
        return self._inner

    def perform(self, context: Any) -> str:
        """The text in ``context`` (a user function's context, or launchkit's own)."""
        if self._inner is None or isinstance(self._inner, LaunchFileSubstitution):
            # a launch file's own class that does not define perform (ROS's words)
            raise NotImplementedError("perform() not implemented for Substitution base class.")
        return self._inner.perform(getattr(context, "real", context))

    def describe(self) -> str:
        """How it was written."""
        if self._inner is None or isinstance(self._inner, LaunchFileSubstitution):
            return repr(self)  # ROS's default for a class that does not say
        return self._inner.describe()

    def __add__(self, other: object) -> list[object]:
        return [self, other]

    def __radd__(self, other: object) -> list[object]:
        return [other, self]


class LaunchFileSubstitution(Substitution):
    """A launch file's own ``launch.Substitution`` subclass as a launchkit substitution: its
    ``perform`` called with the context launch files see, the stand-in modules installed."""

    def __init__(self, owner: SubstitutionLike, location: Location | None) -> None:
        self.owner = owner
        self.location = location
        self._modules = current_modules()

    def perform(self, context: LaunchContext) -> str:
        """What the class's ``perform`` returns (``--print`` showing an event handler's
        actions does not call it: ROS would only on the event)."""
        if context.instead_of_calling is not None:
            return f"<{type(self.owner).__name__}>"
        view = LaunchContextView(context)
        result = call_user(self.owner.perform, "substitution", self._modules, view)
        return str(result)

    def describe(self) -> str:
        """What the class's ``describe`` says, else its name."""
        if type(self.owner).describe is SubstitutionLike.describe:
            return f"{type(self.owner).__name__}()"
        text = call_user(self.owner.describe, "substitution", self._modules)
        return str(text) or f"{type(self.owner).__name__}()"


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
        name = function_name(function)
        raise LaunchFileError(
            f"{what} {name}() raised {type(error).__name__}: {error}",
            error_location(error, function),
        ) from None


def function_name(function: Callable[..., Any]) -> str:
    """A function's name as written (``<lambda>``, ``Class.method``, not the functions it is
    defined in)."""
    name = str(getattr(function, "__qualname__", None) or type(function).__name__)
    return name.rpartition("<locals>.")[2]


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


class LaunchContextView:
    """ROS's LaunchContext API for user code: configurations, environment, locals, performing
    substitutions, registering handlers and emitting events."""

    def __init__(self, context: LaunchContext) -> None:
        self.real = context

    @property
    def launch_configurations(self) -> dict[str, str]:
        """The launch configurations of the current scope (a live dict)."""
        return self.real.configurations

    @property
    def environment(self) -> dict[str, str]:
        """The environment processes started now inherit (a live dict)."""
        return self.real.environment

    def get_locals_as_dict(self) -> dict[str, Any]:
        """The locals: ``event`` in a handler, the current launch file's path and folder."""
        values = dict(self.real.locals)
        current = self.real.current_file
        if current is not None:
            values.setdefault("current_launch_file_path", str(current))
            values.setdefault("current_launch_file_directory", str(current.parent))
        return values

    @property
    def locals(self) -> types.SimpleNamespace:
        """The locals as attributes (``context.locals.event``)."""
        return types.SimpleNamespace(**self.get_locals_as_dict())

    def extend_locals(self, new_locals: dict[str, Any]) -> None:
        """Add locals (for the rest of the current handler or function)."""
        self.real.locals.update(new_locals)

    @property
    def is_shutdown(self) -> bool:
        """Whether the launch is shutting down."""
        return self.real.is_shutdown

    def perform_substitution(self, substitution: Any) -> str:
        """The text of a substitution (or of a list of them) now."""
        from launchkit.description.substitutions.base import perform

        return perform(to_value(substitution), self.real)

    def register_event_handler(self, event_handler: Any, append: bool = False) -> None:
        """Register a handler (newest first unless ``append``)."""
        self.real.register_handler(event_handler)
        if append:
            self.real.handlers.remove(event_handler)
            self.real.handlers.append(event_handler)

    def unregister_event_handler(self, event_handler: Any) -> None:
        """Unregister a handler."""
        if event_handler in self.real.handlers:
            self.real.handlers.remove(event_handler)

    def emit_event_sync(self, event: Any) -> None:
        """Emit an event, as ``EmitEvent(event=...)`` would."""
        from launchkit.description.actions.event_actions import EmitEvent

        EmitEvent(event, here()).execute(self.real)

    emit_event = emit_event_sync

    def __getattr__(self, name: str) -> Any:
        raise LaunchFileError(
            f"LaunchContext.{name} is not provided by launchkit",
            here(),
            expected="launch_configurations, environment, locals, perform_substitution, "
            "register_event_handler, emit_event",
        )


def context_view(context: Any) -> LaunchContextView:
    """``context`` as launch files see it (a view passes through unchanged)."""
    return context if isinstance(context, LaunchContextView) else LaunchContextView(context)
