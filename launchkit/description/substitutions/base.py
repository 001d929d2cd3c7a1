"""The substitution protocol: a tiny object that turns into a string in a launch context."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from launchkit.errors import LaunchFileError, LaunchkitError, Location, RuntimeLaunchError

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class Substitution:
    """Base of every substitution: ``perform(context) -> str`` and ``describe() -> str``."""

    __slots__ = ()  # subclasses without slots of their own have a dict as usual

    location: Location | None = None

    def perform(self, context: LaunchContext) -> str:
        """The text this substitution stands for in ``context``."""
        raise NotImplementedError

    def describe(self) -> str:
        """How the substitution was written (for messages and ``--print``)."""
        raise NotImplementedError

    def fail(
        self, message: str, *, expected: str | None = None, quoted: list[str] | None = None
    ) -> LaunchkitError:
        """A runtime error located at this substitution (``quoted``: lines shown under it)."""
        return RuntimeLaunchError(message, self.location, expected=expected, quoted=quoted)


#: A value written in a launch file: literal text and substitutions, concatenated.
Value = tuple[Substitution, ...]


class Text(Substitution):
    """Literal text."""

    __slots__ = ("location", "text")

    def __init__(self, text: str, location: Location | None = None) -> None:
        self.text = text
        self.location = location

    def perform(self, context: LaunchContext) -> str:
        """The text itself."""
        return self.text

    def describe(self) -> str:
        """The text, quoted."""
        return repr(self.text)

    def __repr__(self) -> str:
        return f"Text({self.text!r})"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Text) and other.text == self.text

    def __hash__(self) -> int:
        return hash(self.text)


class Call(Substitution):
    """A ``$(name arg ...)`` substitution; subclasses set ``NAME`` and the argument counts."""

    NAME: ClassVar[str] = ""
    MIN_ARGS: ClassVar[int] = 0
    MAX_ARGS: ClassVar[int | None] = None
    USAGE: ClassVar[str] = ""

    def __init__(self, args: Sequence[Value], location: Location | None = None) -> None:
        self.location = location
        if len(args) < self.MIN_ARGS or (self.MAX_ARGS is not None and len(args) > self.MAX_ARGS):
            raise LaunchFileError(
                f"$({self.NAME}) takes {self._arity()}, got {len(args)}",
                location,
                expected=f"$({self.NAME} {self.USAGE})".replace(" )", ")"),
            )
        self.args: tuple[Value, ...] = tuple(args)

    @classmethod
    def _arity(cls) -> str:
        if cls.MAX_ARGS == cls.MIN_ARGS:
            return f"{cls.MIN_ARGS} argument{'s' if cls.MIN_ARGS != 1 else ''}"
        if cls.MAX_ARGS is None:
            return f"at least {cls.MIN_ARGS} arguments"
        return f"{cls.MIN_ARGS} to {cls.MAX_ARGS} arguments"

    def arg(self, index: int, context: LaunchContext, default: str | None = None) -> str:
        """Argument ``index`` performed; ``default`` when it was not given."""
        if index >= len(self.args):
            if default is None:
                raise self.fail(f"$({self.NAME}) is missing argument {index + 1}")
            return default
        return perform(self.args[index], context)

    def describe(self) -> str:
        """``$(name arg ...)`` as written (approximately)."""
        parts = [self.NAME, *(describe(a) for a in self.args)]
        return "$(" + " ".join(parts) + ")"

    def __repr__(self) -> str:
        return f"{type(self).__name__}{self.args!r}"

    def __eq__(self, other: object) -> bool:
        return type(other) is type(self) and other.args == self.args

    def __hash__(self) -> int:
        return hash((type(self), self.args))


def perform(value: Value, context: LaunchContext) -> str:
    """Perform every part of ``value`` and concatenate the results."""
    return "".join([part.perform(context) for part in value])


def describe(value: Value) -> str:
    """A readable rendering of ``value`` as it was written."""
    out = []
    for part in value:
        out.append(part.text if isinstance(part, Text) else part.describe())
    return "".join(out)


def literal(value: Value) -> str | None:
    """The text of ``value`` when it contains no substitution, else None."""
    if all(isinstance(p, Text) for p in value):
        return "".join(p.text for p in value)  # type: ignore[attr-defined]
    return None
