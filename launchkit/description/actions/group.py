"""``<group>`` and ``<reset>``: scoping of launch configurations."""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action
from launchkit.description.launch_context import Scope
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import Location, RuntimeLaunchError

#: what ``launchkit agent --name`` accepts (launchkit.remote.protocol checks the same)
MACHINE_NAME = re.compile(r"^[A-Za-z0-9_.-]{1,64}$")

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext


@dataclass(frozen=True)
class Keep:
    """``<keep name value/>``: a configuration kept through a reset."""

    name: Value
    value: Value


def _kept(keeps: Sequence[Keep], context: LaunchContext) -> dict[str, str]:
    return {perform(k.name, context): perform(k.value, context) for k in keeps}


class Group(Action):
    """Run children in a pushed scope (``scoped``), optionally starting afresh
    (``forwarding="false"``), as ROS's ``GroupAction`` does.

    A scoped group that forwards sets its ``<keep>``s as configurations inside the scope; one
    that does not forward starts from the environment the launch began with and from nothing
    but its ``<keep>``s (evaluated after that environment reset). An unscoped group ignores
    ``forwarding``: its ``<keep>``s are plain ``<let>``s and everything leaks. ``machine`` names
    the host (agent) that runs the processes inside (launchkit's extension:
    ``docs/multi-host.md``; empty: this host).
    """

    TAG = "group"

    def __init__(
        self,
        actions: Sequence[Action],
        scoped: bool = True,
        forwarding: bool = True,
        keeps: Sequence[Keep] = (),
        location: Location | None = None,
        condition: Condition | None = None,
        machine: Value | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.actions = list(actions)
        self.scoped = scoped
        self.forwarding = forwarding
        self.keeps = list(keeps)
        self.machine = machine

    def children(self) -> Sequence[Action]:
        """The grouped actions."""
        return self.actions

    def execute(self, context: LaunchContext) -> None:
        """Run the children, in a new scope when ``scoped``."""
        if not self.scoped:
            self._set_keeps(context)
            self._run(context)
            return
        with context.scoped():
            if self.forwarding:
                self._set_keeps(context)
            else:
                context.environment.clear()
                context.environment.update(context.initial_environment)
                reset(context, self.keeps)
            self._run(context)

    def _set_keeps(self, context: LaunchContext) -> None:
        for keep in self.keeps:
            context.configurations[perform(keep.name, context)] = perform(keep.value, context)

    def _run(self, context: LaunchContext) -> None:
        if self.machine is not None:
            machine = perform(self.machine, context).strip()
            if machine and not MACHINE_NAME.match(machine):
                raise RuntimeLaunchError(
                    f"machine {machine!r} is not a valid agent name",
                    self.location,
                    expected="1-64 letters, digits, '_', '.' or '-' (or empty: this host)",
                )
            context.scope.machine = machine
        for action in self.actions:
            action.visit(context)


def reset(context: LaunchContext, keeps: Sequence[Keep]) -> None:
    """Clear configurations (and ROS globals) except the kept ones, evaluated first."""
    kept = _kept(keeps, context)
    context.scope = Scope(
        configurations=kept,
        environment=context.scope.environment,
        machine=context.scope.machine,
    )


class Reset(Action):
    """``<reset>``: clear every configuration except the ``<keep>``s."""

    TAG = "reset"

    def __init__(
        self,
        keeps: Sequence[Keep] = (),
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.keeps = list(keeps)

    def execute(self, context: LaunchContext) -> None:
        """Reset the current scope."""
        reset(context, self.keeps)
