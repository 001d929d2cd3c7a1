"""``$(var NAME [DEFAULT])`` and ``$(anon NAME)``: launch configurations."""

from __future__ import annotations

import os
import random
import re
import socket
from typing import TYPE_CHECKING

from launchkit.description.substitutions.base import Call

if TYPE_CHECKING:
    from launchkit.description.launch_context import LaunchContext


class Var(Call):
    """The value of launch configuration NAME (an ``<arg>``, ``<let>`` or ``name:=value``)."""

    NAME = "var"
    MIN_ARGS = 1
    MAX_ARGS = 2
    USAGE = "NAME [DEFAULT]"

    def perform(self, context: LaunchContext) -> str:
        """The configuration's value, or DEFAULT, or an error naming the missing name."""
        name = self.arg(0, context)
        value = context.configurations.get(name)
        if value is not None:
            return value
        if len(self.args) > 1:
            return self.arg(1, context)
        raise self.fail(
            f"launch configuration '{name}' is not defined",
            expected="an <arg>, a <let> or a name:=value for it, or $(var NAME DEFAULT)",
        )


class Anon(Call):
    """``NAME_<host>_<pid>_<random>``, the same for one NAME during the whole run."""

    NAME = "anon"
    MIN_ARGS = 1
    MAX_ARGS = 1
    USAGE = "NAME"

    def perform(self, context: LaunchContext) -> str:
        """The anonymous name for NAME, made on first use."""
        name = self.arg(0, context)
        known = context.anon_names.get(name)
        if known is None:
            raw = f"{name}_{socket.gethostname()}_{os.getpid()}_{random.getrandbits(63)}"
            known = re.sub(r"[.\-:]", "_", raw)
            context.anon_names[name] = known
        return known
