"""The evaluator behind ``$(eval)`` and ``PythonExpression``: a strict whitelist over Python's AST.

Nothing is evaluated by Python's ``eval``. The expression is parsed with :mod:`ast` and walked
here, node by node; a node kind, a name, an attribute or a call that is not listed below is an
error. What an expression can reach (:mod:`launchkit.description.substitutions.sandbox_names`):

* literals (numbers, strings, ``True``/``False``/``None``, lists, tuples, sets, dicts), the
  operators (arithmetic, comparison, ``and``/``or``/``not``, ``x if c else y``), indexing and
  slicing, and f-strings without format specs;
* the modules named by ``$(eval)``'s second argument (ROS's default is ``math``; ``math`` is
  the only module offered), both as ``math.pi`` and, as ROS does for ``math``, as bare names;
* a few pure builtins (:data:`BUILTINS`) and a few ``str`` methods (:data:`STR_METHODS`).

Every intermediate value is bounded (:class:`Limits`): an integer's bits, a string's or a
collection's size, checked *before* an operation that could blow up (``9**9**9``, ``'x' * 10**9``,
``math.factorial(10**6)``), and the whole evaluation has a time limit checked at every node, so
a Ctrl-C or the deadline always gets through between two small steps.
"""

from __future__ import annotations

import ast
import operator
import time
from collections.abc import Callable, Sequence
from typing import Any

from launchkit.description.substitutions.sandbox_names import (
    BUILTINS,
    MODULES,
    STR_METHODS,
    Function,
    LimitError,
    Limits,
    Module,
    SandboxError,
    builtins,
    check_bits,
    check_length,
    check_power,
    int_bits,
    module_names,
    str_method,
    too_big,
    weight,
)

__all__ = [
    "BUILTINS",
    "MODULES",
    "STR_METHODS",
    "LimitError",
    "Limits",
    "SandboxError",
    "evaluate",
]


# -- the evaluator -----------------------------------------------------------------------------

_BINARY: dict[type[ast.operator], Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: operator.mod,
    ast.Pow: operator.pow,
    ast.LShift: operator.lshift,
    ast.RShift: operator.rshift,
    ast.BitAnd: operator.and_,
    ast.BitOr: operator.or_,
    ast.BitXor: operator.xor,
}
_UNARY: dict[type[ast.unaryop], Callable[[Any], Any]] = {
    ast.UAdd: operator.pos,
    ast.USub: operator.neg,
    ast.Not: operator.not_,
    ast.Invert: operator.invert,
}
_COMPARE: dict[type[ast.cmpop], Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b,
    ast.Is: operator.is_,
    ast.IsNot: operator.is_not,
}
_SEQUENCES = (str, list, tuple)


class _Evaluator:
    def __init__(self, modules: Sequence[str], limits: Limits) -> None:
        self.limits = limits
        self.names: dict[str, Any] = dict(builtins(limits))
        for name in modules:
            module = Module(name, module_names(limits))
            if name == "math":
                self.names.update(module.names)  # ROS's backwards-compatible bare math names
            self.names[name] = module
        self.deadline = time.monotonic() + limits.seconds

    def value(self, node: ast.AST) -> Any:
        if time.monotonic() > self.deadline:
            raise LimitError(f"the expression took longer than {self.limits.seconds:g} s")
        handler = getattr(self, f"_{type(node).__name__}", None)
        if handler is None:
            raise SandboxError(f"{_describe(node)} is not available in $(eval)")
        result = handler(node)
        self._check_size(result)
        return result

    def _check_size(self, value: Any) -> None:
        if isinstance(value, int):
            check_bits(int_bits(value), self.limits)
        elif isinstance(value, (str, list, tuple, set, dict, range)):
            check_length(weight(value, self.limits.length), self.limits)

    # one method per node kind (ast's class names)

    def _Expression(self, node: ast.Expression) -> Any:
        return self.value(node.body)

    def _Constant(self, node: ast.Constant) -> Any:
        if not isinstance(node.value, (int, float, complex, str, type(None))):
            raise SandboxError(f"{type(node.value).__name__} literals are not available")
        return node.value

    def _Name(self, node: ast.Name) -> Any:
        if node.id not in self.names:
            raise SandboxError(f"name '{node.id}' is not defined in $(eval)")
        return self.names[node.id]

    def _Attribute(self, node: ast.Attribute) -> Any:
        owner = self.value(node.value)
        if isinstance(owner, Module):
            if node.attr not in owner.names:
                raise SandboxError(f"'{owner.name}' has no public name '{node.attr}'")
            return owner.names[node.attr]
        if isinstance(owner, str) and node.attr in STR_METHODS:
            return str_method(owner, node.attr, self.limits)
        raise SandboxError(f"attribute '{node.attr}' is not available in $(eval)")

    def _BinOp(self, node: ast.BinOp) -> Any:
        left, right = self.value(node.left), self.value(node.right)
        kind = type(node.op)
        if kind is ast.Mod and isinstance(left, str):
            raise SandboxError("'%' string formatting is not available in $(eval); use +")
        self._check_binary(kind, left, right)
        return _BINARY[kind](left, right)

    def _check_binary(self, kind: type[ast.operator], left: Any, right: Any) -> None:
        limits = self.limits
        if kind is ast.Pow:
            check_power(left, right, limits)
        elif kind is ast.Mult:
            if isinstance(left, int) and isinstance(right, int):
                check_bits(int_bits(left) + int_bits(right), limits)
            for sequence, count in ((left, right), (right, left)):
                if isinstance(sequence, _SEQUENCES) and isinstance(count, int):
                    check_length(weight(sequence, limits.length) * count, limits)
        elif kind is ast.LShift and isinstance(left, int) and isinstance(right, int):
            check_bits(int_bits(left) + right, limits)
        elif kind is ast.Add and isinstance(left, _SEQUENCES) and isinstance(right, _SEQUENCES):
            check_length(len(left) + len(right), limits)

    def _UnaryOp(self, node: ast.UnaryOp) -> Any:
        return _UNARY[type(node.op)](self.value(node.operand))

    def _BoolOp(self, node: ast.BoolOp) -> Any:
        result: Any = None
        for operand in node.values:
            result = self.value(operand)
            if bool(result) is isinstance(node.op, ast.Or):
                return result
        return result

    def _Compare(self, node: ast.Compare) -> Any:
        left = self.value(node.left)
        for op, comparator in zip(node.ops, node.comparators, strict=True):
            right = self.value(comparator)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def _IfExp(self, node: ast.IfExp) -> Any:
        return self.value(node.body if self.value(node.test) else node.orelse)

    def _Call(self, node: ast.Call) -> Any:
        function = self.value(node.func)
        if not isinstance(function, Function):
            raise SandboxError(f"{_describe(node.func)} cannot be called in $(eval)")
        args = [self._argument(a) for a in node.args]
        kwargs: dict[str, Any] = {}
        for keyword in node.keywords:
            if keyword.arg is None:
                raise SandboxError("'**' arguments are not available in $(eval)")
            kwargs[keyword.arg] = self.value(keyword.value)
        return function(*args, **kwargs)

    def _argument(self, node: ast.expr) -> Any:
        if isinstance(node, ast.Starred):
            raise SandboxError("'*' arguments are not available in $(eval)")
        return self.value(node)

    def _Subscript(self, node: ast.Subscript) -> Any:
        return self.value(node.value)[self.value(node.slice)]

    def _Slice(self, node: ast.Slice) -> slice:
        parts = (node.lower, node.upper, node.step)
        return slice(*(None if part is None else self.value(part) for part in parts))

    def _List(self, node: ast.List) -> list[Any]:
        return [self._argument(e) for e in node.elts]

    def _Tuple(self, node: ast.Tuple) -> tuple[Any, ...]:
        return tuple(self._argument(e) for e in node.elts)

    def _Set(self, node: ast.Set) -> set[Any]:
        return {self._argument(e) for e in node.elts}

    def _Dict(self, node: ast.Dict) -> dict[Any, Any]:
        if any(key is None for key in node.keys):
            raise SandboxError("'**' in a dict is not available in $(eval)")
        return {self.value(k): self.value(v) for k, v in zip(node.keys, node.values, strict=True)}  # type: ignore[arg-type]

    def _JoinedStr(self, node: ast.JoinedStr) -> str:
        return "".join(str(self.value(part)) for part in node.values)

    def _FormattedValue(self, node: ast.FormattedValue) -> str:
        if node.format_spec is not None:
            raise SandboxError("format specs in f-strings are not available in $(eval)")
        value = self.value(node.value)
        return repr(value) if node.conversion == ord("r") else str(value)


def _describe(node: ast.AST) -> str:
    try:
        return f"'{ast.unparse(node)}'"
    except Exception:  # an odd node that cannot be printed: its kind is enough
        return type(node).__name__


def evaluate(
    expression: str, modules: Sequence[str] = ("math",), limits: Limits | None = None
) -> Any:
    """The value of ``expression`` with ``modules`` (names in :data:`MODULES`) visible;
    :class:`SandboxError` for anything the sandbox refuses or that fails."""
    limits = limits or Limits()
    unknown = [m for m in modules if m not in MODULES]
    if unknown:
        raise SandboxError(
            f"module '{unknown[0]}' is not available in $(eval) "
            f"(launchkit offers {', '.join(sorted(MODULES))} only)"
        )
    if len(expression) > limits.expression:
        raise too_big(f"an expression of {len(expression)} characters")
    try:
        tree = ast.parse(expression.strip(), mode="eval")
    except SyntaxError as error:
        raise SandboxError(f"invalid expression: {error.msg}") from None
    except (RecursionError, MemoryError, ValueError):
        raise SandboxError("the expression is nested too deeply to parse") from None
    evaluator = _Evaluator(modules, limits)
    try:
        return evaluator.value(tree)
    except SandboxError:
        raise
    except MemoryError:
        raise LimitError(
            f"the expression needs more than {limits.memory // 2**20} MiB of memory"
        ) from None
    except RecursionError:
        raise SandboxError("the expression is nested too deeply") from None
    except Exception as error:  # the expression itself failed (1/0, int('x'), ...)
        raise SandboxError(f"{type(error).__name__}: {error}") from None
