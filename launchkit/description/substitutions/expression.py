"""``$(eval EXPR [MODULES])``: a Python expression, evaluated by launchkit's sandbox.

As in ROS, MODULES is a comma-separated list of modules the expression may use (default
``math``, whose names are also visible bare); launchkit offers ``math`` only. The expression is
never given to Python's ``eval``: :mod:`launchkit.description.substitutions.sandbox` walks it
over a whitelist, with bounded sizes, in an evaluator process stopped at the time limit
(:mod:`launchkit.description.substitutions.sandbox_process`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call
from launchkit.description.substitutions.sandbox_process import (
    LimitError,
    Limits,
    SandboxError,
    evaluate,
)

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class Eval(Call):
    """``str(EXPR)`` evaluated in the sandbox with MODULES (``math`` by default) visible."""

    NAME = "eval"
    MIN_ARGS = 1
    MAX_ARGS = 2
    USAGE = "EXPRESSION [MODULES]"

    def perform(self, context: LaunchContext) -> str:
        """The expression's value as text, or an error quoting the expression."""
        expression = self.arg(0, context)
        modules = [m.strip() for m in self.arg(1, context, "math").split(",") if m.strip()]
        try:
            return evaluate(expression, modules)
        except SandboxError as error:
            expected = (
                f"an expression within $(eval)'s limits ({Limits().describe()})"
                if isinstance(error, LimitError)
                else "math, plain values and a few builtins (see docs/launch-files.md)"
            )
            raise self.fail(f"$(eval {_quoted(expression)}): {error}", expected=expected) from None


def _quoted(expression: str) -> str:
    text = expression if len(expression) <= 80 else expression[:77] + "..."
    return repr(text)
