"""What ``$(eval)``'s sandbox offers and how it bounds values (the evaluator is
:mod:`launchkit.description.substitutions.sandbox`).

Callables are wrapped in :class:`Function`, whose guard checks the arguments before the call,
so that nothing can start an operation whose result would be too large: the guards estimate
the result's size from the arguments (an integer's bits, a string's or a collection's length).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

#: The modules an expression may ask for (``$(eval EXPR MODULES)``), by name.
MODULES: dict[str, Any] = {"math": math}


class SandboxError(Exception):
    """The expression cannot be evaluated: its message says why, for the user."""


class LimitError(SandboxError):
    """The expression went past one of the :class:`Limits`."""


@dataclass(frozen=True)
class Limits:
    """Bounds on one evaluation."""

    seconds: float = 1.0
    int_bits: int = 10_000  # about 3000 decimal digits
    length: int = 100_000  # characters of a string, items of a collection
    expression: int = 100_000  # characters of the expression text
    memory: int = 256 * 2**20  # bytes the evaluating process may grow by

    def describe(self) -> str:
        """The limits in words, for an error message."""
        return (
            f"{self.seconds:g} s of CPU time, {self.length:,} characters or items, "
            f"{self.int_bits:,}-bit integers, {self.memory // 2**20} MiB of memory"
        )


@dataclass(frozen=True)
class Function:
    """A callable the sandbox offers; ``guard`` checks the arguments before the call."""

    name: str
    impl: Callable[..., Any]
    guard: Callable[..., None] | None = None

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        if self.guard is not None:
            self.guard(*args, **kwargs)
        return self.impl(*args, **kwargs)


@dataclass(frozen=True)
class Module:
    """A module as expressions see it: only its public functions and constants."""

    name: str
    names: Mapping[str, Any]


def int_bits(value: Any) -> int:
    """The bits of an integer's magnitude (0 for anything else)."""
    return abs(value).bit_length() if isinstance(value, int) else 0


def too_big(what: str) -> LimitError:
    """The error for a result that would exceed a limit."""
    return LimitError(f"{what} would be too large for $(eval)")


def check_bits(bits: int, limits: Limits) -> None:
    """Refuse an integer of ``bits`` bits."""
    if bits > limits.int_bits:
        raise too_big(f"an integer of about {bits} bits (at most {limits.int_bits})")


def check_length(length: int, limits: Limits, what: str = "a value") -> None:
    """Refuse a string or collection of ``length`` characters or items."""
    if length > limits.length:
        raise too_big(f"{what} of {length} items (at most {limits.length})")


def module_names(limits: Limits) -> dict[str, Any]:
    """``math``'s public names, its integer-producing functions guarded."""

    def factorial(n: Any, *_: Any) -> None:
        if isinstance(n, int) and n > 1000:
            raise too_big(f"factorial({n})")

    def comb(n: Any, k: Any = 0, *_: Any) -> None:
        if isinstance(n, int):
            check_bits(n, limits)

    def perm(n: Any, k: Any = None, *_: Any) -> None:
        if isinstance(n, int):
            check_bits((n if k is None else int(k)) * max(1, int_bits(n)), limits)

    def product(values: Any = (), *_: Any, **__: Any) -> None:
        check_bits(sum(int_bits(v) for v in values), limits)

    def lcm(*values: Any) -> None:
        check_bits(sum(int_bits(v) for v in values), limits)

    guards: dict[str, Callable[..., None]] = {
        "factorial": factorial,
        "comb": comb,
        "perm": perm,
        "prod": product,
        "lcm": lcm,
    }
    names: dict[str, Any] = {}
    for name in dir(math):
        if name.startswith("_"):
            continue
        value = getattr(math, name)
        names[name] = Function(name, value, guards.get(name)) if callable(value) else value
    return names


def builtins(limits: Limits) -> dict[str, Function]:
    """The builtins an expression may call, each guarded where it could blow up."""

    def power(base: Any, exponent: Any, *modulus: Any) -> None:
        if modulus:
            raise SandboxError("pow() with a modulus is not available in $(eval)")
        check_power(base, exponent, limits)

    def numbers_only(values: Any, start: Any = 0) -> None:
        if not all(isinstance(v, (int, float, complex)) for v in (*values, start)):
            raise SandboxError("sum() adds numbers only in $(eval)")

    def bounded_range(*args: Any) -> None:
        check_length(len(range(*args)), limits, "a range")

    table: dict[str, tuple[Callable[..., Any], Callable[..., None] | None]] = {
        "abs": (abs, None),
        "all": (all, None),
        "any": (any, None),
        "bool": (bool, None),
        "chr": (chr, None),
        "dict": (dict, None),
        "divmod": (divmod, None),
        "float": (float, None),
        "int": (int, None),
        "len": (len, None),
        "list": (list, None),
        "max": (max, None),
        "min": (min, None),
        "ord": (ord, None),
        "pow": (pow, power),
        "range": (range, bounded_range),
        "round": (round, None),
        "set": (set, None),
        "sorted": (sorted, None),
        "str": (str, None),
        "sum": (sum, numbers_only),
        "tuple": (tuple, None),
    }
    return {name: Function(name, impl, guard) for name, (impl, guard) in table.items()}


#: The names of the builtins an expression may call.
BUILTINS = tuple(sorted(builtins(Limits())))

#: The ``str`` methods an expression may call (none of them formats or reaches an object).
STR_METHODS = (
    "capitalize",
    "casefold",
    "center",
    "count",
    "endswith",
    "find",
    "isalnum",
    "isalpha",
    "isdecimal",
    "isdigit",
    "islower",
    "isnumeric",
    "isspace",
    "isupper",
    "join",
    "ljust",
    "lower",
    "lstrip",
    "partition",
    "removeprefix",
    "removesuffix",
    "replace",
    "rfind",
    "rjust",
    "rpartition",
    "rsplit",
    "rstrip",
    "split",
    "splitlines",
    "startswith",
    "strip",
    "swapcase",
    "title",
    "upper",
    "zfill",
)


def str_method(text: str, name: str, limits: Limits) -> Function:
    """``text.name`` as a callable, guarded where its result could be too long."""
    method = getattr(text, name)

    def guard(*args: Any, **kwargs: Any) -> None:
        if name in ("center", "ljust", "rjust", "zfill") and args and isinstance(args[0], int):
            check_length(args[0], limits, "a string")
        elif name == "replace" and len(args) >= 2:
            old, new = args[0], args[1]
            if isinstance(old, str) and isinstance(new, str):
                count = text.count(old) if old else len(text) + 1
                check_length(len(text) + count * len(new), limits, "a string")
        elif name == "join" and args:
            items = list(args[0])
            total = sum(len(i) for i in items if isinstance(i, str)) + len(text) * len(items)
            check_length(total, limits, "a string")

    return Function(f"str.{name}", method, guard)


def check_power(base: Any, exponent: Any, limits: Limits) -> None:
    """Refuse ``base ** exponent`` when the result would have too many bits."""
    if isinstance(base, int) and isinstance(exponent, int) and exponent > 0 and abs(base) > 1:
        check_bits(exponent * int_bits(base), limits)  # an upper bound of the result's bits


def weight(value: Any, limit: int) -> int:
    """How many characters and items ``value`` holds, nested ones included: a string counts
    its characters, any other item 1 (counting stops just past ``limit``)."""
    if isinstance(value, (str, range)):
        return len(value)
    if not isinstance(value, (list, tuple, set, dict)):
        return 1
    total = 0
    items: Iterable[Any] = value.items() if isinstance(value, dict) else value
    for item in items:
        if total > limit:
            break
        total += max(1, weight(item, limit - total))
    return total
