"""``$(eval EXPR)``: a Python expression evaluated with ``math`` and nothing that reaches out.

Only ``math`` (bare names and ``math.*``) and a few pure builtins are visible; names with a
double underscore are rejected before evaluation, so no attribute walk reaches ``__import__``,
files or the process.
"""

from __future__ import annotations

import ast
import builtins
import math
from typing import TYPE_CHECKING, Any

from launchkit.description.substitutions.base import Call

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext

_SAFE_BUILTINS: dict[str, Any] = {
    name: getattr(builtins, name)
    for name in (
        "abs",
        "all",
        "any",
        "bool",
        "divmod",
        "float",
        "int",
        "len",
        "list",
        "max",
        "min",
        "pow",
        "range",
        "round",
        "sorted",
        "str",
        "sum",
        "tuple",
        "True",
        "False",
        "None",
    )
}


def _namespace() -> dict[str, Any]:
    names: dict[str, Any] = {k: getattr(math, k) for k in dir(math) if not k.startswith("_")}
    names.update(_SAFE_BUILTINS)
    names["math"] = math
    return {"__builtins__": {}, **names}


class Eval(Call):
    """``str(eval(EXPR))`` in a sandbox holding ``math`` only (MODULES are not supported)."""

    NAME = "eval"
    MIN_ARGS = 1
    MAX_ARGS = 2
    USAGE = "EXPRESSION"

    def perform(self, context: LaunchContext) -> str:
        """The expression's value as text, or an error quoting the expression."""
        expression = self.arg(0, context)
        if len(self.args) > 1 and self.arg(1, context).strip() not in ("", "math"):
            raise self.fail(
                "$(eval) imports no modules in launchkit", expected="expressions using math only"
            )
        try:
            tree = ast.parse(expression.strip(), mode="eval")
        except SyntaxError as error:
            raise self.fail(f"invalid expression {expression!r}: {error.msg}") from None
        for node in ast.walk(tree):
            name = getattr(node, "id", None) or getattr(node, "attr", None)
            if isinstance(name, str) and "__" in name:
                raise self.fail(
                    f"'{name}' is not allowed in $(eval)", expected="math and plain values only"
                )
        try:
            value = eval(compile(tree, "<eval>", "eval"), _namespace())
        except Exception as error:  # the user's expression failed: report it, not a traceback
            raise self.fail(
                f"evaluating {expression!r} failed: {type(error).__name__}: {error}"
            ) from None
        return str(value)
