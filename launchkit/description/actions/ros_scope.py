"""ROS scope tags: ``push_ros_namespace``, ``set_parameter``, ``set_parameters_from_file``,
``set_remap``, ``set_use_sim_time``. Their effect is limited by ``<group>`` like configurations."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launchkit.description.actions.base import Action, NameValueAction, typed_bool
from launchkit.description.substitutions.base import Value, perform
from launchkit.errors import Location

if TYPE_CHECKING:
    from launchkit.description.conditions import Condition
    from launchkit.description.launch_context import LaunchContext

NAMESPACE_CONFIGURATION = "ros_namespace"


def join_namespace(base: str, namespace: str) -> str:
    """ROS namespace composition: an absolute ``namespace`` wins, a relative one is appended."""
    if namespace.startswith("/"):
        joined = namespace
    else:
        joined = base.rstrip("/") + "/" + namespace
    joined = "/" + joined.strip("/")
    return joined


def ros_namespace(base: str | None, own: str | None) -> str | None:
    """launch_ros's ``make_namespace_absolute(prefix_namespace(base, own))``: None when
    neither is given."""
    if base is None and own is None:
        return None
    if own is None:
        combined = base or ""
    elif not base or own.startswith("/"):
        combined = own
    else:
        combined = ("" if base == "/" else base) + "/" + own
    if combined != "/":
        combined = combined.rstrip("/")
    return combined if combined.startswith("/") else "/" + combined


class PushRosNamespace(Action):
    """Prefix the namespace of later nodes in scope."""

    TAG = "push_ros_namespace"

    def __init__(
        self,
        namespace: Value,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.namespace = namespace

    def execute(self, context: LaunchContext) -> None:
        """Push it: relative to the pushed one, absolute as given (launch_ros's rules)."""
        namespace = perform(self.namespace, context).strip()
        base = context.configurations.get(NAMESPACE_CONFIGURATION)
        pushed = ros_namespace(base, namespace)
        if pushed is not None:
            context.configurations[NAMESPACE_CONFIGURATION] = pushed


class SetParameter(NameValueAction):
    """A parameter given to every later node in scope (and read by ``$(param)``)."""

    TAG = "set_parameter"

    def apply(self, context: LaunchContext, name: str, value: str) -> None:
        """Record it in the scope."""
        context.scope.global_params.append((name, value))


class SetParametersFromFile(Action):
    """A parameters file given to every later node in scope."""

    TAG = "set_parameters_from_file"

    def __init__(
        self,
        filename: Value,
        location: Location | None = None,
        condition: Condition | None = None,
    ) -> None:
        super().__init__(location, condition)
        self.filename = filename

    def execute(self, context: LaunchContext) -> None:
        """Record it in the scope."""
        context.scope.global_params.append(perform(self.filename, context))


class SetRemap(NameValueAction):
    """A remapping given to every later node in scope: ``name`` is what it maps from,
    ``value`` what it maps to."""

    TAG = "set_remap"

    def apply(self, context: LaunchContext, name: str, value: str) -> None:
        """Record it in the scope."""
        context.scope.remaps.append((name, value))


class SetUseSimTime(Action):
    """``<set_use_sim_time value>``: ``use_sim_time`` for every later node in scope, as a
    global parameter. (Jazzy cannot run the tag; its Python ``SetUseSimTime`` sets only the
    launch's own ROS clock, which the Python frontend's ``nodes=False`` follows.)"""

    TAG = "set_use_sim_time"

    def __init__(
        self,
        value: Value,
        location: Location | None = None,
        condition: Condition | None = None,
        *,
        nodes: bool = True,
    ) -> None:
        super().__init__(location, condition)
        self.value = value
        self.nodes = nodes

    def execute(self, context: LaunchContext) -> None:
        """Check the value; record ``use_sim_time`` as a global parameter for the nodes."""
        value = typed_bool(self.value, context, "set_use_sim_time value", self.location)
        if self.nodes:
            context.scope.global_params.append(("use_sim_time", "true" if value else "false"))
