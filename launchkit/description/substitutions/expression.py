"""``$(eval EXPR [MODULES])``: a Python expression, evaluated by launchkit's sandbox.

As in ROS, MODULES is a comma-separated list of modules the expression may use (default
``math``, whose names are also visible bare); launchkit offers ``math`` only. The expression is
never given to Python's ``eval``: :mod:`launchkit.description.substitutions.sandbox` walks it
over a whitelist, with bounded sizes and a time limit.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call
from launchkit.description.substitutions.sandbox import SandboxError, evaluate

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
        # the sandbox's tables are built on import: only a launch that evaluates pays for them
        try:
            return str(evaluate(expression, modules))
        except SandboxError as error:
            raise self.fail(
                f"$(eval {_quoted(expression)}): {error}",
                expected="math, plain values and a few builtins (see docs/launch-files.md)",
            ) from None


def _quoted(expression: str) -> str:
    text = expression if len(expression) <= 80 else expression[:77] + "..."
    return repr(text)
